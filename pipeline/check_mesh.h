#pragma once
// `fabmesh check` as a function: a mesh file (or a mesh in memory) read,
// welded and validated object by object, then its objects tested for
// interpenetration; and its JSON item (docs/reports.md).

#include <algorithm>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "geometry/core/soup.h"
#include "geometry/core/stage_timer.h"
#include "geometry/mesh/interpenetration.h"
#include "geometry/validation/validate.h"
#include "pipeline/failure.h"
#include "pipeline/report.h"

namespace fabmesh {

/// How a mesh is checked (`check --weld-tolerance`, `--max-seconds`).
struct CheckOptions {
  double weld_tolerance = 0.0;  ///< merge vertices closer than this first; 0: exactly equal ones
  double max_seconds = 600.0;   ///< time budget of each object's self-intersection test (0: none)
  /// Occurrences of each defect kind listed with their faces and vertices
  /// (`check --max-locations`, `defect_locations` in JSON); the count is always the total.
  std::size_t max_locations = 100;
  /// Keep every occurrence's location and each object's welded mesh, for
  /// `check --mark` (marked_mesh); the JSON still lists max_locations.
  bool keep_for_marking = false;
};

/// A weld tolerance that closes an open object (`check`'s hint, `weld_hint`
/// in JSON): chosen from the data (weld_candidate), then tried.
struct WeldHint {
  double tolerance = 0.0;           ///< the value to give --weld-tolerance
  double closing_distance = 0.0;    ///< the smallest tolerance giving every boundary vertex a partner
  double mean_edge = 0.0;           ///< the mesh's mean edge length, for scale
  std::size_t merged_vertices = 0;  ///< vertices welding with `tolerance` merges (beyond the exact weld)
  bool valid_after = false;         ///< welded so, the object is valid (not only closed)
};

/// One object of a file, welded and validated.
struct ObjectCheck {
  std::string name;  ///< empty for a file of one object
  ValidationReport report;
  std::size_t welded_vertices = 0;
  /// Kept for the assembly test when the file has several objects, and
  /// with CheckOptions::keep_for_marking.
  TriangleSoup welded;
  /// `defect_locations` of `check --json`: per defect kind its count and
  /// the first CheckOptions::max_locations occurrences, faces and vertices
  /// numbered as the object was read (a welded vertex by the lowest index
  /// merged into it), with the vertices' coordinates.
  nlohmann::ordered_json defect_locations;
  /// Set when the object has boundary edges and welding within a small
  /// tolerance (far below its mean edge) closes every one of them.
  std::optional<WeldHint> weld_hint;
};

/// The outcome for one file: a report per object, or why it could not be read.
struct FileCheck {
  std::string file;
  bool readable = false;
  std::string format;
  std::string units;  ///< as the file states it; empty for formats that carry none
  std::vector<std::string> notes;
  std::vector<ObjectCheck> objects;  ///< one for a single-object file
  /// Several objects: the pairs of them that interpenetrate (indices into objects).
  Interpenetration assembly;
  StageTimings timings_ms;  ///< several objects: read and assembly
  Failure failure;          ///< why it could not be read, when not readable
  ItemFacts facts;          ///< its verdict: check_facts, or failed_facts when not readable

  bool several() const { return objects.size() > 1; }
  bool valid() const { return facts.status == ItemStatus::Ok; }
};

/// `check`'s exit code when no defect was found but a check did not finish
/// (a self-intersection test out of its time budget): neither valid (0) nor
/// invalid (1), so that a CI gate can tell "unknown" from "bad". The other
/// codes are pipeline/failure.h's; 4 is `batch --merge`'s.
constexpr int kExitUndetermined = 6;

/// What `check` concludes about a file.
enum class CheckVerdict {
  Valid,         ///< every object valid (exit 0)
  Invalid,       ///< a defect found (exit 1)
  Unreadable,    ///< not read (exit 2, or 5 for a fault of the machine)
  Undetermined,  ///< no defect found, but a check unfinished (exit 6: kExitUndetermined)
};

/// "valid", "invalid", "unreadable" or "undetermined".
const char* to_string(CheckVerdict verdict);

/// The verdict on `check`: Undetermined when no object has a defect but
/// some object's self-intersection test stopped at its time budget (or the
/// nesting of its components was not settled), so that a CI gate can tell
/// "unknown" from "bad".
CheckVerdict verdict_of(const FileCheck& check);

/// The exit code of `check`'s verdict on one file.
int exit_code_of(const FileCheck& check);

/// Of the exit codes of several files, the one `check` exits with: bad
/// input (2) or a fault of the machine (5, 3) first, then invalid (1), then
/// undetermined (6), then 0.
int worst_check_code(int a, int b);

/// Reads `path` ("-": standard input, any format told by content) and
/// checks each of its objects, then their assembly. A file that cannot be
/// read is a FileCheck that is not `readable`, with why.
FileCheck check_file(const std::string& path, const CheckOptions& options);

/// Checks a mesh held in memory as a file of one object (no file, format or unit).
/// \throw InputError (key "vertices") for a non-finite coordinate, as a
///        file's reader refuses one; as validate for an index out of range.
FileCheck check_soup(const TriangleSoup& soup, const CheckOptions& options);

/// The `check --json` item of `check` (file, format, units, notes, then the
/// validation facts, or per object and the assembly).
nlohmann::ordered_json check_json(const FileCheck& check);

}  // namespace fabmesh
