#pragma once
// Strain (k = 2) and curvature-variation (k = 3) energies of a quasi-cubic
// uniform B-spline as quadratic functions of its interior local parameters
// (docs/math/curves.md 2.1), and their box-constrained minimisers.

#include <Eigen/Core>
#include <vector>

#include "geometry/core/types.h"

namespace fabmesh {

/// E(x) = x' Q x + 2 b' x + c, x = (lambda_1 .. lambda_{n-1}); Q is tridiagonal.
struct QuadraticEnergy {
  Eigen::MatrixXd q;
  Eigen::VectorXd b;
  double c = 0.0;
  double operator()(const Eigen::VectorXd& x) const { return x.dot(q * x) + 2.0 * b.dot(x) + c; }
};

/// E_k = sum over all n spans of integral_0^1 |r_i^(k)|^2 dt, integrated
/// exactly from the basis' monomial coefficients. `points` = p0..pn (n >= 2),
/// order k = 2 or 3. \throw GeometryError, RangeError
QuadraticEnergy quasi_bspline_energy(const std::vector<Vec2>& points, int order);

/// The same energy at given lambdas (size n - 1) by Gauss-Legendre
/// quadrature of the evaluated curve: an independent check of the closed form.
double quasi_bspline_energy_by_quadrature(const std::vector<Vec2>& points, const std::vector<double>& lambdas,
                                          int order);

struct FairestLambdas {
  std::vector<double> lambdas;  ///< lambda_1 .. lambda_{n-1}, each in [-8, 1]
  double energy = 0.0;
};

/// Minimises E_k over [-8, 1]^(n-1) exactly as a convex box QP.
FairestLambdas quasi_bspline_fairest(const std::vector<Vec2>& points, int order);

}  // namespace fabmesh
