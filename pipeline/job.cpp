#include "pipeline/job.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "geometry/core/errors.h"
#include "pipeline/build_design.h"
#include "pipeline/outputs.h"

namespace fabmesh {
namespace {

// Share of the tolerance kept for output quantization (Draco, float32 files).
constexpr double kOutputShare = 0.1;

}  // namespace

PreparedJob prepare_job(const Design& design, const JobOptions& options) {
  PreparedJob job;
  JobReport& report = job.report;
  report.name = design.common.name;
  report.kind = kind_name(design);
  report.units = design.common.units;
  report.tolerance = design.common.tolerance;
  StageTimer watch(report.timings_ms);
  const std::vector<const OutputFormat*> formats = resolve_outputs(design);
  const bool wants_cutting = std::any_of(formats.begin(), formats.end(), [](const OutputFormat* f) {
    return f->content == OutputContent::CuttingOutline;
  });
  const BuildContext context{design.common, (1.0 - kOutputShare) * design.common.tolerance, wants_cutting,
                             watch};
  const BuiltMesh built = build_design(design, context);
  report.max_deviation = built.max_deviation;
  report.build = built.facts;
  report.validation = built.validation;
  report.purpose = built.purpose;
  if (!fit_for(report.validation, built.purpose)) {
    require_valid(report.validation, fmt::format("{} '{}'", report.kind, report.name));
  }
  // The encoders get the tolerance the build left unused.
  const double output_tolerance = design.common.tolerance - built.max_deviation;
  for (const OutputFormat* format : formats) {
    const std::string path =
        (std::filesystem::path(options.out_dir) / (design.common.name + "." + std::string(format->name)))
            .string();
    job.files.push_back({path, format->encode({design.common, built, output_tolerance, path})});
    report.outputs.push_back(path);
    watch.lap("encode_" + std::string(format->name));
  }
  return job;
}

JobReport write_job(PreparedJob job, const JobOptions& options) {
  StageTimer watch(job.report.timings_ms);
  std::error_code ec;
  std::filesystem::create_directories(options.out_dir, ec);
  if (ec) {
    throw FileError(options.out_dir, 0, 0,
                    fmt::format("{}: cannot create the output folder: {}", options.out_dir, ec.message()));
  }
  write_files_atomically(job.files);
  watch.lap("write");
  return std::move(job.report);
}

JobReport run_job(const Design& design, const JobOptions& options) {
  return write_job(prepare_job(design, options), options);
}

}  // namespace fabmesh
