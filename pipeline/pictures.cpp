#include "pipeline/pictures.h"

#include <fmt/format.h>

#include <filesystem>
#include <type_traits>

#include "geometry/core/errors.h"
#include "geometry/core/stage_timer.h"
#include "geometry/curves/composite.h"
#include "geometry/surfaces/patch_network.h"
#include "io/pictures/plot_curve.h"
#include "pipeline/build_design.h"
#include "pipeline/design_curves.h"
#include "pipeline/failure.h"

namespace fabmesh {
namespace {

Vec2 plan(const Vec3& p) { return {p.x(), p.y()}; }

// A patch border seen from above, as the H-Bézier curve of its projected control points.
PlotCurve border_curve(const HBezierPatch& patch, PatchSide side, const std::string& name) {
  const std::array<Vec3, 4> p = border_points(patch, side);
  const HBezierParams& h = border_params(patch, side);
  const std::array<Vec2, 4> q{plan(p[0]), plan(p[1]), plan(p[2]), plan(p[3])};
  PlotCurve c;
  c.name = name;
  c.curve = CompositeCurve({Segment::hbezier(q, h.alpha, h.lambda, h.mu)}, false);
  c.control_polygons = control_polygons(c.curve);
  return c;
}

void add_surface(const PatchNetwork& network, CurvePlot& plot) {
  for (std::size_t k = 0; k < network.patches.size(); ++k) {
    const HBezierPatch& patch = network.patches[k];
    const std::string& name = network.names[k];
    for (const PatchSide side : {PatchSide::UMin, PatchSide::UMax, PatchSide::VMin, PatchSide::VMax})
      plot.curves.push_back(border_curve(patch, side, name + " " + to_string(side)));
    const ControlNet& net = patch.points();
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        if (i + 1 < 4) plot.net_lines.push_back({plan(net[i][j]), plan(net[i + 1][j])});
        if (j + 1 < 4) plot.net_lines.push_back({plan(net[i][j]), plan(net[i][j + 1])});
      }
    }
  }
}

std::string relative_to(const std::string& path, const std::string& base) {
  return std::filesystem::path(path).lexically_relative(base.empty() ? "." : base).generic_string();
}

}  // namespace

CurvePlot shape_plot(const DesignCommon& common, const BuiltShape& shape) {
  CurvePlot plot;
  plot.title = common.name;
  plot.units = common.units;
  for (const NamedBuiltCurve& c : shape.curves) plot.curves.push_back(plot_curve(c.curve, c.name));
  if (shape.patches) add_surface(*shape.patches, plot);
  return plot;
}

CurvePlot design_plot(const Design& design) { return shape_plot(design.common, build_shape(design)); }

std::string design_plot_svg(const Design& design, const CurvePlotOptions& options) {
  return plot_curves_svg(design_plot(design), options);
}

TriangleSoup design_mesh(const Design& design) {
  if (std::holds_alternative<CurveDesign>(design.body)) {
    throw InputError(
        fmt::format("{}: a curve design has no mesh to preview; try `fabmesh plot`", design.common.name));
  }
  StageTimings timings;
  StageTimer watch(timings);
  const BuildContext context{design.common, design.common.tolerance, false, watch, process_memory_limit()};
  return build_design(design, context).soup;
}

std::string preview_png(const TriangleSoup& soup, const PreviewOptions& options) {
  return encode_png(render_preview(soup, options));
}

ReportRow report_row(const JobReport& report, const std::string& base) {
  ReportRow row;
  row.name = report.name;
  row.kind = report.kind;
  row.units = report.units;
  const bool mesh = report.purpose != MeshPurpose::Drawing;
  row.status = !mesh || report.validation.valid() ? ReportStatus::Ok : ReportStatus::Invalid;
  row.message = !mesh                       ? "drawing written"
                : report.validation.valid() ? "valid for fabrication"
                                            : "written for viewing only: not valid for fabrication";
  row.max_deviation = report.max_deviation;
  if (mesh) {
    row.volume = report.validation.volume;
    row.area = report.validation.area;
    row.triangles = report.validation.triangles;
  }
  row.bbox = std::array<Vec3, 2>{report.bbox_min, report.bbox_max};
  for (const auto& [stage, ms] : report.timings_ms) row.timings.push_back({stage, ms / 1000.0});
  for (const std::string& path : report.outputs) row.files.push_back(relative_to(path, base));
  return row;
}

ReportRow failed_row(const std::string& design_file, int exit_code, const std::string& message) {
  ReportRow row;
  row.name = std::filesystem::path(design_file).stem().string();
  row.status = status_of<ReportStatus>(exit_code);
  row.message = message;
  return row;
}

}  // namespace fabmesh
