#include <cmath>

#include "geometry/curves/basis.h"

namespace fabmesh {
namespace {

using Poly = std::array<double, 5>;  // coefficients of t^0..t^4

// u^a t^b with u = 1 - t, a + b <= 4, expanded in powers of t.
Poly monomial(int a, int b) {
  Poly p{};
  double binom = 1.0;  // C(a, i)
  for (int i = 0; i <= a; ++i) {
    p[i + b] += ((i % 2 == 0) ? 1.0 : -1.0) * binom;
    binom = binom * (a - i) / (i + 1);
  }
  return p;
}

void add(Poly& target, double factor, const Poly& p) {
  for (int i = 0; i < 5; ++i) target[i] += factor * p[i];
}

}  // namespace

std::array<std::array<double, 5>, 4> quasi_bspline_coefficients(double l, double m) {
  const Poly u4 = monomial(4, 0), u3t = monomial(3, 1), u2t2 = monomial(2, 2), ut3 = monomial(1, 3),
             t4 = monomial(0, 4);
  std::array<Poly, 4> b{};
  add(b[0], 4.0 - l, u4);
  add(b[0], 4.0 * (1.0 - l), u3t);
  add(b[1], 2.0 * (8.0 + l), u4);
  add(b[1], 8.0 * (8.0 + l), u3t);
  add(b[1], 72.0, u2t2);
  add(b[1], 4.0 * (7.0 - m), ut3);
  add(b[1], 4.0 - m, t4);
  add(b[2], 4.0 - l, u4);
  add(b[2], 4.0 * (7.0 - l), u3t);
  add(b[2], 72.0, u2t2);
  add(b[2], 8.0 * (8.0 + m), ut3);
  add(b[2], 2.0 * (8.0 + m), t4);
  add(b[3], 4.0 * (1.0 - m), ut3);
  add(b[3], 4.0 - m, t4);
  for (auto& p : b) {
    for (double& c : p) c /= 24.0;
  }
  return b;
}

BasisJet quasi_bspline_basis(double t, double l, double m) {
  const auto coef = quasi_bspline_coefficients(l, m);
  BasisJet jet{};
  for (int j = 0; j < 4; ++j) {
    const auto& c = coef[j];
    jet[0][j] = c[0] + t * (c[1] + t * (c[2] + t * (c[3] + t * c[4])));
    jet[1][j] = c[1] + t * (2.0 * c[2] + t * (3.0 * c[3] + t * 4.0 * c[4]));
    jet[2][j] = 2.0 * c[2] + t * (6.0 * c[3] + t * 12.0 * c[4]);
    jet[3][j] = 6.0 * c[3] + t * 24.0 * c[4];
  }
  return jet;
}

std::array<double, 4> quasi_bspline_fourth_bound(double l, double m) {
  const auto coef = quasi_bspline_coefficients(l, m);
  return {24.0 * std::abs(coef[0][4]), 24.0 * std::abs(coef[1][4]), 24.0 * std::abs(coef[2][4]),
          24.0 * std::abs(coef[3][4])};
}

}  // namespace fabmesh
