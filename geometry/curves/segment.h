#pragma once
// One piece of a composite curve: a basis of one family and its control
// points. Every segment is parameterised by s in [0, 1]; its native parameter
// (T-Bézier t, H-Bézier u, ellipse angle-parameter t) is an affine function of s.
// A rational cubic Bézier segment also carries one positive weight per point.

#include <array>
#include <optional>

#include "geometry/core/types.h"
#include "geometry/curves/basis.h"

namespace fabmesh {

enum class SegmentKind { TBezier, EllipseArc, Line, HBezier, QuasiBSpline, RationalBezier };

/// Name of a kind as used in design files ("tbezier", "ellipse_arc", ...).
const char* to_string(SegmentKind kind);

/// An exact elliptic arc: centre, semi-axes a (along the rotated x axis) and b,
/// rotation of the axes and the central angles (degrees) from -> to; to < from
/// runs clockwise. |to - from| <= 360.
struct EllipseArcParams {
  Vec2 center{0.0, 0.0};
  double a = 1.0;
  double b = 1.0;
  double rotation_deg = 0.0;
  double from_deg = 0.0;
  double to_deg = 360.0;
};

/// Position and derivatives d^k r / ds^k, k = 0..3.
using CurveJet = std::array<Vec2, 4>;

class Segment {
 public:
  /// Cubic T-Bézier with lambda, mu in [-2, 1]. \throw RangeError
  static Segment tbezier(const std::array<Vec2, 4>& points, double lambda, double mu);
  /// Generalized cubic H-Bézier: alpha in (0, 10], lambda, mu in (lambda*(alpha), 1]. \throw RangeError
  static Segment hbezier(const std::array<Vec2, 4>& points, double alpha, double lambda, double mu);
  /// Straight segment from -> to (distinct points). \throw GeometryError
  static Segment line(const Vec2& from, const Vec2& to);
  /// Exact elliptic arc through the T-Bézier form of docs/math/curves.md 1.2. \throw RangeError
  static Segment ellipse_arc(const EllipseArcParams& params);
  /// One span of a quasi-cubic B-spline: points p(i-1)..p(i+2), l = lambda_i,
  /// m = lambda_{i+1}, each in [-8, 1] or exactly 4 at the curve's ends. \throw RangeError
  static Segment quasi_bspline_span(const std::array<Vec2, 4>& points, double l, double m);
  /// Rational cubic Bézier (a span of a NURBS curve, docs/math/curves.md 5):
  /// r(s) = sum w_j P_j B_j(s) / sum w_j B_j(s), B_j the cubic Bernstein
  /// polynomials, every weight finite and > 0. \throw RangeError
  static Segment rational_bezier(const std::array<Vec2, 4>& points, const std::array<double, 4>& weights);

  SegmentKind kind() const { return kind_; }
  /// Number of control points used (2 for a line, else 4).
  int control_count() const { return kind_ == SegmentKind::Line ? 2 : 4; }
  const std::array<Vec2, 4>& control_points() const { return points_; }
  double lambda() const { return lambda_; }
  double mu() const { return mu_; }
  double alpha() const { return alpha_; }
  /// The points' weights when kind() == RationalBezier; all 1 for the other kinds.
  const std::array<double, 4>& rational_weights() const { return rational_; }
  /// The ellipse parameters when kind() == EllipseArc.
  const std::optional<EllipseArcParams>& ellipse() const { return ellipse_; }

  /// The same control points with other shape parameters (range checked).
  Segment with_shape(double lambda, double mu) const;
  /// The same basis with other control points.
  Segment with_points(const std::array<Vec2, 4>& points) const;

  /// Control-point weights at s for derivative orders 0..3 (d/ds). For a
  /// rational segment these are the rational basis R_j = w_j B_j / sum w_i B_i
  /// and its derivatives: the curve stays linear in its control points.
  BasisJet weights(double s) const;
  /// Point and derivatives at s in [0, 1].
  CurveJet jet(double s) const;
  Vec2 point(double s) const;
  /// Signed curvature at s (positive turning left).
  double curvature(double s) const;
  /// d(native parameter)/ds: derivatives in the native parameter are d/ds divided by its powers.
  double native_scale() const;
  /// Upper bound of |d^4 r / ds^4| over [0, 1], from the basis and the control points.
  double fourth_derivative_bound() const;

 private:
  SegmentKind kind_ = SegmentKind::Line;
  std::array<Vec2, 4> points_{};
  double lambda_ = 0.0, mu_ = 0.0, alpha_ = 1.0;
  double t0_ = 0.0, t1_ = 1.0;  // native range for T-Bézier forms (ellipse arcs)
  Vec2 origin_{0.0, 0.0};       // ellipse arcs: points_ are in the arc's frame
  double cos_ = 1.0, sin_ = 0.0;
  std::optional<EllipseArcParams> ellipse_;
  std::array<double, 4> rational_{1.0, 1.0, 1.0, 1.0};  // rational Bézier: the points' weights
  HBezierConstants hbezier_{};  ///< hbezier_constants(alpha_) for H-Bézier segments, computed once
};

}  // namespace fabmesh
