#include "geometry/curves/segment.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geometry/core/error_checks.h"

namespace fabmesh {
namespace {

constexpr double kDegree = M_PI / 180.0;

void require_finite_points(const std::array<Vec2, 4>& points, int count) {
  for (int j = 0; j < count; ++j) {
    for (int c = 0; c < 2; ++c) {
      if (!std::isfinite(points[j][c])) {
        throw RangeError(fmt::format("P{}", j), points[j][c],
                         fmt::format("control point P{} has a non-finite coordinate {}", j, points[j][c]));
      }
    }
  }
}

void require_quasi_parameter(const char* name, double value) {
  if (value == 4.0) return;  // the end value that makes the curve interpolate p0 and pn
  require_in_range(name, value, -8.0, 1.0);
}

// The cubic Bernstein polynomials B_j(s) and their derivatives, orders 0..3.
BasisJet bernstein_jet(double s) {
  const double u = 1.0 - s;
  BasisJet b{};
  b[0] = {u * u * u, 3.0 * s * u * u, 3.0 * s * s * u, s * s * s};
  b[1] = {-3.0 * u * u, 3.0 * u * u - 6.0 * s * u, 6.0 * s * u - 3.0 * s * s, 3.0 * s * s};
  b[2] = {6.0 * u, 6.0 * s - 12.0 * u, 6.0 * u - 12.0 * s, 6.0 * s};
  b[3] = {-6.0, 18.0, -18.0, 6.0};
  return b;
}

constexpr double kBinomial[5][5] = {
    {1, 0, 0, 0, 0}, {1, 1, 0, 0, 0}, {1, 2, 1, 0, 0}, {1, 3, 3, 1, 0}, {1, 4, 6, 4, 1}};

// docs/math/curves.md 5: R_j = N_j / W with N_j = w_j B_j and W = sum_j N_j;
// Leibniz on N_j = R_j W gives R_j^(k) = (N_j^(k) - sum_{i<k} C(k, i) R_j^(i) W^(k-i)) / W.
BasisJet rational_bezier_basis(double s, const std::array<double, 4>& w) {
  const BasisJet b = bernstein_jet(s);
  BasisJet n{};
  std::array<double, 4> den{};
  for (int k = 0; k < 4; ++k) {
    for (int j = 0; j < 4; ++j) {
      n[k][j] = w[j] * b[k][j];
      den[k] += n[k][j];
    }
  }
  BasisJet r{};
  for (int k = 0; k < 4; ++k) {
    for (int j = 0; j < 4; ++j) {
      double v = n[k][j];
      for (int i = 0; i < k; ++i) v -= kBinomial[k][i] * r[i][j] * den[k - i];
      r[k][j] = v / den[0];
    }
  }
  return r;
}

using Homogeneous = std::array<Eigen::Vector3d, 4>;  // (w x, w y, w) of each control point

// The blossom f(u1, u2, u3) of a cubic Bézier curve: de Casteljau with one
// parameter per level. f(a, a, a), f(a, a, b), f(a, b, b), f(b, b, b) are the
// control points of its piece over [a, b].
Eigen::Vector3d blossom(const Homogeneous& h, double u1, double u2, double u3) {
  Homogeneous d = h;
  const std::array<double, 3> u{u1, u2, u3};
  for (int level = 0; level < 3; ++level) {
    for (int i = 0; i + level < 3; ++i) d[i] = (1.0 - u[level]) * d[i] + u[level] * d[i + 1];
  }
  return d[0];
}

// docs/math/curves.md 5.1: a bound of the fourth derivative over [0, 1] of a
// rational cubic Bézier curve with positive weights: the largest of the
// bounds proven on kRationalPieces equal pieces.
constexpr int kRationalPieces = 16;

double rational_fourth_bound(const std::array<Vec2, 4>& p, const std::array<double, 4>& w) {
  if (std::all_of(w.begin(), w.end(), [&](double x) { return x == w[0]; })) {
    return 0.0;  // equal weights: a cubic polynomial
  }
  Homogeneous h;
  for (int j = 0; j < 4; ++j) h[j] = Eigen::Vector3d(w[j] * p[j].x(), w[j] * p[j].y(), w[j]);
  double bound = 0.0;
  for (int piece = 0; piece < kRationalPieces; ++piece) {
    const double a = static_cast<double>(piece) / kRationalPieces;
    const double b = static_cast<double>(piece + 1) / kRationalPieces;
    const Homogeneous q{blossom(h, a, a, a), blossom(h, a, a, b), blossom(h, a, b, b), blossom(h, b, b, b)};
    // In the piece's own parameter t = (s - a) / (b - a), about its first
    // point c: u = r - c = N / W, N = sum W_i (Q_i - c) B_i, W = sum W_i B_i.
    std::array<double, 4> weight{};
    std::array<Vec2, 4> numerator{};
    double lowest = INFINITY, reach = 0.0;
    const Vec2 c = q[0].head<2>() / q[0].z();
    for (std::size_t i = 0; i < 4; ++i) {
      weight[i] = q[i].z();
      lowest = std::min(lowest, weight[i]);
      const Vec2 rel = q[i].head<2>() / weight[i] - c;
      numerator[i] = weight[i] * rel;
      reach = std::max(reach, rel.norm());  // |u| <= max |Q_i - c|: u lies in their convex hull
    }
    // |N^(k)|, |W^(k)| <= 3! / (3 - k)! max |k-th differences of the control points|.
    std::array<double, 5> nu{}, om{};
    double factor = 1.0;
    for (int k = 1; k <= 3; ++k) {
      factor *= 4 - k;
      double dn = 0.0, dw = 0.0;
      for (int i = 0; i + k <= 3; ++i) {
        Vec2 v = Vec2::Zero();
        double x = 0.0;
        for (int l = 0; l <= k; ++l) {
          const double sign = (k - l) % 2 == 0 ? 1.0 : -1.0;
          v += sign * kBinomial[k][l] * numerator[i + l];
          x += sign * kBinomial[k][l] * weight[i + l];
        }
        dn = std::max(dn, v.norm());
        dw = std::max(dw, std::abs(x));
      }
      nu[k] = factor * dn;
      om[k] = factor * dw;
    }
    // u^(k) = (N^(k) - sum_{i<k} C(k, i) u^(i) W^(k-i)) / W with W >= min W_i > 0
    // (N and W are cubics: their fourth derivatives vanish).
    std::array<double, 5> rho{reach, 0.0, 0.0, 0.0, 0.0};
    for (int k = 1; k <= 4; ++k) {
      double sum = nu[k];
      for (int i = 0; i < k; ++i) sum += kBinomial[k][i] * rho[i] * om[k - i];
      rho[k] = sum / lowest;
    }
    bound = std::max(bound, rho[4] * std::pow(static_cast<double>(kRationalPieces), 4));
  }
  return bound;
}

}  // namespace

const char* to_string(SegmentKind kind) {
  switch (kind) {
    case SegmentKind::TBezier:
      return "tbezier";
    case SegmentKind::EllipseArc:
      return "ellipse_arc";
    case SegmentKind::Line:
      return "line";
    case SegmentKind::HBezier:
      return "hbezier";
    case SegmentKind::QuasiBSpline:
      return "quasi_bspline";
    case SegmentKind::RationalBezier:
      return "rational_bezier";
  }
  return "unknown";
}

Segment Segment::tbezier(const std::array<Vec2, 4>& points, double lambda, double mu) {
  require_finite_points(points, 4);
  require_in_range("lambda", lambda, -2.0, 1.0);
  require_in_range("mu", mu, -2.0, 1.0);
  Segment seg;
  seg.kind_ = SegmentKind::TBezier;
  seg.points_ = points;
  seg.lambda_ = lambda;
  seg.mu_ = mu;
  return seg;
}

Segment Segment::hbezier(const std::array<Vec2, 4>& points, double alpha, double lambda, double mu) {
  require_finite_points(points, 4);
  require_in_range("alpha", alpha, 0.0, 10.0);
  if (alpha == 0.0) throw RangeError("alpha", alpha, "alpha = 0 is outside (0, 10]");
  const double lo = hbezier_lambda_min(alpha);
  for (auto [name, value] : {std::pair{"lambda", lambda}, std::pair{"mu", mu}}) {
    require_in_range(name, value, lo, 1.0);
    if (value == lo) {
      throw RangeError(name, value,
                       fmt::format("{} = {} is outside ({}, 1] for alpha = {}", name, value, lo, alpha));
    }
  }
  Segment seg;
  seg.kind_ = SegmentKind::HBezier;
  seg.points_ = points;
  seg.alpha_ = alpha;
  seg.hbezier_ = hbezier_constants(alpha);
  seg.lambda_ = lambda;
  seg.mu_ = mu;
  return seg;
}

Segment Segment::line(const Vec2& from, const Vec2& to) {
  require_finite_points({from, to, to, to}, 2);
  if (from == to) {
    throw GeometryError("line",
                        fmt::format("line from ({}, {}) to itself has zero length", from.x(), from.y()));
  }
  Segment seg;
  seg.kind_ = SegmentKind::Line;
  seg.points_ = {from, to, to, to};
  return seg;
}

Segment Segment::ellipse_arc(const EllipseArcParams& p) {
  require_finite_points({p.center, p.center, p.center, p.center}, 1);
  require_positive("a", p.a);
  require_positive("b", p.b);
  require_in_range("rotation_deg", p.rotation_deg, -360.0, 360.0);
  require_in_range("from_deg", p.from_deg, -720.0, 720.0);
  require_in_range("to_deg", p.to_deg, -720.0, 720.0);
  const double sweep = p.to_deg - p.from_deg;
  if (sweep == 0.0 || std::abs(sweep) > 360.0) {
    throw RangeError(
        "to_deg", p.to_deg,
        fmt::format("ellipse arc sweep to_deg - from_deg = {} must be nonzero and at most 360", sweep));
  }
  Segment seg;
  seg.kind_ = SegmentKind::EllipseArc;
  // docs/math/curves.md 1.2: lambda = mu = 0 and these points give (a cos(pi t/2), b sin(pi t/2))
  // for every t.
  seg.points_ = {Vec2(p.a, 0.0), Vec2(p.a, p.b / 2.0), Vec2(p.a / 2.0, p.b), Vec2(0.0, p.b)};
  seg.t0_ = p.from_deg / 90.0;
  seg.t1_ = p.to_deg / 90.0;
  seg.origin_ = p.center;
  seg.cos_ = std::cos(p.rotation_deg * kDegree);
  seg.sin_ = std::sin(p.rotation_deg * kDegree);
  seg.ellipse_ = p;
  return seg;
}

Segment Segment::quasi_bspline_span(const std::array<Vec2, 4>& points, double l, double m) {
  require_finite_points(points, 4);
  require_quasi_parameter("lambda_i", l);
  require_quasi_parameter("lambda_i+1", m);
  Segment seg;
  seg.kind_ = SegmentKind::QuasiBSpline;
  seg.points_ = points;
  seg.lambda_ = l;
  seg.mu_ = m;
  return seg;
}

Segment Segment::rational_bezier(const std::array<Vec2, 4>& points, const std::array<double, 4>& weights) {
  require_finite_points(points, 4);
  for (std::size_t j = 0; j < 4; ++j) {
    if (!(std::isfinite(weights[j]) && weights[j] > 0.0)) {
      throw RangeError(
          fmt::format("w{}", j), weights[j],
          fmt::format("weight w{} = {} of a rational Bézier segment is not finite and > 0", j, weights[j]));
    }
  }
  Segment seg;
  seg.kind_ = SegmentKind::RationalBezier;
  seg.points_ = points;
  seg.rational_ = weights;
  return seg;
}

Segment Segment::with_shape(double lambda, double mu) const {
  switch (kind_) {
    case SegmentKind::TBezier:
      return tbezier(points_, lambda, mu);
    case SegmentKind::HBezier:
      return hbezier(points_, alpha_, lambda, mu);
    case SegmentKind::QuasiBSpline:
      return quasi_bspline_span(points_, lambda, mu);
    case SegmentKind::EllipseArc:
    case SegmentKind::Line:
    case SegmentKind::RationalBezier:
      break;
  }
  throw GeometryError(to_string(kind_),
                      fmt::format("a {} segment has no shape parameters", to_string(kind_)));
}

Segment Segment::with_points(const std::array<Vec2, 4>& points) const {
  switch (kind_) {
    case SegmentKind::TBezier:
      return tbezier(points, lambda_, mu_);
    case SegmentKind::HBezier:
      return hbezier(points, alpha_, lambda_, mu_);
    case SegmentKind::QuasiBSpline:
      return quasi_bspline_span(points, lambda_, mu_);
    case SegmentKind::Line:
      return line(points[0], points[1]);
    case SegmentKind::RationalBezier:
      return rational_bezier(points, rational_);
    case SegmentKind::EllipseArc:
      break;
  }
  throw GeometryError("ellipse_arc", "an ellipse arc is defined by its parameters, not by control points");
}

double Segment::native_scale() const {
  switch (kind_) {
    case SegmentKind::EllipseArc:
      return t1_ - t0_;
    case SegmentKind::HBezier:
      return alpha_;
    default:
      return 1.0;
  }
}

BasisJet Segment::weights(double s) const {
  BasisJet w{};
  const double scale = native_scale();
  switch (kind_) {
    case SegmentKind::TBezier:
      w = tbezier_basis(s, lambda_, mu_);
      break;
    case SegmentKind::EllipseArc:
      w = tbezier_basis(t0_ + s * scale, 0.0, 0.0);
      break;
    case SegmentKind::HBezier:
      w = hbezier_basis(s * alpha_, alpha_, lambda_, mu_, hbezier_);
      break;
    case SegmentKind::QuasiBSpline:
      w = quasi_bspline_basis(s, lambda_, mu_);
      break;
    case SegmentKind::RationalBezier:
      return rational_bezier_basis(s, rational_);
    case SegmentKind::Line:
      w[0] = {1.0 - s, s, 0.0, 0.0};
      w[1] = {-1.0, 1.0, 0.0, 0.0};
      return w;
  }
  double factor = 1.0;
  for (int k = 1; k < 4; ++k) {
    factor *= scale;
    for (double& x : w[k]) x *= factor;
  }
  return w;
}

CurveJet Segment::jet(double s) const {
  const BasisJet w = weights(s);
  CurveJet r{};
  for (int k = 0; k < 4; ++k) {
    Vec2 v = Vec2::Zero();
    for (int j = 0; j < control_count(); ++j) v += w[k][j] * points_[j];
    r[k] = v;
  }
  if (kind_ == SegmentKind::EllipseArc) {
    for (int k = 0; k < 4; ++k) {
      const Vec2 v = r[k];
      r[k] = Vec2(cos_ * v.x() - sin_ * v.y(), sin_ * v.x() + cos_ * v.y());
    }
    r[0] += origin_;
  }
  return r;
}

Vec2 Segment::point(double s) const { return jet(s)[0]; }

double Segment::curvature(double s) const {
  const CurveJet r = jet(s);
  const double speed = r[1].norm();
  return cross2(r[1], r[2]) / (speed * speed * speed);
}

double Segment::fourth_derivative_bound() const {
  std::array<double, 4> b{};
  const double scale = std::abs(native_scale());
  switch (kind_) {
    case SegmentKind::TBezier:
      b = tbezier_fourth_bound(lambda_, mu_);
      break;
    case SegmentKind::EllipseArc:
      b = tbezier_fourth_bound(0.0, 0.0);
      break;
    case SegmentKind::HBezier:
      b = hbezier_fourth_bound(alpha_, lambda_, mu_);
      break;
    case SegmentKind::QuasiBSpline:
      b = quasi_bspline_fourth_bound(lambda_, mu_);
      break;
    case SegmentKind::Line:
      return 0.0;
    case SegmentKind::RationalBezier:
      return rational_fourth_bound(points_, rational_);
  }
  // The weights' fourth derivatives sum to zero, so r'''' = sum_j w_j'''' (P_j - P_0).
  double bound = 0.0;
  for (int j = 1; j < 4; ++j) bound += b[j] * (points_[j] - points_[0]).norm();
  return bound * std::pow(scale, 4);
}

}  // namespace fabmesh
