#pragma once
// Proven bounds of a segment's derivatives and curvature over parameter
// intervals, and the least curvature of a segment found by branch and bound
// (no sampling that could miss a minimum).
//
// On [a, b] with centre c and half-width h, Taylor's theorem with the
// segment's bound M4 >= |r''''| over [0, 1] gives, for every s in [a, b]:
//   |r'''(s)|         <= |r'''(c)| + h M4                               = B3
//   |r''(s)|          <= |r''(c)| + h |r'''(c)| + h^2/2 M4              = B2
//   |r'(s) - r'(c)|   <= h |r''(c)| + h^2/2 |r'''(c)| + h^3/6 M4        = E1
//   |r'(s)|           >= |r'(c)| - E1                                   = S
// The signed curvature k = (r' x r'') / |r'|^3 has the derivative
//   k' = (r' x r''') / |r'|^3 - 3 (r' x r'') (r' . r'') / |r'|^5,
// so |k'| <= B3 / S^2 + 3 B2^2 / S^3 = L on the interval, and
// k(s) >= k(c) - h L there: a lower bound that bisection tightens.

#include <cstddef>
#include <limits>

#include "geometry/curves/segment.h"

namespace fabmesh {

/// Bounds of the derivatives (d/ds) of a segment over [a, b] (see above).
struct JetBounds {
  CurveJet at_center;    ///< the jet at the interval's centre
  double half = 0.0;     ///< h
  double d2 = 0.0;       ///< B2 >= |r''|
  double d3 = 0.0;       ///< B3 >= |r'''|
  double min_speed = 0;  ///< S <= |r'| (may be <= 0: no bound)
};

/// The bounds above on [a, b] given M4 >= sup |r''''| over [0, 1].
JetBounds jet_bounds(const Segment& segment, double a, double b, double fourth_bound);

/// The least of sign * (signed curvature) over a segment's parameter range [0, 1].
struct CurvatureBound {
  double least = 0.0;     ///< proven lower bound of sign * k(s) over [0, 1] (may be -infinity)
  double attained = 0.0;  ///< sign * k(s) at s: a value the curve takes, >= least
  double s = 0.0;         ///< where `attained` is taken
};

/// Branch and bound (best first) on sign * k, k the signed curvature (positive
/// turning left along the segment's parameter); sign = -1 for travel against
/// the parameter. Lines: 0; circle arcs: exact; ellipse arcs: the analytic
/// extremes of their curvature; other families: the interval bound above,
/// refined until attained - least <= precision (> 0), or least >= good_enough
/// (the caller needs no more: every value is proven at least that), or
/// `budget` intervals have been evaluated (then `least` is the weaker bound).
CurvatureBound least_curvature(const Segment& segment, double sign, double precision,
                               double good_enough = std::numeric_limits<double>::infinity(),
                               std::size_t budget = 200000);

}  // namespace fabmesh
