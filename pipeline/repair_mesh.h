#pragma once
// `fabmesh repair` as a function: a mesh file read, each of its objects
// repaired (geometry/repair/repair.h), the result encoded, read back and
// validated as `check` would, then written all or nothing; or refused with
// what could not be mended (docs/repair.md).

#include <string>
#include <vector>

#include "geometry/core/soup.h"
#include "geometry/core/stage_timer.h"
#include "geometry/repair/repair.h"
#include "pipeline/failure.h"

namespace fabmesh {

/// How a file is repaired and where the result goes.
struct RepairFileOptions {
  RepairOptions repair;  ///< the engine's options (max_deviation, wrap, weld distance)
  /// Where to write: a file (its ending names the format: .3mf, .stl, .obj,
  /// .ply, .off), a folder (FOLDER/STEM.3mf), or empty: beside the input as
  /// STEM.repaired.3mf.
  std::string output;
  bool output_is_folder = false;  ///< `output` names a folder even without a trailing '/'
  bool write = true;              ///< false: repair and verify, write nothing (a dry run)
};

/// One object of a file, repaired.
struct RepairedObject {
  std::string name;  ///< the file's name for it; empty for a file of one object
  RepairResult result;
};

/// The outcome for one file.
struct FileRepair {
  std::string file;
  bool readable = false;
  std::string format;  ///< of the input ("STL", "3MF", ...)
  std::string units;   ///< as the input states it; empty when it states none
  std::vector<std::string> notes;
  std::vector<RepairedObject> objects;
  std::string output;         ///< where the result goes (written only when `written`)
  std::string output_format;  ///< "3MF", "STL", ...
  std::string output_units;   ///< the unit the output states (3MF) or assumes
  std::size_t solids = 0;     ///< closed solids written (3MF: one object each)
  /// The output as written, read back and validated object by object (as `check` reads it).
  bool valid_as_written = false;
  /// How far writing moved a vertex at most (float32 and decimals; 0 for exact formats).
  double writing_error = 0.0;
  /// The proven bound of the distance between the input and the file written:
  /// the largest object's measured distance plus writing_error.
  double distance = 0.0;
  bool written = false;
  Failure failure;  ///< exit code and message when not Ok
  StageTimings timings_ms;

  /// 0 written (or verified, in a dry run), 1 not mended (or too far), 2 bad input, 5 not writable.
  int exit_code() const { return failure.exit_code; }
};

/// Repairs the mesh file at `path` and writes the result (options.write).
/// Never throws for an input it cannot read or repair: the FileRepair says why.
FileRepair repair_file(const std::string& path, const RepairFileOptions& options);

/// Repairs a soup held in memory (no file, format or unit): the engine's
/// result for it, as repair_file's single object.
RepairResult repair_soup(const TriangleSoup& soup, const RepairOptions& options);

/// The output path of repairing `input` as `options` say.
std::string repair_output_path(const std::string& input, const RepairFileOptions& options);

}  // namespace fabmesh
