#include "fabmesh/build.h"

#include <algorithm>
#include <exception>
#include <optional>

#include "api/src/detail.h"
#include "api/src/soup.h"
#include "api/src/validation_report.h"
#include "geometry/sampling/sample_curve.h"
#include "pipeline/design_curves.h"
#include "pipeline/failure.h"
#include "pipeline/job.h"
#include "pipeline/optimize.h"
#include "pipeline/output_table.h"
#include "pipeline/report.h"
#include "pipeline/validate_parts.h"

namespace fabmesh::api {
namespace {

// The public roles are the pipeline's, enumerator for enumerator: a part's
// role converts by value, and its name is the pipeline's name.
static_assert(static_cast<int>(PartRole::Product) == static_cast<int>(fabmesh::PartRole::Product) &&
              static_cast<int>(PartRole::MouldSide) == static_cast<int>(fabmesh::PartRole::MouldSide) &&
              static_cast<int>(PartRole::MouldBase) == static_cast<int>(fabmesh::PartRole::MouldBase) &&
              static_cast<int>(PartRole::Piece) == static_cast<int>(fabmesh::PartRole::Piece) &&
              static_cast<int>(PartRole::Master) == static_cast<int>(fabmesh::PartRole::Master) &&
              static_cast<int>(PartRole::Case) == static_cast<int>(fabmesh::PartRole::Case));

// The design's curves as built, sampled within the design's tolerance, each
// with the spec it was built from (fairing it again starts there).
std::vector<BuiltCurve> public_curves(const fabmesh::Design& design, const fabmesh::Result& built) {
  const std::vector<fabmesh::NamedCurve> specs = fabmesh::design_curves(design);
  std::vector<BuiltCurve> curves;
  for (const fabmesh::NamedBuiltCurve& named : built.curves) {
    fabmesh::SampleOptions options;
    options.tolerance = design.common.tolerance;
    const fabmesh::Polyline2 line = fabmesh::sample_curve(named.curve.curve, options);
    const auto spec = std::find_if(specs.begin(), specs.end(),
                                   [&](const fabmesh::NamedCurve& c) { return c.name == named.name; });
    BuiltCurve c{named.name,
                 {},
                 line.closed,
                 line.max_deviation,
                 detail::curve_handle(named.curve, spec != specs.end() ? spec->spec : fabmesh::CurveSpec{})};
    c.points.reserve(line.points.size());
    for (const Vec2& p : line.points) c.points.push_back({p.x(), p.y()});
    curves.push_back(std::move(c));
  }
  return curves;
}

// The public part of a result's part.
Part public_part(const fabmesh::Part& part) {
  Part out;
  out.name = part.name;
  out.role = static_cast<PartRole>(part.role);
  out.mesh = detail::public_mesh(part.mesh);
  out.validation = detail::public_report(part.validation, fabmesh::validation_json(part.validation));
  return out;
}

// What the job's builder made: the result's parts, curves and the product's mesh and verdict.
void take_built(const fabmesh::Result& built, const fabmesh::Design& design, Result& result) {
  result.name = built.name;
  result.kind = built.kind;
  result.max_deviation = built.max_deviation;
  result.warnings = built.warnings;
  for (const fabmesh::Part& part : built.parts) {
    result.parts.push_back(public_part(part));
    result.parts.back().mesh.units = unit_named(built.units);
  }
  if (!result.parts.empty() && result.parts.front().role == PartRole::Product) {
    result.vertices = result.parts.front().mesh.vertices;
    result.triangles = result.parts.front().mesh.triangles;
    result.validation = result.parts.front().validation;
  }
  result.curves = public_curves(design, built);
}

// The files a valid result's outputs write, and the ones skipped.
void take_files(const fabmesh::Result& built, Result& result) {
  for (const fabmesh::OutputFile& f : built.files) {
    result.files.push_back(
        {f.path, f.format, unit_named(f.units), f.added_error, f.valid_as_written, f.parts});
  }
  for (const fabmesh::SkippedOutput& s : built.skipped) result.skipped.push_back(s.format + ": " + s.reason);
}

}  // namespace

const char* to_string(PartRole role) { return fabmesh::to_string(static_cast<fabmesh::PartRole>(role)); }

Result build(const Design& design) {
  const fabmesh::Design& d = design.data().design;
  return detail::translated([&] {
    Result result;
    result.units = unit_named(d.common.units);
    result.tolerance = d.common.tolerance;
    const fabmesh::JobPlan plan = fabmesh::plan_job(d, {});
    fabmesh::Result built = fabmesh::build_job(d, plan);
    take_built(built, d, result);
    try {
      fabmesh::require_fit(built, d.common.purpose);
      const fabmesh::EncodedJob encoded = fabmesh::encode_job(built, plan);
      for (const fabmesh::EncodedFile& f : encoded.files) built.files.push_back(f.file);
      built.skipped = encoded.skipped;
      built.timings_ms.insert(built.timings_ms.end(), encoded.timings_ms.begin(), encoded.timings_ms.end());
      take_files(built, result);
      result.valid = true;
      result.set_json(fabmesh::design_item(d.common.path, built).dump());
    } catch (const fabmesh::ValidationFailed&) {
      // Not fit for what the design is for: the mesh and its defects are the answer.
      const fabmesh::Failure failure = fabmesh::describe_failure(std::current_exception());
      result.error = failure.message;
      nlohmann::ordered_json item = fabmesh::error_item("design", d.common.path, failure);
      item["valid"] = false;
      result.set_json(item.dump());
    }
    return result;
  });
}

void write_output(const Design& design, const std::filesystem::path& file) {
  const fabmesh::Design& d = design.data().design;
  detail::translated([&] {
    const fabmesh::OutputFormat* format = fabmesh::format_of_file(file.string());
    if (format == nullptr)
      detail::bad_argument("file", "'" + file.string() + "' names no format fabmesh writes");
    fabmesh::JobOptions options;
    options.export_format = std::string(format->name);
    options.output_file = file.string();
    options.out_dir = ".";
    fabmesh::run_job(d, options);
  });
}

std::vector<std::filesystem::path> write_outputs(const Design& design, const std::filesystem::path& folder) {
  const fabmesh::Design& d = design.data().design;
  return detail::translated([&] {
    fabmesh::JobOptions options;
    options.out_dir = folder.string();
    const std::vector<std::string> paths = fabmesh::written_paths(fabmesh::run_job(d, options));
    return std::vector<std::filesystem::path>(paths.begin(), paths.end());
  });
}

std::string optimize(const Design& design) {
  const fabmesh::Design& d = design.data().design;
  return detail::translated(
      [&] { return fabmesh::optimize_items(d.common.path, fabmesh::optimize_design(d)).dump(); });
}

}  // namespace fabmesh::api
