#pragma once
// `fabmesh check` as a function: a mesh file (or a mesh in memory) read,
// welded and validated object by object, then its objects tested for
// interpenetration; and its JSON item (docs/reports.md).

#include <algorithm>
#include <nlohmann/json.hpp>
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
};

/// One object of a file, welded and validated.
struct ObjectCheck {
  std::string name;  ///< empty for a file of one object
  ValidationReport report;
  std::size_t welded_vertices = 0;
  TriangleSoup welded;  ///< kept for the assembly test when the file has several objects
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

/// Reads `path` and checks each of its objects, then their assembly. A file
/// that cannot be read is a FileCheck that is not `readable`, with why.
FileCheck check_file(const std::string& path, const CheckOptions& options);

/// Checks a mesh held in memory as a file of one object (no file, format or unit).
FileCheck check_soup(const TriangleSoup& soup, const CheckOptions& options);

/// The `check --json` item of `check` (file, format, units, notes, then the
/// validation facts, or per object and the assembly).
nlohmann::ordered_json check_json(const FileCheck& check);

}  // namespace fabmesh
