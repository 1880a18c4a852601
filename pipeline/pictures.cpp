#include "pipeline/pictures.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "geometry/core/errors.h"
#include "geometry/core/stage_timer.h"
#include "geometry/curves/composite.h"
#include "geometry/mesh/bounding_box.h"
#include "geometry/surfaces/patch_network.h"
#include "io/pictures/plot_curve.h"
#include "pipeline/design_curves.h"

namespace fabmesh {
namespace {

Vec2 plan(const Vec3& p) { return {p.x(), p.y()}; }

// Appends `part` to `scene`, every vertex moved by `shift`.
void append_shifted(TriangleSoup& scene, const TriangleSoup& part, const Vec3& shift) {
  const auto base = static_cast<std::uint32_t>(scene.vertices.size());
  for (const Vec3& v : part.vertices) scene.vertices.push_back(v + shift);
  for (const auto& t : part.triangles) scene.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
}

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

// A vessel's overall height and widest diameter, measured on its section
// (the profile closed as the builder makes it): the height beside the
// widest point, the diameter as the radius from the axis at its height.
// The point of `curve` farthest from the axis x = 0, as (|x|, y): the best
// of 64 samples per segment, refined by golden-section search between its
// neighbours to the last bits (|x| is unimodal there for a sampled profile).
Vec2 farthest_from_axis(const CompositeCurve& curve) {
  Vec2 best(-1.0, 0.0);
  for (const Segment& seg : curve.segments()) {
    const auto r = [&](double t) { return std::abs(seg.point(t).x()); };
    constexpr int kSamples = 64;
    int at = 0;
    for (int i = 1; i <= kSamples; ++i) {
      if (r(static_cast<double>(i) / kSamples) > r(static_cast<double>(at) / kSamples)) at = i;
    }
    double lo = std::max(0, at - 1) / static_cast<double>(kSamples);
    double hi = std::min(kSamples, at + 1) / static_cast<double>(kSamples);
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    for (int k = 0; k < 80 && hi - lo > 1e-16; ++k) {
      const double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
      if (r(a) < r(b)) {
        lo = a;
      } else {
        hi = b;
      }
    }
    for (const double t : {lo, hi, static_cast<double>(at) / kSamples}) {
      const Vec2 p = seg.point(t);
      if (std::abs(p.x()) > best.x()) best = Vec2(std::abs(p.x()), p.y());
    }
  }
  return best;
}

void add_vessel_dimensions(const std::vector<std::vector<Vec2>>& section, const CompositeCurve* profile,
                           const std::string& units, CurvePlot& plot) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  double z_lo = kInfinity, z_hi = -kInfinity;
  Vec2 widest(-kInfinity, 0.0);
  for (const auto& loop : section) {
    for (const Vec2& p : loop) {
      z_lo = std::min(z_lo, p.y());
      z_hi = std::max(z_hi, p.y());
      if (std::abs(p.x()) > widest.x()) widest = Vec2(std::abs(p.x()), p.y());
    }
  }
  // The section is sampled: between its points the profile (its outer wall) may reach farther.
  if (profile != nullptr) {
    const Vec2 exact = farthest_from_axis(*profile);
    if (exact.x() > widest.x() && exact.y() >= z_lo && exact.y() <= z_hi) widest = exact;
  }
  if (!(z_hi > z_lo) || !(widest.x() > 0.0)) return;
  const auto text = [&](const char* what, double v) { return fmt::format("{}{:.4g} {}", what, v, units); };
  // Downwards at the widest radius, set off to its right.
  plot.dimensions.push_back({"height", Vec2(widest.x(), z_hi), Vec2(widest.x(), z_lo), z_hi - z_lo,
                             text("height ", z_hi - z_lo), 18.0});
  plot.dimensions.push_back({"widest diameter", Vec2(0.0, widest.y()), widest, 2.0 * widest.x(),
                             text("\u00d8 ", 2.0 * widest.x()), 0.0});
}

}  // namespace

