#include "geometry/sampling/cut_loop.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/core/error_checks.h"
#include "geometry/sampling/sample_curve.h"

namespace fabmesh {
namespace {

void reverse_loop(CutLoop& loop) {
  std::reverse(loop.entities.begin(), loop.entities.end());
  for (CutEntity& e : loop.entities) {
    std::reverse(e.points.begin(), e.points.end());
    std::reverse(e.weights.begin(), e.weights.end());
    std::swap(e.arc.from_deg, e.arc.to_deg);
  }
}

// A polynomial by its coefficients, c[k] of s^k.
using Poly = std::vector<double>;

double eval(const Poly& c, double s) {
  double v = 0.0;
  for (auto k = c.size(); k-- > 0;) v = v * s + c[k];
  return v;
}

Poly derivative(const Poly& c) {
  Poly d;
  for (std::size_t k = 1; k < c.size(); ++k) d.push_back(static_cast<double>(k) * c[k]);
  return d;
}

Poly times(const Poly& a, const Poly& b) {
  if (a.empty() || b.empty()) return {};
  Poly c(a.size() + b.size() - 1, 0.0);
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = 0; j < b.size(); ++j) c[i + j] += a[i] * b[j];
  }
  return c;
}

Poly minus(Poly a, const Poly& b) {
  if (a.size() < b.size()) a.resize(b.size(), 0.0);
  for (std::size_t k = 0; k < b.size(); ++k) a[k] -= b[k];
  return a;
}

// Parameters in [a, b] at which f changes sign or vanishes, plus the ends of
// the intervals on which f is monotone. Those intervals lie between the
// roots of f' (found the same way, down to a linear f'), so each holds at
// most one root of f: a sign change, which bisection pins to the last bits.
// Every parameter returned is a point of the curve, so extra ones are harmless.
void monotone_roots(Poly f, double a, double b, std::vector<double>& out) {
  while (!f.empty() && f.back() == 0.0) f.pop_back();
  if (f.size() <= 1) return;  // a constant: no isolated root
  std::vector<double> cuts{a};
  if (f.size() == 2) {
    const double r = -f[0] / f[1];
    if (r > a && r < b) cuts.push_back(r);
  } else {
    std::vector<double> critical;
    monotone_roots(derivative(f), a, b, critical);
    std::sort(critical.begin(), critical.end());
    for (const double c : critical) {
      if (c > cuts.back() && c < b) cuts.push_back(c);
    }
  }
  cuts.push_back(b);
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    double lo = cuts[i], hi = cuts[i + 1];
    out.push_back(lo);
    double flo = eval(f, lo);
    const double fhi = eval(f, hi);
    if (flo == 0.0 || fhi == 0.0 || (flo < 0.0) == (fhi < 0.0)) continue;
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (lo + hi);
      if (!(mid > lo && mid < hi)) break;
      const double fm = eval(f, mid);
      if (fm == 0.0) {
        lo = hi = mid;
        break;
      }
      if ((fm < 0.0) == (flo < 0.0)) {
        lo = mid;
        flo = fm;
      } else {
        hi = mid;
      }
    }
    out.push_back(lo);
    out.push_back(hi);
  }
  out.push_back(b);
}

// The ends of a Spline and its points where x' = 0 or y' = 0. With
// N = sum w_j (P_j - P_0) B_j and W = sum w_j B_j (cubics), x = N_x / W and
// x' = (N_x' W - N_x W') / W^2, W > 0: the numerator, of degree <= 4 (the
// terms of degree 5 cancel), has the parameters of the extremes among its roots.
void spline_extremes(const CutEntity& e, std::vector<Vec2>& out) {
  // The cubic Bernstein polynomials B_j by their coefficients of s^k.
  constexpr double kBernstein[4][4] = {{1, -3, 3, -1}, {0, 3, -6, 3}, {0, 0, 3, -3}, {0, 0, 0, 1}};
  Poly w(4, 0.0);
  std::array<Poly, 2> n{Poly(4, 0.0), Poly(4, 0.0)};
  for (std::size_t j = 0; j < 4; ++j) {
    for (std::size_t k = 0; k < 4; ++k) {
      w[k] += e.weights[j] * kBernstein[j][k];
      for (int axis = 0; axis < 2; ++axis)
        n[axis][k] += e.weights[j] * (e.points[j][axis] - e.points[0][axis]) * kBernstein[j][k];
    }
  }
  const Poly dw = derivative(w);
  std::vector<double> s;
  for (int axis = 0; axis < 2; ++axis) {
    Poly f = minus(times(derivative(n[axis]), w), times(n[axis], dw));
    f.resize(5);  // its s^5 terms, 3 n_3 w_3 - 3 n_3 w_3, cancel
    monotone_roots(f, 0.0, 1.0, s);
  }
  out.push_back(e.points.front());
  out.push_back(e.points.back());
  for (const double t : s) out.push_back(spline_point(e, t));
}

// The arc's end points and its extreme points in x and y that lie on the arc.
void arc_extremes(const EllipseArcParams& a, std::vector<Vec2>& out) {
  const double phi = a.rotation_deg * M_PI / 180.0;
  const double lo = std::min(a.from_deg, a.to_deg), hi = std::max(a.from_deg, a.to_deg);
  out.push_back(arc_point(a, a.from_deg));
  out.push_back(arc_point(a, a.to_deg));
  // dx/dt = 0 and dy/dt = 0 of center + R(phi) (a cos t, b sin t).
  for (double t0 : {std::atan2(-a.b * std::sin(phi), a.a * std::cos(phi)),
                    std::atan2(a.b * std::cos(phi), a.a * std::sin(phi))}) {
    for (int k = -3; k <= 3; ++k) {
      const double deg = t0 * 180.0 / M_PI + 180.0 * k;
      if (deg >= lo && deg <= hi) out.push_back(arc_point(a, deg));
    }
  }
}

