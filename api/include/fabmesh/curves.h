#pragma once
// Plane curves of the three families fabmesh builds with (docs/math/):
// evaluated exactly, sampled within a proven bound.

#include <array>
#include <cstddef>
#include <memory>
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

/// Generalized cubic H-Bézier segments through `points` (3n + 1 control
/// points), alpha in (0, 10], lambda and mu as docs/math/h-bezier.md allows.
/// \throw InputError ("points", "alpha", "lambda", "mu")
Curve hbezier(const std::vector<Point2>& points, double alpha = 1.0, double lambda = 0.0, double mu = 0.0);

}  // namespace api
#ifndef FABMESH_BUILDING_LIBRARY
using namespace api;  // fabmesh::Design, fabmesh::build, ...
#endif
}  // namespace fabmesh
