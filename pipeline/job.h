#pragma once
// One design through the stages: build and validate (no I/O), encode every
// output in memory, then write them all or none.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "geometry/core/stage_timer.h"
#include "geometry/mesh/validate.h"
#include "io/design/design.h"
#include "io/file.h"
#include "pipeline/built_mesh.h"

namespace fabmesh {

struct JobOptions {
  std::string out_dir = "out";  ///< created when missing
};

/// What one job did.
struct JobReport {
  std::string name;
  std::string kind;
  std::string units;
  std::vector<std::string> outputs;  ///< paths written (or to be written, for a prepared job)
  ValidationReport validation;
  MeshPurpose purpose = MeshPurpose::Fabrication;
  double max_deviation = 0.0;  ///< proven bound of the mesh against the exact shape, model units
  double tolerance = 0.0;
  nlohmann::json build;  ///< builder facts, e.g. {"angular_segments": 128, "section_points": 90}
  StageTimings timings_ms;
};

/// A job built, validated and encoded, with nothing written yet.
struct PreparedJob {
  JobReport report;
  std::vector<FileWrite> files;  ///< every output's path and bytes
};

/// Builds, validates and encodes `design` into its outputs' bytes. Does no
/// I/O. A mesh that is not valid for fabrication (or, for a viewing mesh,
/// has defects beyond its open border) stops the job here.
/// \throw InputError (bad design), ValidationFailed (the mesh, or its decoded Draco form, is invalid)
PreparedJob prepare_job(const Design& design, const JobOptions& options);

/// Writes a prepared job's files into their folder (created when missing),
/// all or nothing (write_files_atomically); fills report.outputs.
/// \throw FileError
JobReport write_job(PreparedJob job, const JobOptions& options);

/// prepare_job then write_job.
JobReport run_job(const Design& design, const JobOptions& options);

}  // namespace fabmesh
