#pragma once
// Test shapes for regions built in code, and the exact area of a closed
// composite curve (Green's theorem, Gauss-Legendre on each segment).

#include <cmath>
#include <vector>

#include "geometry/curves/composite.h"
#include "geometry/fairing/gauss_legendre.h"

namespace fabmesh::test {

/// Signed area enclosed by a closed curve: 1/2 sum over segments of the
/// integral of r x r' ds, 24 Gauss-Legendre nodes on each of 16 pieces of a
/// segment (the segments are smooth: trigonometric or polynomial in s).
inline double exact_area(const CompositeCurve& curve) {
  static const QuadratureRule rule = gauss_legendre(24);
  constexpr int pieces = 16;
  double area = 0.0;
  for (const Segment& seg : curve.segments()) {
    for (int p = 0; p < pieces; ++p) {
      for (std::size_t k = 0; k < rule.nodes.size(); ++k) {
        const double s = (p + rule.nodes[k]) / pieces;
        const CurveJet j = seg.jet(s);
        area += 0.5 * rule.weights[k] / pieces * cross2(j[0], j[1]);
      }
    }
  }
  return area;
}

/// Length of a closed curve by the same quadrature.
inline double exact_length(const CompositeCurve& curve) {
  static const QuadratureRule rule = gauss_legendre(24);
  constexpr int pieces = 16;
  double length = 0.0;
  for (const Segment& seg : curve.segments()) {
    for (int p = 0; p < pieces; ++p) {
      for (std::size_t k = 0; k < rule.nodes.size(); ++k) {
        length += rule.weights[k] / pieces * seg.jet((p + rule.nodes[k]) / pieces)[1].norm();
      }
    }
  }
  return length;
}

/// A closed polygon of line segments through `pts`.
inline CompositeCurve polygon(const std::vector<Vec2>& pts) {
  std::vector<Segment> segs;
  for (std::size_t i = 0; i < pts.size(); ++i)
    segs.push_back(Segment::line(pts[i], pts[(i + 1) % pts.size()]));
  return CompositeCurve(segs, true);
}

/// A rectangle [x0, x1] x [y0, y1] with corners rounded by exact quarter circles of radius r.
inline CompositeCurve rounded_rect(double x0, double y0, double x1, double y1, double r) {
  auto arc = [](Vec2 c, double rad, double from, double to) {
    EllipseArcParams e;
    e.center = c;
    e.a = e.b = rad;
    e.from_deg = from;
    e.to_deg = to;
    return Segment::ellipse_arc(e);
  };
  return CompositeCurve({Segment::line({x0 + r, y0}, {x1 - r, y0}), arc({x1 - r, y0 + r}, r, -90, 0),
                         Segment::line({x1, y0 + r}, {x1, y1 - r}), arc({x1 - r, y1 - r}, r, 0, 90),
                         Segment::line({x1 - r, y1}, {x0 + r, y1}), arc({x0 + r, y1 - r}, r, 90, 180),
                         Segment::line({x0, y1 - r}, {x0, y0 + r}), arc({x0 + r, y0 + r}, r, 180, 270)},
                        true);
}

/// A whole ellipse as one exact arc.
inline CompositeCurve ellipse(Vec2 center, double a, double b, double rotation_deg) {
  EllipseArcParams e;
  e.center = center;
  e.a = a;
  e.b = b;
  e.rotation_deg = rotation_deg;
  return CompositeCurve({Segment::ellipse_arc(e)}, true);
}

}  // namespace fabmesh::test
