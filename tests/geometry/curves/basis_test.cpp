#include "geometry/curves/basis.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <random>

using namespace fabmesh;

namespace {

double sum(const std::array<double, 4>& w) { return w[0] + w[1] + w[2] + w[3]; }

// Largest difference between a basis' analytic derivatives (orders 1..3)
// and central differences of the order below.
template <class F>
double max_derivative_mismatch(F basis, double t, double h) {
  const BasisJet plus = basis(t + h), minus = basis(t - h);
  const BasisJet at = basis(t);
  double worst = 0.0;
  for (int k = 1; k < 4; ++k) {
    for (int j = 0; j < 4; ++j) {
      const double fd = (plus[k - 1][j] - minus[k - 1][j]) / (2 * h);
      worst = std::max(worst, std::abs(at[k][j] - fd));
    }
  }
  return worst;
}

}  // namespace

TEST_CASE("tbezier basis: partition of unity and non-negativity on the parameter box", "[curves][tbezier]") {
  for (double lambda : {-2.0, -1.0, 0.0, 0.5, 1.0}) {
    for (double mu : {-2.0, -0.3, 0.0, 1.0}) {
      for (int i = 0; i <= 20; ++i) {
        const double t = i / 20.0;
        const BasisJet w = tbezier_basis(t, lambda, mu);
        CHECK(sum(w[0]) == Approx(1.0).margin(1e-15));
        for (int k = 1; k < 4; ++k) CHECK(sum(w[k]) == Approx(0.0).margin(1e-12));
        for (double b : w[0]) CHECK(b >= -1e-15);
      }
    }
  }
}

TEST_CASE("tbezier basis: analytic derivatives agree with differences", "[curves][tbezier]") {
  for (double t : {0.1, 0.37, 0.8}) {
    CHECK(max_derivative_mismatch([](double x) { return tbezier_basis(x, 0.7, -1.3); }, t, 1e-6) <= 1e-7);
  }
}

TEST_CASE("tbezier basis: fourth-derivative bound holds", "[curves][tbezier]") {
  const auto bound = tbezier_fourth_bound(-1.5, 0.8);
  for (int i = 0; i <= 200; ++i) {
    const double t = i / 200.0, h = 1e-4;
    const BasisJet p = tbezier_basis(t + h, -1.5, 0.8), m = tbezier_basis(t - h, -1.5, 0.8);
    for (int j = 0; j < 4; ++j) CHECK(std::abs((p[3][j] - m[3][j]) / (2 * h)) <= bound[j] * (1 + 1e-6));
  }
}

TEST_CASE("quasi-cubic B-spline basis: partition of unity for any local parameters",
          "[curves][quasi_bspline]") {
  for (double l : {-8.0, -2.0, 0.0, 1.0, 4.0}) {
    for (double m : {-8.0, 0.5, 4.0}) {
      for (int i = 0; i <= 10; ++i) {
        const BasisJet w = quasi_bspline_basis(i / 10.0, l, m);
        CHECK(sum(w[0]) == Approx(1.0).margin(1e-14));
        for (int k = 1; k < 4; ++k) CHECK(sum(w[k]) == Approx(0.0).margin(1e-12));
      }
      CHECK(max_derivative_mismatch([&](double x) { return quasi_bspline_basis(x, l, m); }, 0.4, 1e-5) <=
            1e-7);
    }
  }
}

TEST_CASE("hbezier basis: the test vectors of h-bezier.md", "[curves][hbezier]") {
  const BasisJet a = hbezier_basis(0.5, 1.0, 0.0, 0.0);
  CHECK(a[0][0] == Approx(0.120406174496).epsilon(1e-11));
  CHECK(a[0][1] == Approx(0.379593825504).epsilon(1e-11));
  CHECK(a[0][2] == Approx(0.379593825504).epsilon(1e-11));
  CHECK(a[0][3] == Approx(0.120406174496).epsilon(1e-11));
  const BasisJet b = hbezier_basis(1.0, 2.0, 1.0, 1.0);
  CHECK(b[0][0] == Approx(0.0565217506727).epsilon(1e-11));
  CHECK(b[0][1] == Approx(0.443478249327).epsilon(1e-11));
  CHECK(b[0][2] == Approx(0.443478249327).epsilon(1e-11));
  CHECK(b[0][3] == Approx(0.0565217506727).epsilon(1e-11));

  const HBezierEndConstants e = hbezier_end_constants(1.0, 0.0, 0.0);
  CHECK(e.a0 == Approx(3.09975419414).epsilon(1e-11));
  CHECK(e.a1 == Approx(3.09975419414).epsilon(1e-11));
  CHECK(e.b0 == Approx(6.70772367015).epsilon(1e-11));
  CHECK(e.b1 == Approx(6.70772367015).epsilon(1e-11));
  CHECK(e.e == Approx(6.09929355661).epsilon(1e-11));
}

