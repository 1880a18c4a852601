#include "io/cutting/svg_writing.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace fabmesh {

std::string svg_number(double v) { return fmt::format("{}", v == 0.0 ? 0.0 : v); }

std::string svg_point(const Vec2& p) { return svg_number(p.x()) + " " + svg_number(-p.y()); }

void append_svg_arc(std::string& d, const EllipseArcParams& a) {
  const double span = a.to_deg - a.from_deg;
  const int pieces = std::max(1, static_cast<int>(std::ceil(std::abs(span) / 120.0)));
  // Counter-clockwise in the model is counter-clockwise on screen after the flip: sweep 0.
  const int sweep = span > 0.0 ? 0 : 1;
  for (int i = 1; i <= pieces; ++i) {
    const Vec2 end = arc_point(a, a.from_deg + span * i / pieces);
    d += fmt::format(" A {} {} {} 0 {} {}", svg_number(a.a), svg_number(a.b), svg_number(-a.rotation_deg),
                     sweep, svg_point(end));
  }
}

void append_svg_loop(std::string& d, const CutLoop& loop) {
  for (const CutEntity& e : loop.entities) {
    if (&e == &loop.entities.front()) d += (d.empty() ? "M " : " M ") + svg_point(e.points.front());
    if (e.kind == CutKind::Arc) {
      append_svg_arc(d, e.arc);
    } else if (e.kind == CutKind::Spline) {
      const std::array<double, 4>& w = e.weights;
      if (w[1] == w[0] && w[2] == w[0] && w[3] == w[0]) {  // a polynomial cubic: exact
        d += " C " + svg_point(e.points[1]) + " " + svg_point(e.points[2]) + " " + svg_point(e.points[3]);
      } else {  // SVG has no rational curves
        const std::vector<Vec2> pts = spline_polyline(e, loop.tolerance);
        for (std::size_t i = 1; i < pts.size(); ++i) d += " L " + svg_point(pts[i]);
      }
    } else {
      for (std::size_t i = 1; i < e.points.size(); ++i) d += " L " + svg_point(e.points[i]);
    }
  }
}

std::string svg_start(const Vec2& lo, const Vec2& hi, double margin, const std::string& units) {
  const double m = margin;
  const double w = hi.x() - lo.x() + 2 * m, h = hi.y() - lo.y() + 2 * m;
  const double scale = units == "m" ? 1000.0 : 1.0;
  const std::string unit = units == "m" ? "mm" : units;
  return fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}{}\" height=\"{}{}\" viewBox=\"{} {} {} {}\">\n",
      svg_number(w * scale), unit, svg_number(h * scale), unit, svg_number(lo.x() - m),
      svg_number(-(hi.y() + m)), svg_number(w), svg_number(h));
}

}  // namespace fabmesh
