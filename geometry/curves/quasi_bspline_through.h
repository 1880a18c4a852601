#pragma once
// A quasi-cubic B-spline that passes through given points (`through:` in a
// design): the control points p0..pn whose curve meets q0..qn at its joints,
// for given local parameters. docs/math/curves.md 2.3 has the system and
// when it can be solved.

#include <string>
#include <vector>

#include "geometry/core/types.h"

namespace fabmesh {

struct QuasiBSplineThrough {
  std::vector<Vec2> points;  ///< the control points p0..pn (p0 = q0, pn = qn)
  /// Largest distance from a through point to the curve's joint it is
  /// meant to be, computed exactly from the rounded control points and
  /// rounded up: a proven bound, not an estimate.
  double deviation = 0.0;
};

/// The control points of the quasi-cubic B-spline with local parameters
/// `lambdas` (lambda_1..lambda_{n-1}, each in [-8, 1]; empty: all 0) that
/// passes through `through` (q0..qn, n >= 2) at its joints. The tridiagonal
/// system is tested for singularity exactly (its determinant in integers)
/// and solved with partial pivoting, then refined against its exact residual.
/// \throw GeometryError at `key` when the system is singular (no such curve,
///        or not one), or so close to it that the solution misses a point by
///        more than 1e-9 of the points' extent; RangeError for a bad lambda.
QuasiBSplineThrough quasi_bspline_through(const std::vector<Vec2>& through,
                                          const std::vector<double>& lambdas, const std::string& key = {});

}  // namespace fabmesh
