#pragma once
// Curvature-variation energy of a cubic T-Bézier segment (docs/math/curves.md 1.3) and
// its fairest shape parameters.

#include <array>

#include "geometry/core/types.h"

namespace fabmesh {

/// E(lambda, mu) = integral_0^1 |r'''|^2 dt
///               = a0 l^2 + a1 m^2 + 2 a2 l m + 2 a3 l + 2 a4 m + c.
struct TBezierEnergy {
  double a0 = 0, a1 = 0, a2 = 0, a3 = 0, a4 = 0, c = 0;
  double operator()(double lambda, double mu) const {
    return a0 * lambda * lambda + a1 * mu * mu + 2 * a2 * lambda * mu + 2 * a3 * lambda + 2 * a4 * mu + c;
  }
};

/// The closed form of docs/math/curves.md 1.3 for control points P0..P3 (2D). The
/// constant c is E(0, 0), integrated by 32-point Gauss-Legendre (exact to
/// rounding for this trigonometric polynomial).
TBezierEnergy tbezier_curvature_variation_energy(const std::array<Vec2, 4>& points);

struct FairestShape {
  double lambda = 0.0;
  double mu = 0.0;
  double energy = 0.0;
};

/// Minimises the energy over the box [-2, 1]^2 exactly: the interior
/// stationary point when it is inside, else the best of the four edges'
/// exact one-dimensional minima (corners included).
FairestShape tbezier_fairest(const TBezierEnergy& energy);

}  // namespace fabmesh
