#include "io/design/read_countertop.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "io/design/read_curve.h"

namespace fabmesh {
namespace {

std::size_t read_budget(const yaml::Fields& f, const YAML::Node& root, std::size_t fallback) {
  if (!root["max_triangles"].IsDefined()) return fallback;
  const double budget = f.number(root["max_triangles"], "max_triangles");
  if (budget < 1.0 || budget > 2e9 || budget != std::floor(budget)) {
    f.fail(root["max_triangles"], "max_triangles",
           fmt::format("max_triangles = {} must be a whole number in [1, 2e9]", budget));
  }
  return static_cast<std::size_t>(budget);
}

CurveSpec read_closed_curve(const yaml::Fields& f, const YAML::Node& node, const std::string& field) {
  CurveSpec spec = read_curve(f, node, field);
  if (!spec.closed)
    f.fail(node, field + ".closed", fmt::format("{} must be a closed curve (closed: true)", field));
  return spec;
}

CountertopHole read_hole(const yaml::Fields& f, const YAML::Node& n, const std::string& field) {
  if (!n.IsMap() || n.size() != 1) {
    f.fail(n, field, "a hole is a map with one key: ellipse, rounded_rect or outline");
  }
  f.require_map(n, field, {"ellipse", "rounded_rect", "outline"});
  CountertopHole hole;
  if (n["ellipse"].IsDefined()) {
    const YAML::Node e = n["ellipse"];
    const std::string ef = field + ".ellipse";
    f.require_map(e, ef, {"center", "a", "b", "rotation_deg"});
    const Vec2 c = f.point2(f.required(e, "center", ef), ef + ".center");
    const double a = f.number(f.required(e, "a", ef), ef + ".a");
    const double b = f.number(f.required(e, "b", ef), ef + ".b");
    const double rot = f.number_or(e, "rotation_deg", ef + ".rotation_deg", 0.0);
    hole.shape = "ellipse";
    f.checked(e, ef, [&] { hole.curve = ellipse_curve(c, a, b, rot); });
  } else if (n["rounded_rect"].IsDefined()) {
    const YAML::Node r = n["rounded_rect"];
    const std::string rf = field + ".rounded_rect";
    f.require_map(r, rf, {"center", "size", "radius", "rotation_deg"});
    const Vec2 c = f.point2(f.required(r, "center", rf), rf + ".center");
    const Vec2 size = f.point2(f.required(r, "size", rf), rf + ".size");
    const double radius = f.number(f.required(r, "radius", rf), rf + ".radius");
    const double rot = f.number_or(r, "rotation_deg", rf + ".rotation_deg", 0.0);
    hole.shape = "rounded_rect";
    f.checked(r, rf, [&] { hole.curve = rounded_rect_curve(c, size.x(), size.y(), radius, rot); });
  } else {
    hole.shape = "outline";
    hole.curve = read_closed_curve(f, n["outline"], field + ".outline");
  }
  hole.curve.label = f.label(n, field);
  return hole;
}

SegmentSpec arc_spec(const Vec2& center, double a, double b, double rotation_deg, double from, double to) {
  SegmentSpec s;
  s.kind = SegmentKind::EllipseArc;
  s.ellipse.center = center;
  s.ellipse.a = a;
  s.ellipse.b = b;
  s.ellipse.rotation_deg = rotation_deg;
  s.ellipse.from_deg = from;
  s.ellipse.to_deg = to;
  Segment::ellipse_arc(s.ellipse);  // range checks
  return s;
}

}  // namespace

CurveSpec ellipse_curve(const Vec2& center, double a, double b, double rotation_deg) {
  require_positive("a", a);
  require_positive("b", b);
  require_in_range("rotation_deg", rotation_deg, -1e6, 1e6);
  CurveSpec spec;
  spec.closed = true;
  spec.closing_declared = Continuity::G1;
  spec.segments.push_back(arc_spec(center, a, b, rotation_deg, 0.0, 360.0));
  spec.label = "ellipse";
  return spec;
}

CurveSpec rounded_rect_curve(const Vec2& center, double w, double h, double r, double rotation_deg) {
  require_positive("size[0]", w);
  require_positive("size[1]", h);
  require_in_range("radius", r, 0.0, 0.5 * std::min(w, h));
  require_in_range("rotation_deg", rotation_deg, -1e6, 1e6);
  const double t = rotation_deg * M_PI / 180.0;
  const Eigen::Rotation2Dd rot(t);
  auto place = [&](double x, double y) -> Vec2 { return center + rot * Vec2(x, y); };
  const double hw = 0.5 * w, hh = 0.5 * h;
  const Continuity joint = r > 0.0 ? Continuity::G1 : Continuity::G0;
  CurveSpec spec;
  spec.closed = true;
  spec.closing_declared = joint;
  spec.label = "rounded_rect";
  // Counter-clockwise: each straight side (skipped when the corners use it all up), then the corner after it.
  const std::array<Vec2, 4> side_from{Vec2(-hw + r, -hh), Vec2(hw, -hh + r), Vec2(hw - r, hh),
                                      Vec2(-hw, hh - r)};
  const std::array<Vec2, 4> side_to{Vec2(hw - r, -hh), Vec2(hw, hh - r), Vec2(-hw + r, hh),
                                    Vec2(-hw, -hh + r)};
  const std::array<Vec2, 4> corner{Vec2(hw - r, -hh + r), Vec2(hw - r, hh - r), Vec2(-hw + r, hh - r),
                                   Vec2(-hw + r, -hh + r)};
  for (int i = 0; i < 4; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (side_from[k] != side_to[k]) {
      SegmentSpec line;
      line.kind = SegmentKind::Line;
      if (spec.segments.empty()) line.points.push_back(place(side_from[k].x(), side_from[k].y()));
      line.points.push_back(place(side_to[k].x(), side_to[k].y()));
      line.declared = joint;
      spec.segments.push_back(line);
    }
    if (r > 0.0) {
      SegmentSpec arc =
          arc_spec(place(corner[k].x(), corner[k].y()), r, r, rotation_deg, -90.0 + 90.0 * i, 90.0 * i);
      arc.declared = joint;
      spec.segments.push_back(arc);
    }
  }
  return spec;
}

CountertopDesign read_countertop(const yaml::Fields& f, const YAML::Node& root) {
  f.require_map(root, "",
                {"name", "kind", "units", "tolerance", "outputs", "outline", "holes", "thickness", "max_edge",
                 "max_triangles"});
  CountertopDesign d;
  d.outline = read_closed_curve(f, f.required(root, "outline", "outline"), "outline");
  if (root["holes"].IsDefined()) {
    const YAML::Node holes = root["holes"];
    f.require_list(holes, "holes");
    for (std::size_t i = 0; i < holes.size(); ++i)
      d.holes.push_back(read_hole(f, holes[i], fmt::format("holes[{}]", i)));
  }
  const YAML::Node thickness = f.required(root, "thickness", "thickness");
  d.thickness = f.number(thickness, "thickness");
  if (d.thickness <= 0.0)
    f.fail(thickness, "thickness", fmt::format("thickness = {} must be > 0", d.thickness));
  if (root["max_edge"].IsDefined()) {
    d.max_edge = f.number(root["max_edge"], "max_edge");
    if (d.max_edge <= 0.0)
      f.fail(root["max_edge"], "max_edge", fmt::format("max_edge = {} must be > 0", d.max_edge));
  }
  d.max_triangles = read_budget(f, root, d.max_triangles);
  return d;
}

}  // namespace fabmesh
