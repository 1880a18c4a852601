#include "io/cutting/svg.h"

#include <fmt/format.h>

#include <cmath>

namespace fabmesh {
namespace {

// Shortest round-trip decimal of a coordinate (y negated for SVG's downward axis).
std::string num(double v) { return fmt::format("{}", v == 0.0 ? 0.0 : v); }
std::string pt(const Vec2& p) { return num(p.x()) + " " + num(-p.y()); }

// An exact arc as A commands of at most 120 degrees each (a whole ellipse
// needs at least two; pieces below 180 degrees make the flags unambiguous).
void append_arc(std::string& d, const EllipseArcParams& a) {
  const double span = a.to_deg - a.from_deg;
  const int pieces = std::max(1, static_cast<int>(std::ceil(std::abs(span) / 120.0)));
  // Counter-clockwise in the model is counter-clockwise on screen after the flip: sweep 0.
  const int sweep = span > 0.0 ? 0 : 1;
  for (int i = 1; i <= pieces; ++i) {
    const Vec2 end = arc_point(a, a.from_deg + span * i / pieces);
    d += fmt::format(" A {} {} {} 0 {} {}", num(a.a), num(a.b), num(-a.rotation_deg), sweep, pt(end));
  }
}

}  // namespace

std::string encode_svg(const std::vector<CutLoop>& loops, const SvgOptions& options) {
  const auto [lo, hi] = cut_bounds(loops);
  const double m = options.margin;
  const double w = hi.x() - lo.x() + 2 * m, h = hi.y() - lo.y() + 2 * m;
  const double scale = options.units == "m" ? 1000.0 : 1.0;
  const std::string unit = options.units == "m" ? "mm" : options.units;
  std::string out = fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}{}\" height=\"{}{}\" viewBox=\"{} {} {} {}\">\n",
      num(w * scale), unit, num(h * scale), unit, num(lo.x() - m), num(-(hi.y() + m)), num(w), num(h));
  std::size_t holes = 0;
  for (const CutLoop& loop : loops) {
    std::string d;
    for (const CutEntity& e : loop.entities) {
      if (d.empty()) d = "M " + pt(e.points.front());
      if (e.kind == CutKind::Arc) {
        append_arc(d, e.arc);
      } else {
        for (std::size_t i = 1; i < e.points.size(); ++i) d += " L " + pt(e.points[i]);
      }
    }
    if (loop.closed) d += " Z";
    const std::string id = loop.outer ? std::string("outline") : fmt::format("hole{}", holes++);
    out += fmt::format("  <path id=\"{}\" d=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"0.5\"/>\n", id,
                       d, loop.outer ? "red" : "blue");
  }
  out += "</svg>\n";
  return out;
}

}  // namespace fabmesh
