#include <cmath>

#include "geometry/curves/basis.h"

namespace fabmesh {
namespace {

constexpr double kHalfPi = M_PI / 2.0;

// f(x(t)) for a cubic polynomial f with coefficients q (in x), where x(t)
// has derivatives x1, x2, x3: value and first three derivatives (Faa di Bruno).
std::array<double, 4> compose(const std::array<double, 4>& q, double x, double x1, double x2, double x3) {
  const double f0 = q[0] + x * (q[1] + x * (q[2] + x * q[3]));
  const double f1 = q[1] + x * (2.0 * q[2] + 3.0 * x * q[3]);
  const double f2 = 2.0 * q[2] + 6.0 * x * q[3];
  const double f3 = 6.0 * q[3];
  return {f0, f1 * x1, f2 * x1 * x1 + f1 * x2, f3 * x1 * x1 * x1 + 3.0 * f2 * x1 * x2 + f1 * x3};
}

// b0 = (1-x)^2 (1 - p x) and b1 = x (1-x)(2 + p - p x) as cubics in x.
std::array<double, 4> outer_coefficients(double p) { return {1.0, -(2.0 + p), 1.0 + 2.0 * p, -p}; }
std::array<double, 4> inner_coefficients(double p) { return {0.0, 2.0 + p, -(2.0 + 2.0 * p), p}; }

double fourth_bound(const std::array<double, 4>& q) {
  // A product of k factors sin/cos(w t) has |d^4/dt^4| <= (k w)^4 (Leibniz).
  double bound = 0.0;
  for (int k = 1; k <= 3; ++k) bound += std::abs(q[k]) * std::pow(k * kHalfPi, 4);
  return bound;
}

}  // namespace

BasisJet tbezier_basis(double t, double lambda, double mu) {
  const double w = kHalfPi;
  const double s = std::sin(w * t);
  const double c = std::cos(w * t);
  // s' = w c, s'' = -w^2 s, s''' = -w^3 c;  c' = -w s, c'' = -w^2 c, c''' = w^3 s
  const auto b0 = compose(outer_coefficients(lambda), s, w * c, -w * w * s, -w * w * w * c);
  const auto b1 = compose(inner_coefficients(lambda), s, w * c, -w * w * s, -w * w * w * c);
  const auto b2 = compose(inner_coefficients(mu), c, -w * s, -w * w * c, w * w * w * s);
  const auto b3 = compose(outer_coefficients(mu), c, -w * s, -w * w * c, w * w * w * s);
  BasisJet jet{};
  for (int k = 0; k < 4; ++k) jet[k] = {b0[k], b1[k], b2[k], b3[k]};
  return jet;
}

std::array<double, 4> tbezier_fourth_bound(double lambda, double mu) {
  return {fourth_bound(outer_coefficients(lambda)), fourth_bound(inner_coefficients(lambda)),
          fourth_bound(inner_coefficients(mu)), fourth_bound(outer_coefficients(mu))};
}

}  // namespace fabmesh
