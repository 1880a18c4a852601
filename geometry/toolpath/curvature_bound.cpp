#include "geometry/toolpath/curvature_bound.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <vector>

namespace fabmesh {
namespace {

double signed_curvature(const CurveJet& j) {
  const double speed = j[1].norm();
  return cross2(j[1], j[2]) / (speed * speed * speed);
}

// Ellipse arcs: along the angle parameter t the curvature is a b / q(t)^(3/2),
// q = a^2 sin^2 t + b^2 cos^2 t, whose extremes lie at the arc's ends or at
// multiples of 90 degrees (dq/dt = (a^2 - b^2) sin 2t).
CurvatureBound ellipse_least(const EllipseArcParams& e, double sign) {
  const double span = e.to_deg - e.from_deg;
  const double sigma = span > 0.0 ? sign : -sign;
  auto q = [&](double deg) {
    const double t = deg * M_PI / 180.0;
    const double sn = std::sin(t), cs = std::cos(t);
    return e.a * e.a * sn * sn + e.b * e.b * cs * cs;
  };
  std::vector<double> candidates{e.from_deg, e.to_deg};
  const double lo = std::min(e.from_deg, e.to_deg), hi = std::max(e.from_deg, e.to_deg);
  for (double k = std::ceil(lo / 90.0); k * 90.0 <= hi; k += 1.0) candidates.push_back(k * 90.0);
  double best_deg = candidates.front(), best_q = q(best_deg);
  for (double deg : candidates) {
    const double v = q(deg);
    // sigma > 0: the least curvature is where q is largest; sigma < 0: where it is smallest.
    if (sigma > 0.0 ? v > best_q : v < best_q) best_q = v, best_deg = deg;
  }
  CurvatureBound out;
  out.least = out.attained = sigma * e.a * e.b / std::pow(best_q, 1.5);
  out.s = (best_deg - e.from_deg) / span;
  return out;
}

struct Cell {
  double a, b;
  double lower;                                                    // proven lower bound of sign * k on [a, b]
  bool operator<(const Cell& o) const { return lower > o.lower; }  // priority queue: smallest bound first
};

}  // namespace

JetBounds jet_bounds(const Segment& seg, double a, double b, double m4) {
  JetBounds out;
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  out.at_center = seg.jet(c);
  out.half = h;
  const double d1 = out.at_center[1].norm(), d2 = out.at_center[2].norm(), d3 = out.at_center[3].norm();
  out.d3 = d3 + h * m4;
  out.d2 = d2 + h * d3 + 0.5 * h * h * m4;
  out.min_speed = d1 - (h * d2 + 0.5 * h * h * d3 + h * h * h / 6.0 * m4);
  return out;
}

CurvatureBound least_curvature(const Segment& seg, double sign, double precision, double good_enough,
                               std::size_t budget) {
  CurvatureBound out;
  if (seg.kind() == SegmentKind::Line) {
    out.s = 0.5;
    return out;
  }
  if (seg.kind() == SegmentKind::EllipseArc) return ellipse_least(*seg.ellipse(), sign);

  const double m4 = seg.fourth_derivative_bound();
  out.attained = INFINITY;
  std::priority_queue<Cell> queue;
  std::size_t evaluated = 0;
  auto push = [&](double a, double b) {
    const JetBounds jb = jet_bounds(seg, a, b, m4);
    ++evaluated;
    const double value = sign * signed_curvature(jb.at_center);
    if (value < out.attained) out.attained = value, out.s = 0.5 * (a + b);
    double lower = -std::numeric_limits<double>::infinity();
    if (jb.min_speed > 0.0) {
      const double s = jb.min_speed;
      lower = value - jb.half * (jb.d3 / (s * s) + 3.0 * jb.d2 * jb.d2 / (s * s * s));
    }
    queue.push({a, b, lower});
  };
  constexpr int kInitial = 16;
  for (int i = 0; i < kInitial; ++i)
    push(static_cast<double>(i) / kInitial, static_cast<double>(i + 1) / kInitial);
  for (double end : {0.0, 1.0}) {  // the ends are often the extremes: evaluate them exactly
    const double value = sign * signed_curvature(seg.jet(end));
    if (value < out.attained) out.attained = value, out.s = end;
  }
  while (!queue.empty()) {
    const Cell cell = queue.top();
    if (cell.lower >= out.attained - precision) break;  // every cell left is within precision
    if (cell.lower >= good_enough) break;               // every value is proven above what matters
    if (evaluated >= budget) break;
    queue.pop();
    const double mid = 0.5 * (cell.a + cell.b);
    if (!(mid > cell.a && mid < cell.b)) {  // cannot split further: keep the weaker bound
      out.least = cell.lower;
      return out;
    }
    push(cell.a, mid);
    push(mid, cell.b);
  }
  out.least = queue.empty() ? out.attained : std::min(out.attained, queue.top().lower);
  return out;
}

}  // namespace fabmesh
