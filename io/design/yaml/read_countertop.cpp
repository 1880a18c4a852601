#include "io/design/yaml/read_countertop.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geometry/curves/shapes.h"
#include "io/design/yaml/read_curve.h"

namespace fabmesh {
namespace {

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
  f.require_map(n, field, key_group("countertop.holes[]"));
  CountertopHole hole;
  if (n["ellipse"].IsDefined()) {
    const YAML::Node e = n["ellipse"];
    const std::string ef = field + ".ellipse";
    f.require_map(e, ef, key_group("countertop.holes[].ellipse"));
    const Vec2 c = f.point2(f.required(e, "center", ef), ef + ".center");
    const double a = f.number(f.required(e, "a", ef), ef + ".a");
    const double b = f.number(f.required(e, "b", ef), ef + ".b");
    const double rot = f.number_or(e, "rotation_deg", ef + ".rotation_deg", 0.0);
    hole.shape = "ellipse";
    f.checked(e, ef, [&] { hole.curve = ellipse_curve(c, a, b, rot); });
  } else if (n["rounded_rect"].IsDefined()) {
    const YAML::Node r = n["rounded_rect"];
    const std::string rf = field + ".rounded_rect";
    f.require_map(r, rf, key_group("countertop.holes[].rounded_rect"));
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

}  // namespace

CountertopDesign read_countertop(const yaml::Fields& f, const YAML::Node& root) {
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
  d.max_triangles = f.budget_or(root, "max_triangles", d.max_triangles);
  return d;
}

}  // namespace fabmesh
