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
#include "pipeline/outputs.h"
#include "pipeline/report.h"

namespace fabmesh::api {
namespace {

// The design's curves as built, sampled within the design's tolerance, each
// with the spec it was built from (fairing it again starts there).
std::vector<BuiltCurve> public_curves(const fabmesh::Design& design, const fabmesh::BuiltShape& shape) {
  const std::vector<fabmesh::NamedCurve> specs = fabmesh::design_curves(design);
  std::vector<BuiltCurve> curves;
  for (const fabmesh::NamedBuiltCurve& named : shape.curves) {
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

// What the job's builder made, as the result's mesh, verdict and curves.
void take_built(const fabmesh::BuiltMesh& built, const fabmesh::Design& design, BuildResult& result) {
  Mesh mesh = detail::public_mesh(built.soup);
  result.vertices = std::move(mesh.vertices);
  result.triangles = std::move(mesh.triangles);
  result.max_deviation = built.max_deviation;
  result.validation = detail::public_report(built.validation, fabmesh::validation_json(built.validation));
  result.curves = public_curves(design, built.shape);
}

}  // namespace

BuildResult build(const Design& design) {
  const fabmesh::Design& d = design.data().design;
  return detail::translated([&] {
    BuildResult result;
    result.units = d.common.units;
    result.tolerance = d.common.tolerance;
    fabmesh::JobOptions options;
    options.on_built = [&](const fabmesh::BuiltMesh& built) { take_built(built, d, result); };
    try {
      const fabmesh::PreparedJob job = fabmesh::prepare_job(d, options);
      result.valid = true;
      result.report_json = fabmesh::design_item(d.common.path, job.report).dump();
    } catch (const fabmesh::ValidationFailed&) {
      // Not fit for what the design is for: the mesh and its defects are the answer.
      const fabmesh::Failure failure = fabmesh::describe_failure(std::current_exception());
      result.error = failure.message;
      nlohmann::ordered_json item = fabmesh::error_item("design", d.common.path, failure);
      item["valid"] = false;
      result.report_json = item.dump();
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
    const fabmesh::JobReport report = fabmesh::run_job(d, options);
    return std::vector<std::filesystem::path>(report.outputs.begin(), report.outputs.end());
  });
}

std::string optimize(const Design& design) {
  const fabmesh::Design& d = design.data().design;
  return detail::translated(
      [&] { return fabmesh::optimize_items(d.common.path, fabmesh::optimize_design(d)).dump(); });
}

}  // namespace fabmesh::api
