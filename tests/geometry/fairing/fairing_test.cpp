#include <catch2/catch.hpp>
#include <random>

#include "geometry/curves/basis.h"
#include "geometry/fairing/box_qp.h"
#include "geometry/fairing/gauss_legendre.h"
#include "geometry/fairing/quasi_bspline_energy.h"
#include "geometry/fairing/tbezier_energy.h"

using namespace fabmesh;

namespace {

double tbezier_energy_by_quadrature(const std::array<Vec2, 4>& p, double l, double m) {
  const QuadratureRule rule = gauss_legendre(48);
  double e = 0.0;
  for (std::size_t i = 0; i < rule.nodes.size(); ++i) {
    const BasisJet w = tbezier_basis(rule.nodes[i], l, m);
    Vec2 r3 = Vec2::Zero();
    for (int j = 0; j < 4; ++j) r3 += w[3][j] * p[j];
    e += rule.weights[i] * r3.squaredNorm();
  }
  return e;
}

std::array<Vec2, 4> random_points(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-5, 5);
  return {Vec2(u(rng), u(rng)), Vec2(u(rng), u(rng)), Vec2(u(rng), u(rng)), Vec2(u(rng), u(rng))};
}

}  // namespace

TEST_CASE("gauss-legendre: integrates polynomials of degree 2n-1 exactly", "[fairing]") {
  const QuadratureRule r = gauss_legendre(5);
  for (int d = 0; d <= 9; ++d) {
    double s = 0.0;
    for (std::size_t i = 0; i < r.nodes.size(); ++i) s += r.weights[i] * std::pow(r.nodes[i], d);
    CHECK(s == Approx(1.0 / (d + 1)).epsilon(1e-14));
  }
}

TEST_CASE("tbezier curvature-variation energy: closed form equals quadrature on random data",
          "[fairing][tbezier]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> shape(-2, 1);
  for (int trial = 0; trial < 50; ++trial) {
    const auto p = random_points(rng);
    const double l = shape(rng), m = shape(rng);
    const TBezierEnergy e = tbezier_curvature_variation_energy(p);
    CHECK(e(l, m) == Approx(tbezier_energy_by_quadrature(p, l, m)).epsilon(1e-10));
  }
}

TEST_CASE("tbezier fairest: the exact box optimum, never worse than a clamp or a grid",
          "[fairing][tbezier]") {
  std::mt19937 rng(11);
  int strictly_better_than_clamp = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const auto p = random_points(rng);
    const TBezierEnergy e = tbezier_curvature_variation_energy(p);
    const FairestShape f = tbezier_fairest(e);
    REQUIRE(f.lambda >= -2.0);
    REQUIRE(f.lambda <= 1.0);
    REQUIRE(f.mu >= -2.0);
    REQUIRE(f.mu <= 1.0);
    CHECK(f.energy == Approx(e(f.lambda, f.mu)));
    // Grid search cannot beat the exact optimum.
    double grid = INFINITY;
    for (int i = 0; i <= 150; ++i) {
      for (int j = 0; j <= 150; ++j) grid = std::min(grid, e(-2 + 3.0 * i / 150, -2 + 3.0 * j / 150));
    }
    CHECK(f.energy <= grid + 1e-9 * std::abs(grid));
    // Clamping the unconstrained optimum is what the spec forbids; it is sometimes worse.
    const double det = e.a0 * e.a1 - e.a2 * e.a2;
    const double l = std::clamp((e.a2 * e.a4 - e.a1 * e.a3) / det, -2.0, 1.0);
    const double m = std::clamp((e.a2 * e.a3 - e.a0 * e.a4) / det, -2.0, 1.0);
    CHECK(f.energy <= e(l, m) + 1e-12 * std::abs(e(l, m)));
    if (f.energy < e(l, m) * (1 - 1e-9)) ++strictly_better_than_clamp;
  }
  CHECK(strictly_better_than_clamp > 0);
}

TEST_CASE("quasi-cubic B-spline energies: closed form equals quadrature on random data",
          "[fairing][quasi_bspline]") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-4, 4), lam(-8, 1);
  for (int trial = 0; trial < 20; ++trial) {
    const int n = 2 + trial % 6;
    std::vector<Vec2> pts;
    for (int i = 0; i <= n; ++i) pts.emplace_back(u(rng), u(rng));
    std::vector<double> lambdas;
    Eigen::VectorXd x(n - 1);
    for (int i = 0; i < n - 1; ++i) lambdas.push_back(x[i] = lam(rng));
    for (int k : {2, 3}) {
      const QuadraticEnergy e = quasi_bspline_energy(pts, k);
      CHECK(e(x) == Approx(quasi_bspline_energy_by_quadrature(pts, lambdas, k)).epsilon(1e-10));
      // Banded: only neighbouring lambdas interact.
      for (int i = 0; i < n - 1; ++i) {
        for (int j = 0; j < n - 1; ++j) {
          if (std::abs(i - j) > 1) CHECK(e.q(i, j) == 0.0);
        }
      }
    }
  }
}

TEST_CASE("quasi-cubic B-spline fairing reproduces Example 4 of curves.md", "[fairing][quasi_bspline]") {
  const std::vector<Vec2> pts{{1.5, 6}, {0, 4.5}, {2, 4}, {3, 3}, {1.5, 2}};
  const FairestLambdas strain = quasi_bspline_fairest(pts, 2);
  REQUIRE(strain.lambdas.size() == 3);
  CHECK(strain.lambdas[0] == Approx(-1.9492).margin(5e-5));
  CHECK(strain.lambdas[1] == Approx(-1.6598).margin(5e-5));
  CHECK(strain.lambdas[2] == Approx(-1.7580).margin(5e-5));
  const FairestLambdas cv = quasi_bspline_fairest(pts, 3);
  CHECK(cv.lambdas[0] == Approx(-0.2765).margin(5e-5));
  CHECK(cv.lambdas[1] == Approx(-1.1013).margin(5e-5));
  CHECK(cv.lambdas[2] == Approx(0.1601).margin(5e-5));
}

TEST_CASE("box QP: the result satisfies the KKT conditions on random problems", "[fairing][qp]") {
  std::mt19937 rng(5);
  std::normal_distribution<double> g(0, 1);
  for (int trial = 0; trial < 100; ++trial) {
    const int n = 1 + trial % 9;
    Eigen::MatrixXd a(n, n);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) a(i, j) = g(rng);
    }
    const Eigen::MatrixXd h = a * a.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
    Eigen::VectorXd lin(n);
    for (int i = 0; i < n; ++i) lin[i] = 5 * g(rng);
    const Eigen::VectorXd lo = Eigen::VectorXd::Constant(n, -1), hi = Eigen::VectorXd::Constant(n, 0.5);
    const BoxQpResult r = solve_box_qp(h, lin, lo, hi);
    const Eigen::VectorXd grad = h * r.x + lin;
    for (int i = 0; i < n; ++i) {
      REQUIRE(r.x[i] >= -1.0);
      REQUIRE(r.x[i] <= 0.5);
      if (r.x[i] > -1.0 + 1e-12 && r.x[i] < 0.5 - 1e-12) CHECK(std::abs(grad[i]) < 1e-9);
      if (r.x[i] <= -1.0 + 1e-12) CHECK(grad[i] >= -1e-9);
      if (r.x[i] >= 0.5 - 1e-12) CHECK(grad[i] <= 1e-9);
    }
  }
}