// A quasi-cubic span with both local parameters 0 is the uniform cubic
// B-spline span, a polynomial cubic (a DXF template's polynomial SPLINE is
// read as such spans): a Spline with equal weights, exactly.
bool is_cubic_bspline_span(const Segment& seg) {
  return seg.kind() == SegmentKind::QuasiBSpline && seg.lambda() == 0.0 && seg.mu() == 0.0;
}

// The Bézier points of the uniform cubic B-spline span with control points b.
std::array<Vec2, 4> bezier_of_bspline_span(const std::array<Vec2, 4>& b) {
  return {(b[0] + 4.0 * b[1] + b[2]) / 6.0, (2.0 * b[1] + b[2]) / 3.0, (b[1] + 2.0 * b[2]) / 3.0,
          (b[1] + 4.0 * b[2] + b[3]) / 6.0};
}

}  // namespace

Vec2 spline_point(const CutEntity& e, double s) {
  const double u = 1.0 - s;
  const std::array<double, 4> b{u * u * u, 3.0 * u * u * s, 3.0 * u * s * s, s * s * s};
  Vec2 n(0.0, 0.0);
  double w = 0.0;
  for (std::size_t j = 0; j < 4; ++j) {
    n += e.weights[j] * b[j] * e.points[j];
    w += e.weights[j] * b[j];
  }
  return n / w;
}

std::vector<Vec2> spline_polyline(const CutEntity& spline, double tolerance) {
  require_positive("tolerance", tolerance);
  const Segment seg = Segment::rational_bezier(
      {spline.points[0], spline.points[1], spline.points[2], spline.points[3]}, spline.weights);
  SampleOptions so;
  so.tolerance = tolerance;
  std::vector<Vec2> out;
  for (const double s : sample_segment_parameters(seg, so)) out.push_back(seg.point(s));
  out.front() = spline.points.front();
  out.back() = spline.points.back();
  return out;
}

Vec2 arc_point(const EllipseArcParams& a, double deg) {
  const double t = deg * M_PI / 180.0;
  return a.center +
         Eigen::Rotation2Dd(a.rotation_deg * M_PI / 180.0) * Vec2(a.a * std::cos(t), a.b * std::sin(t));
}

CutLoop cut_loop(const CompositeCurve& curve, const std::string& label, bool outer,
                 const CutLoopOptions& options) {
  require_positive("tolerance", options.tolerance);
  SampleOptions so;
  so.tolerance = options.tolerance;
  CutLoop loop;
  loop.label = label;
  loop.outer = outer;
  loop.closed = curve.closed();
  loop.tolerance = options.tolerance;
  for (const Segment& seg : curve.segments()) {
    if (seg.kind() == SegmentKind::Line) {
      loop.entities.push_back({CutKind::Line, {seg.point(0.0), seg.point(1.0)}, {}});
    } else if (seg.kind() == SegmentKind::EllipseArc) {
      loop.entities.push_back({CutKind::Arc, {seg.point(0.0), seg.point(1.0)}, *seg.ellipse()});
    } else if (seg.kind() == SegmentKind::RationalBezier) {
      const std::array<Vec2, 4>& p = seg.control_points();
      loop.entities.push_back({CutKind::Spline, {p[0], p[1], p[2], p[3]}, {}, seg.rational_weights()});
    } else if (is_cubic_bspline_span(seg)) {
      const std::array<Vec2, 4> z = bezier_of_bspline_span(seg.control_points());
      loop.entities.push_back({CutKind::Spline, {z[0], z[1], z[2], z[3]}, {}, {1.0, 1.0, 1.0, 1.0}});
    } else {
      if (loop.entities.empty() || loop.entities.back().kind != CutKind::Polyline) {
        loop.entities.push_back({CutKind::Polyline, {seg.point(0.0)}, {}});
      }
      std::vector<Vec2>& pts = loop.entities.back().points;
      const std::vector<double> s = sample_segment_parameters(seg, so);
      for (std::size_t i = 1; i < s.size(); ++i) pts.push_back(seg.point(s[i]));
    }
  }
  // A loop that starts and ends inside one run of polyline segments is one polyline.
  if (loop.closed && loop.entities.size() > 1 && loop.entities.front().kind == CutKind::Polyline &&
      loop.entities.back().kind == CutKind::Polyline) {
    std::vector<Vec2>& tail = loop.entities.back().points;
    tail.insert(tail.end(), loop.entities.front().points.begin() + 1, loop.entities.front().points.end());
    loop.entities.erase(loop.entities.begin());
  }
  if (options.reverse) reverse_loop(loop);
  return loop;
}

std::pair<Vec2, Vec2> cut_bounds(const std::vector<CutLoop>& loops) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Vec2 lo = Vec2::Constant(kInf), hi = Vec2::Constant(-kInf);
  std::vector<Vec2> pts;
  for (const CutLoop& l : loops) {
    for (const CutEntity& e : l.entities) {
      if (e.kind == CutKind::Spline) {
        pts.clear();  // its inner control points are off the curve
        spline_extremes(e, pts);
      } else {
        pts = e.points;
        if (e.kind == CutKind::Arc) arc_extremes(e.arc, pts);
      }
      for (const Vec2& p : pts) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    }
  }
  return {lo, hi};
}

}  // namespace fabmesh
