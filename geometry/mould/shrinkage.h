#pragma once
// Clay shrinkage: a piece is modelled at its fired size and made larger (the
// master and the mould cavity) so that it shrinks to that size in the kiln.

#include "geometry/curves/composite.h"

namespace fabmesh {

/// The scale from fired to wet (master) size for a linear shrinkage s:
/// 1 / (1 - s), so that master * (1 - s) = fired. s = 0.12 gives 1.1364.
/// \throw RangeError unless 0 <= s < 1 (and finite).
double shrinkage_factor(double shrinkage);

/// `curve` scaled about the origin by `factor` (> 0). Exact for every family:
/// each basis sums to one (docs/math/curves.md), so scaling the control points scales
/// every point of the curve; ellipse arcs get a scaled centre and semi-axes.
/// Shape parameters (lambda, mu, alpha) are unchanged.
/// \throw RangeError for factor <= 0 or not finite.
CompositeCurve scale_curve(const CompositeCurve& curve, double factor);

}  // namespace fabmesh