CurvePlot shape_plot(const DesignCommon& common, const std::vector<NamedBuiltCurve>& curves,
                     const PatchNetwork* patches, const std::vector<std::vector<Vec2>>* section,
                     const std::vector<std::vector<Vec2>>& overhangs, double overhang_limit_deg) {
  CurvePlot plot;
  plot.title = common.name;
  plot.units = common.units;
  for (const NamedBuiltCurve& c : curves) plot.curves.push_back(plot_curve(c.curve, c.name));
  if (patches != nullptr) add_surface(*patches, plot);
  if (section != nullptr) {
    plot.revolution_axis = true;
    plot.axis_names = {"r", "z"};
    for (const auto& loop : *section) plot.outlines.push_back({"section", loop});
    add_vessel_dimensions(*section, curves.empty() ? nullptr : &curves.front().curve.curve, common.units,
                          plot);
  }
  if (!overhangs.empty()) {
    plot.flags.push_back(
        {fmt::format("overhang beyond {:g}\u00b0 from vertical, printed upright (print.max_overhang_deg)",
                     overhang_limit_deg),
         overhangs});
  }
  return plot;
}

CurvePlot shape_plot(const DesignCommon& common, const BuiltShape& shape) {
  return shape_plot(common, shape.curves, shape.patches ? &*shape.patches : nullptr,
                    shape.revolved ? &shape.section : nullptr, shape.overhangs, shape.overhang_limit_deg);
}

CurvePlot shape_plot(const DesignCommon& common, const Result& result) {
  const auto* surface = std::get_if<SurfaceProducts>(&result.products);
  const auto* vessel = std::get_if<VesselProducts>(&result.products);
  if (vessel == nullptr) {
    return shape_plot(common, result.curves, surface != nullptr ? &surface->patches : nullptr, nullptr, {},
                      0.0);
  }
  return shape_plot(common, result.curves, nullptr, &vessel->section, vessel->overhangs,
                    vessel->overhang_limit_deg);
}

CurvePlot design_plot(const Design& design, std::vector<std::string>* contradicted) {
  return shape_plot(design.common, build_shape(design, contradicted));
}

std::string design_plot_svg(const Design& design, const CurvePlotOptions& options,
                            std::vector<std::string>* contradicted) {
  return plot_curves_svg(design_plot(design, contradicted), options);
}

std::string preview_png(const TriangleSoup& soup, const PreviewOptions& options) {
  return encode_png(render_preview(soup, options));
}

std::string size_caption(const TriangleSoup& soup, const std::string& units) {
  if (soup.vertices.empty()) return "";
  const BoundingBox box = bounding_box(soup.vertices);
  const Vec3 size = box.hi - box.lo;
  auto number = [](double x) {
    // Four significant digits without an exponent (the caption's font has no 'e').
    const int magnitude = x > 0.0 ? static_cast<int>(std::floor(std::log10(x))) : 0;
    return fmt::format("{:.{}f}", x, std::clamp(3 - magnitude, 0, 9));
  };
  std::string text = fmt::format("{} x {} x {}", number(size.x()), number(size.y()), number(size.z()));
  if (!units.empty()) text += " " + units;
  return text;
}

namespace {

// `part` moved by `shift` at the end of the scene, under its name.
void add_part(ExplodedScene& scene, const Part& part, const Vec3& shift) {
  append_shifted(scene.soup, part.mesh, shift);
  scene.parts.push_back({part.name, part.mesh.triangles.size()});
}

// A kitchen's pieces apart: each top piece moved away from the top's middle
// by a twentieth of its size (the seams open), the backsplash strips (built
// at the origin) in a row beyond the top's far edge.
ExplodedScene kitchen_scene(const Result& result, const KitchenProducts& k) {
  ExplodedScene scene;
  const Part* own = product(result);
  if (own == nullptr) return scene;
  const BoundingBox top = bounding_box(own->mesh.vertices);
  const Vec3 middle = 0.5 * (top.lo + top.hi);
  const double gap = 0.05 * std::max(top.hi.x() - top.lo.x(), top.hi.y() - top.lo.y());
  double x = top.lo.x();  // where the next strip starts
  for (const KitchenPiece& piece : k.split.pieces) {
    const auto part = std::find_if(result.parts.begin(), result.parts.end(), [&](const Part& p) {
      return p.role == PartRole::Piece && p.name == piece.name;
    });
    if (part == result.parts.end()) continue;
    if (piece.strip) {
      add_part(scene, *part, Vec3(x, top.hi.y() + gap, 0.0));
      x += bounding_box(part->mesh.vertices).hi.x() + gap;
      continue;
    }
    const BoundingBox box = bounding_box(part->mesh.vertices);
    const Vec3 out = 0.5 * (box.lo + box.hi) - middle;
    const Vec3 flat(out.x(), out.y(), 0.0);
    add_part(scene, *part, flat.norm() > 0.0 ? Vec3(gap * flat.normalized()) : Vec3::Zero());
  }
  return scene;
}

}  // namespace

