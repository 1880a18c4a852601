#pragma once
// Plane curves of the three families fabmesh builds with (docs/math/):
// evaluated exactly, sampled within a proven bound.

#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace fabmesh {
namespace api {

using Point2 = std::array<double, 2>;

/// A polyline that stays within `max_deviation` of the exact curve (both ways).
struct SampledCurve {
  std::vector<Point2> points;
  bool closed = false;
  double max_deviation = 0.0;  ///< proven, model units
};

/// How smoothly two segments meet: G0 (they touch), G1 (tangents agree), G2
/// (curvatures agree too); None: they do not even touch.
enum class Continuity { None = -1, G0 = 0, G1 = 1, G2 = 2 };

/// One joint of a composite, as measured on the exact curve.
struct Joint {
  std::size_t before = 0;                                ///< the segment that ends at the joint
  std::size_t after = 0;                                 ///< the segment that starts there
  bool closing = false;                                  ///< the joint that closes a closed curve
  double gap = 0.0;                                      ///< distance between the two ends, model units
  double tangent_angle = 0.0;                            ///< angle between the end tangents, radians
  double curvature_before = 0.0, curvature_after = 0.0;  ///< signed, 1 / model units
  double curvature_jump = 0.0;             ///< |k1 - k2| / max(|k1|, |k2|, 1 / the curve's extent)
  Continuity declared = Continuity::G0;    ///< what the segments asked for (joins, `continuity`)
  Continuity achieved = Continuity::None;  ///< what the numbers show
};

/// The energy a fairing minimises (docs/math/curves.md): the strain energy
/// (the integral of the squared second derivative) or the curvature-variation
/// energy (of the squared third derivative).
enum class Energy { Strain, CurvatureVariation };

/// What fairing did to a curve.
struct Fairing {
  Energy energy = Energy::CurvatureVariation;
  double energy_before = 0.0;  ///< the energy of the curve as given
  double energy_after = 0.0;   ///< the energy of the faired curve (never larger)
};

/// A quasi-cubic B-spline made to pass through given points
/// (quasi_bspline_through, or a design's `through:`).
struct Through {
  std::vector<Point2> points;          ///< q0..qn, the points it passes through at its joints
  std::vector<Point2> control_points;  ///< p0..pn solved from them (p0 = q0, pn = qn)
  /// Proven: no q_i is farther than this from its joint of the curve the
  /// control points make, model units (of the order of 1e-16 of the size).
  double deviation = 0.0;
};

namespace detail {
struct CurveData;
}

/// A composite curve of n segments with parameter t in [0, n]: segment
/// floor(t) at its own parameter t - floor(t) (the last segment takes t = n).
/// Immutable; safe to use from several threads at once.
class Curve {
 public:
  std::size_t segments() const;
  bool closed() const;
  /// The point at t. \throw InputError ("t") outside [0, segments()] or not finite
  Point2 point(double t) const;
  /// The derivative of order 1, 2 or 3 with respect to t at t (within a
  /// segment; at a joint, the later segment's). \throw InputError ("order", "t")
  Point2 derivative(double t, int order = 1) const;
  /// Signed curvature at t (positive turning left), 1 / model units. \throw InputError ("t")
  double curvature(double t) const;
  /// Samples the curve so that the polyline stays within `tolerance` of it,
  /// with the proven bound achieved. \throw InputError ("tolerance") for a
  /// tolerance that is not > 0 or needs more points than the budget
  SampledCurve sample(double tolerance) const;
  /// Every joint between consecutive segments (and the closing one of a
  /// closed curve), measured on the exact curve.
  std::vector<Joint> joints() const;
  /// What fairing did, for a curve made by fair(); empty otherwise.
  std::optional<Fairing> fairing() const;
  /// The points a curve made to pass through them passes through, and its
  /// solved control points; empty for any other curve.
  std::optional<Through> through() const;

  /// For the library's own implementation.
  const detail::CurveData& data() const { return *data_; }
  explicit Curve(std::shared_ptr<const detail::CurveData> data) : data_(std::move(data)) {}

