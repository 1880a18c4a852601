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

// The measures of `mesh` on its row; counts, volume and area only when measured.
void add_measures(const MeshFacts& mesh, ReportRow& row) {
  row.kind = mesh.kind;
  row.units = mesh.units;
  row.max_deviation = mesh.max_deviation;
  if (mesh.measured) {
    row.volume = mesh.volume;
    row.area = mesh.area;
    row.triangles = mesh.triangles;
  }
  row.bbox = std::array<Vec3, 2>{mesh.bbox_min, mesh.bbox_max};
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

ReportStatus report_status(ItemStatus status) {
  switch (status) {
    case ItemStatus::Ok:
      return ReportStatus::Ok;
    case ItemStatus::Invalid:
      return ReportStatus::Invalid;
    case ItemStatus::BadInput:
      return ReportStatus::BadInput;
    case ItemStatus::Error:
    case ItemStatus::Missing:
    case ItemStatus::Environment:
      break;
  }
  return ReportStatus::Error;
}

std::string page_link(const std::string& path, const std::string& base) {
  return std::filesystem::path(path).lexically_relative(base.empty() ? "." : base).generic_string();
}

ReportRow report_row(const ItemFacts& item, const std::string& base) {
  ReportRow row;
  row.name = item.name;
  row.status = report_status(item.status);
  row.message = item.message;
  if (item.mesh) add_measures(*item.mesh, row);
  for (const auto& [stage, ms] : item.timings_ms) row.timings.push_back({stage, ms / 1000.0});
  for (const std::string& path : item.files) row.files.push_back(page_link(path, base));
  return row;
}

}  // namespace fabmesh
