#pragma once
// Scalar basis functions of the curve families (docs/math/curves.md, docs/math/h-bezier.md),
// with analytic derivatives. A basis maps a parameter to four weights per
// derivative order; a curve point is the weighted sum of its control points.

#include <array>

namespace fabmesh {

/// Weights of the four control points: w[k][j] = d^k b_j / dt^k, k = 0..3.
using BasisJet = std::array<std::array<double, 4>, 4>;

/// Cubic T-Bézier basis (docs/math/curves.md 1), t in R (periodic extension is exact
/// for ellipses), shape parameters lambda, mu (range checked by callers).
BasisJet tbezier_basis(double t, double lambda, double mu);

/// Upper bound, for all t, of |d^4 b_j / dt^4| for each j (T-Bézier).
std::array<double, 4> tbezier_fourth_bound(double lambda, double mu);

/// Quasi-cubic uniform B-spline span basis (docs/math/curves.md 2), t in [0,1], with
/// l = lambda_i and m = lambda_{i+1}.
BasisJet quasi_bspline_basis(double t, double l, double m);

/// Monomial coefficients c[j][p] of b_{i,j}(t) = sum_p c[j][p] t^p (degree 4).
std::array<std::array<double, 5>, 4> quasi_bspline_coefficients(double l, double m);

/// Exact sup over [0,1] of |d^4 b_j / dt^4| (a constant: degree-4 polynomials).
std::array<double, 4> quasi_bspline_fourth_bound(double l, double m);

/// Generalized cubic H-Bézier basis (docs/math/h-bezier.md) at u in [0, alpha], derivatives
/// with respect to u. Accurate to about 1e-12 down to alpha = 1e-3 (series
/// evaluation of the cancelling differences).
BasisJet hbezier_basis(double u, double alpha, double lambda, double mu);

struct HBezierConstants;

/// The same with the constants of `alpha` computed once by the caller
/// (hbezier_constants(alpha)): they cost more than the basis itself.
BasisJet hbezier_basis(double u, double alpha, double lambda, double mu, const HBezierConstants& constants);

/// Upper bound, for u in [0, alpha], of |d^4 h_j / du^4| for each j.
std::array<double, 4> hbezier_fourth_bound(double alpha, double lambda, double mu);

/// The H-Bézier constants S, C, D, E of docs/math/h-bezier.md, computed without cancellation.
struct HBezierConstants {
  double s, c, d, e;
};
HBezierConstants hbezier_constants(double alpha);

/// Endpoint constants of docs/math/h-bezier.md: P'(0) = a0 (P1-P0), P'(alpha) = a1 (P3-P2),
/// P''(0) = b0 (P0-P1) + e (P2-P1), P''(alpha) = b1 (P3-P2) + e (P1-P2).
struct HBezierEndConstants {
  double a0, a1, b0, b1, e;
};
HBezierEndConstants hbezier_end_constants(double alpha, double lambda, double mu);

/// Lower bound lambda*(alpha) of the shape parameters for a non-negative basis.
double hbezier_lambda_min(double alpha);

/// sinh x - x, cosh x - 1 and cosh x - 1 - x^2/2 without cancellation near 0.
double sinh_minus_x(double x);
double cosh_minus_1(double x);
double cosh_minus_1_minus_half_x2(double x);

}  // namespace fabmesh
