#pragma once
// One design through the stages: build, validate, emit, report.

#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "geometry/mesh/validate.h"
#include "io/design/design.h"

namespace fabmesh {

struct JobOptions {
  std::string out_dir = "out";  ///< created when missing
};

/// What one job did (product.md "JSON reports").
struct JobReport {
  std::string name;
  std::string kind;
  std::vector<std::string> outputs;  ///< paths written
  ValidationReport validation;
  double max_deviation = 0.0;  ///< proven bound of the mesh against the exact surface
  double tolerance = 0.0;
  std::string embedding_proof;  ///< when self-intersection is excluded by construction
  nlohmann::json build;         ///< builder facts, e.g. {"angular_segments": 128, "section_points": 90}
  std::vector<std::pair<std::string, double>> timings_ms;
};

/// Runs one design. Nothing is written unless the mesh is valid; every file
/// is written atomically. \throw InputError (bad design), ValidationFailed
/// (the mesh, or its decoded Draco form, is invalid)
JobReport run_job(const Design& design, const JobOptions& options);

/// The report as product.md's JSON object.
nlohmann::json to_json(const JobReport& report);

}  // namespace fabmesh