TEST_CASE("hbezier basis: partition of unity, symmetry and endpoint constants", "[curves][hbezier]") {
  for (double alpha : {1e-3, 0.05, 0.7, 1.0, 2.5, 9.0}) {
    for (double lambda : {-2.5, 0.0, 0.6}) {
      for (double mu : {-1.0, 0.3, 1.0}) {
        for (int i = 0; i <= 10; ++i) {
          const double u = alpha * i / 10.0;
          const BasisJet w = hbezier_basis(u, alpha, lambda, mu);
          const BasisJet mirrored = hbezier_basis(alpha - u, alpha, mu, lambda);
          CHECK(sum(w[0]) == Approx(1.0).margin(1e-12));
          for (int j = 0; j < 4; ++j) CHECK(w[0][j] == Approx(mirrored[0][3 - j]).margin(1e-12));
        }
        const HBezierEndConstants c = hbezier_end_constants(alpha, lambda, mu);
        const BasisJet w0 = hbezier_basis(0.0, alpha, lambda, mu);
        const BasisJet w1 = hbezier_basis(alpha, alpha, lambda, mu);
        const double scale = 1.0 / alpha, scale2 = scale * scale;  // compare in t = u / alpha units
        CHECK(w0[0][0] == Approx(1.0).margin(1e-12));
        CHECK(w1[0][3] == Approx(1.0).margin(1e-12));
        CHECK(w0[1][1] * scale == Approx(c.a0 * scale).epsilon(1e-9));
        CHECK(w1[1][3] * scale == Approx(c.a1 * scale).epsilon(1e-9));
        CHECK(w0[2][0] * scale2 == Approx(c.b0 * scale2).epsilon(1e-8));
        CHECK(w0[2][2] * scale2 == Approx(c.e * scale2).epsilon(1e-8));
        CHECK(w1[2][3] * scale2 == Approx(c.b1 * scale2).epsilon(1e-8));
      }
    }
  }
}

TEST_CASE("hbezier basis: tends to the polynomial limit as alpha -> 0", "[curves][hbezier]") {
  const double lambda = 0.4, mu = -1.2, alpha = 1e-3;
  for (int i = 0; i <= 10; ++i) {
    const double t = i / 10.0, s = 1 - t;
    const BasisJet w = hbezier_basis(alpha * t, alpha, lambda, mu);
    const std::array<double, 4> limit{s * s * s * (1 - lambda * t), t * s * s * (3 + lambda - lambda * t),
                                      t * t * s * (3 + mu * t), t * t * t * (1 - mu + mu * t)};
    // The limit is reached up to O(alpha^2); accuracy itself is far better.
    for (int j = 0; j < 4; ++j) CHECK(w[0][j] == Approx(limit[j]).margin(1e-6));
  }
}

TEST_CASE("hbezier basis: series and direct evaluation agree across the switch", "[curves][hbezier]") {
  // alpha just below and above 1 use different formulas for H1, H2: the basis must be continuous.
  for (double t : {0.1, 0.5, 0.9}) {
    const BasisJet lo = hbezier_basis(t * (1 - 1e-12), 1 - 1e-12, 0.3, 0.2);
    const BasisJet hi = hbezier_basis(t, 1.0, 0.3, 0.2);
    for (int k = 0; k < 4; ++k) {
      for (int j = 0; j < 4; ++j) CHECK(lo[k][j] == Approx(hi[k][j]).margin(1e-10));
    }
  }
  CHECK(max_derivative_mismatch([](double u) { return hbezier_basis(u, 0.5, 0.3, -0.7); }, 0.2, 1e-6) <=
        1e-5);
  CHECK(max_derivative_mismatch([](double u) { return hbezier_basis(u, 3.0, 0.3, -0.7); }, 1.2, 1e-6) <=
        1e-5);
}

TEST_CASE("hbezier: lambda lower bound values", "[curves][hbezier]") {
  CHECK(hbezier_lambda_min(1e-3) == Approx(-3.0).margin(1e-4));
  CHECK(hbezier_lambda_min(1.0) == Approx(-3.2053).margin(1e-4));
  CHECK(hbezier_lambda_min(2.0) == Approx(-3.8891).margin(1e-4));
  CHECK(hbezier_lambda_min(3.0) == Approx(-5.2879).margin(1e-4));
}