TriangleSoup exploded_scene(const Result& result) { return exploded_scene_parts(result).soup; }

ExplodedScene exploded_scene_parts(const Result& result) {
  if (const auto* countertop = std::get_if<CountertopProducts>(&result.products);
      countertop != nullptr && countertop->kitchen) {
    return kitchen_scene(result, *countertop->kitchen);
  }
  ExplodedScene scene;
  const Part* own = product(result);
  if (own == nullptr) return scene;
  scene.soup = own->mesh;  // where it is, unmoved
  scene.parts.push_back({own->name, own->mesh.triangles.size()});
  std::vector<const Part*> mould;  // in the order built
  for (const Part& p : result.parts) {
    if (p.role == PartRole::MouldSide || p.role == PartRole::MouldBase) mould.push_back(&p);
  }
  if (mould.empty()) return scene;
  // Every part moved away from the vessel by the mould's radius (sides, along
  // their middle's direction from the axis) or half its height (the base).
  const BoundingBox product = bounding_box(own->mesh.vertices);
  BoundingBox all = product;
  for (const Part* part : mould) {
    const BoundingBox box = bounding_box(part->mesh.vertices);
    all.lo = all.lo.cwiseMin(box.lo);
    all.hi = all.hi.cwiseMax(box.hi);
  }
  const double radius =
      std::max({std::abs(all.lo.x()), std::abs(all.hi.x()), std::abs(all.lo.y()), std::abs(all.hi.y())});
  const double height = all.hi.z() - all.lo.z();
  for (const Part* named : mould) {
    const TriangleSoup& part = named->mesh;
    Vec3 centre = Vec3::Zero();
    for (const Vec3& v : part.vertices) centre += v;
    if (!part.vertices.empty()) centre /= static_cast<double>(part.vertices.size());
    const Vec3 out(centre.x(), centre.y(), 0.0);
    Vec3 shift(0.0, 0.0, centre.z() < 0.5 * (product.lo.z() + product.hi.z()) ? -0.5 * height : 0.5 * height);
    if (out.norm() > 1e-9 * radius) shift = out.normalized() * radius;
    add_part(scene, *named, shift);
  }
  return scene;
}

std::string design_preview_png(const DesignCommon& common, const Result& result, PreviewOptions options) {
  // A vessel is the kind built from a profile turned about the z axis.
  const bool vessel = std::holds_alternative<VesselProducts>(result.products);
  const Part* own = product(result);
  const TriangleSoup empty;
  const TriangleSoup& mesh = own != nullptr ? own->mesh : empty;
  options.caption = size_caption(mesh, common.units);
  if (vessel && !mesh.vertices.empty()) {
    const BoundingBox product = bounding_box(mesh.vertices);
    const double reach = 0.08 * (product.hi.z() - product.lo.z());
    options.guides.push_back(
        {Vec3(0.0, 0.0, product.lo.z() - reach), Vec3(0.0, 0.0, product.hi.z() + reach)});
  }
  return preview_png(exploded_scene(result), options);
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
  row.remarks = item.remarks;
  if (item.mesh) add_measures(*item.mesh, row);
  for (const auto& [stage, ms] : item.timings_ms) row.timings.push_back({stage, ms / 1000.0});
  for (const std::string& path : item.files) row.files.push_back(page_link(path, base));
  return row;
}

}  // namespace fabmesh