 private:
  std::shared_ptr<const detail::CurveData> data_;
};

/// Cubic T-Bézier segments through `points` (3n + 1 control points, n >= 1:
/// segment i takes points 3i .. 3i + 3), shape parameters lambda, mu in [-2, 1].
/// \throw InputError ("points", "lambda", "mu")
Curve tbezier(const std::vector<Point2>& points, double lambda = 0.0, double mu = 0.0);

/// A quasi-cubic B-spline with control points p0..pn (n >= 2) and shape
/// parameters lambda_1..lambda_{n-1} in [-8, 1] (empty: all 0).
/// \throw InputError ("points", "lambdas")
Curve quasi_bspline(const std::vector<Point2>& points, const std::vector<double>& lambdas = {});

/// The quasi-cubic B-spline that passes through `through` (q0..qn, n >= 2):
/// q0 at its start, qn at its end, q_i at joint i, for the shape parameters
/// lambda_1..lambda_{n-1} in [-8, 1] (empty: all 0). Its control points are
/// solved from a tridiagonal system whose singularity is decided exactly
/// (docs/math/curves.md 2.3); Curve::through() gives them and the proven
/// deviation. Always solvable when every lambda is -2 or more.
/// \throw InputError ("through": fewer than 3 points, a point not finite, a
/// singular system; "lambdas": a count other than n - 1, a value out of range)
Curve quasi_bspline_through(const std::vector<Point2>& through, const std::vector<double>& lambdas = {});

/// Generalized cubic H-Bézier segments through `points` (3n + 1 control
/// points), alpha in (0, 10], lambda and mu as docs/math/h-bezier.md allows.
/// \throw InputError ("points", "alpha", "lambda", "mu")
Curve hbezier(const std::vector<Point2>& points, double alpha = 1.0, double lambda = 0.0, double mu = 0.0);

/// The family of a composite's segment.
enum class SegmentFamily { TBezier, HBezier, Line };

/// How a segment's leading control points follow from the previous segment
/// (docs/design-files.md, "Composite curves"). A T-Bézier segment uses alpha
/// and beta: r1'(1) = alpha r2'(0), r1''(1) = alpha^2 r2''(0) + beta r2'(0);
/// an H-Bézier segment uses k and m: Q'(0) = k P'(end),
/// Q''(0) = k^2 P''(end) + m P'(end). G0 computes the first control point, G1
/// the first two, G2 the first three.
struct Join {
  Continuity continuity = Continuity::G1;
  double alpha = 1.0;  ///< > 0, T-Bézier
  double beta = 0.0;   ///< T-Bézier, G2
  double k = 1.0;      ///< > 0, H-Bézier
  double m = 0.0;      ///< H-Bézier, G2
};

/// One segment of a composite, as a design file's segment says it.
struct Segment {
  SegmentFamily family = SegmentFamily::TBezier;
  /// A cubic: its 4 control points, or after a join only the free ones (G0:
  /// 3, G1: 2, G2: 1). A line: {from, to} when it is the first segment, else
  /// {to} (it starts where the previous segment ends).
  std::vector<Point2> points;
  double lambda = 0.0;       ///< T-Bézier in [-2, 1]; H-Bézier in (lambda*(alpha), 1]
  double mu = 0.0;           ///< the same range as lambda
  double alpha = 1.0;        ///< H-Bézier: the hyperbolic parameter, in (0, 10]
  std::optional<Join> join;  ///< cubics after the first: build the leading points
  /// Without a join: the continuity this segment declares with the previous
  /// one, verified on the exact curve.
  Continuity continuity = Continuity::G0;
};

/// A composite of segments of any of the families, each starting where the
/// previous one ends. A closed composite must end where it starts; a join on
/// its first segment joins it to the last (the points are then solved for
/// exactly), and `closing` is the continuity declared for the closing joint
/// otherwise. Declared continuity is verified on the exact curve.
/// \throw InputError ("segments[i].points", "segments[i].lambda", ...,
/// "segments": a declared continuity the curve does not have)
Curve composite(const std::vector<Segment>& segments, bool closed = false,
                Continuity closing = Continuity::G0);

/// The curve with the shape parameters that minimise `energy`, every control
/// point kept where it is: a quasi-cubic B-spline's lambdas (strain or
/// curvature variation), or each T-Bézier segment's lambda and mu (curvature
/// variation; other segments stay). A joint may not fall below its declared
/// continuity, or below `keeps` when given.
/// \throw InputError ("energy": an energy the curve's family has no fairing
/// for, such as an H-Bézier curve or strain on T-Bézier segments; "curve": a
/// curve made to pass through points, which fairing would move off them;
/// "keeps": a joint that fairing lowers below its declared continuity)
Curve fair(const Curve& curve, Energy energy = Energy::CurvatureVariation,
           std::optional<Continuity> keeps = std::nullopt);

}  // namespace api
#ifndef FABMESH_BUILDING_LIBRARY
using namespace api;  // fabmesh::Design, fabmesh::build, ...
#endif
}  // namespace fabmesh
