// A quasi-cubic B-spline through given points (docs/math/curves.md 2.3).

#include "geometry/curves/quasi_bspline_through.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "geometry/core/errors.h"
#include "geometry/curves/curve_spec.h"

using namespace fabmesh;

namespace {

// The curve of the control points `p` with `lambdas`, built as designs build it.
CompositeCurve curve_of(const std::vector<Vec2>& p, const std::vector<double>& lambdas) {
  CurveSpec spec;
  spec.family = CurveFamily::QuasiBSpline;
  spec.bspline_points = p;
  spec.bspline_lambdas = lambdas;
  return construct_curve(spec);
}

// Largest distance from q_i to the curve's joint i (its start and end for
// the ends), the curve evaluated by the curve code itself.
double largest_miss(const CompositeCurve& c, const std::vector<Vec2>& q) {
  double most = (c.segments().back().point(1.0) - q.back()).norm();
  for (std::size_t i = 0; i + 1 < q.size(); ++i)
    most = std::max(most, (c.segments()[i].point(0.0) - q[i]).norm());
  return most;
}

std::string message_of(const std::vector<Vec2>& q, const std::vector<double>& lambdas) {
  try {
    (void)quasi_bspline_through(q, lambdas, "profile");
  } catch (const GeometryError& e) {
    CHECK(e.where() == "profile");
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("through: the golden profile's own joints give back its control points", "[curves][through]") {
  // docs/math/curves.md 2: p = (1.5, 6), (1, 5), (2, 4), (3, 3), (1.5, 2), lambdas 0:
  // joint i is (p(i-1) + 4 p(i) + p(i+1)) / 6.
  const std::vector<Vec2> p{{1.5, 6}, {1, 5}, {2, 4}, {3, 3}, {1.5, 2}};
  std::vector<Vec2> q{p.front()};
  for (std::size_t i = 1; i + 1 < p.size(); ++i) q.push_back((p[i - 1] + 4.0 * p[i] + p[i + 1]) / 6.0);
  q.push_back(p.back());
  const QuasiBSplineThrough t = quasi_bspline_through(q, {0, 0, 0});
  REQUIRE(t.points.size() == p.size());
  CHECK(t.points.front() == q.front());  // the ends are the given points, exactly
  CHECK(t.points.back() == q.back());
  for (std::size_t i = 0; i < p.size(); ++i) CHECK((t.points[i] - p[i]).norm() < 1e-14);
  CHECK(t.deviation < 1e-15);
  CHECK(largest_miss(curve_of(t.points, {0, 0, 0}), q) <= t.deviation + 1e-14);
}

TEST_CASE("through: every lambda at -2 or more solves, within the proven deviation", "[curves][through]") {
  std::mt19937 rng(20261130);
  std::uniform_real_distribution<double> coordinate(-50.0, 50.0), lambda(-2.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const std::size_t n = 2 + static_cast<std::size_t>(trial % 40);
    std::vector<Vec2> q(n + 1);
    for (Vec2& v : q) v = {coordinate(rng), coordinate(rng)};
    std::vector<double> lambdas(n - 1);
    for (double& l : lambdas) l = trial % 5 == 0 ? -2.0 : lambda(rng);  // -2: dominant, not strictly
    const QuasiBSplineThrough t = quasi_bspline_through(q, lambdas);
    REQUIRE(t.points.size() == n + 1);
    CHECK(t.deviation < 1e-12);
    // The curve code's own evaluation agrees within its rounding.
    CHECK(largest_miss(curve_of(t.points, lambdas), q) <= t.deviation + 1e-12);
  }
}

TEST_CASE("through: a long profile of 3000 points", "[curves][through]") {
  std::vector<Vec2> q;
  for (int i = 0; i <= 3000; ++i) {
    const double z = i * 0.01;
    q.push_back({2.0 + std::sin(z) + 0.3 * std::sin(7.0 * z), z});
  }
  std::vector<double> lambdas(q.size() - 2);
  for (std::size_t i = 0; i < lambdas.size(); ++i) lambdas[i] = i % 3 == 0 ? 0.7 : -1.3;
  const QuasiBSplineThrough t = quasi_bspline_through(q, lambdas);
  CHECK(t.deviation < 1e-12);
  CHECK(largest_miss(curve_of(t.points, lambdas), q) <= t.deviation + 1e-12);
}

TEST_CASE("through: 20000 points with lambdas below -2 are decided at once", "[curves][through]") {
  // Lambdas of 53 significant bits below -2: the exact continuant would grow by about 60 bits a
  // row; its residues modulo primes decide that it is not 0.
  std::vector<Vec2> q;
  for (int i = 0; i <= 20000; ++i) q.push_back({1.0 + 0.5 * std::sin(i * 0.001), i * 0.001});
  std::vector<double> lambdas(q.size() - 2);
  for (std::size_t i = 0; i < lambdas.size(); ++i) lambdas[i] = i % 2 == 0 ? -2.3 : 0.3;
  const QuasiBSplineThrough t = quasi_bspline_through(q, lambdas);
  CHECK(t.deviation < 1e-12);
  // The same rows all at -8 (every residue 0, a singular system) are decided by the exact
  // continuant, whose whole numbers stay small: lambda = -8 needs no scaling.
  std::vector<double> eights(q.size() - 2, -8.0);
  CHECK_THAT(message_of(q, eights), Catch::Contains("determinant is exactly 0"));
  // An even row's lambda changed keeps the odd-sized system singular (D_odd = -144 D_(odd-2) = 0);
  // a subnormal lambda there would scale every row by 2^1126: too much work to decide exactly,
  // refused saying so rather than taking minutes.
  eights[1] = 1e-310;
  CHECK_THAT(message_of(q, eights), Catch::Contains("would take too long"));
}

TEST_CASE("through: a singular system is bad input, decided exactly", "[curves][through]") {
  // n = 2, lambda_1 = -8: the one equation 12 p0 + 12 p2 = 24 q1 has no p1.
  CHECK_THAT(message_of({{0, 0}, {1, 1}, {2, 0}}, {-8}),
             Catch::Contains("singular") && Catch::Contains("determinant is exactly 0"));
  // n = 3, lambda_1 = lambda_2 = -4: d1 d2 - a1 a2 = 8 * 8 - 8 * 8.
  CHECK_THAT(message_of({{0, 0}, {1, 1}, {2, 1}, {3, 0}}, {-4, -4}), Catch::Contains("singular"));
  // A hair away from it the determinant is not 0 (24e-12): not called singular.
  const std::vector<Vec2> q{{0, 0}, {1, 1}, {2, 1}, {3, 0}};
  const std::string near = message_of(q, {-4, -4 + 1e-12});
  CHECK_THAT(near, !Catch::Contains("exactly 0"));
  if (near == "no error") {
    const QuasiBSplineThrough t = quasi_bspline_through(q, {-4, -4 + 1e-12});
    CHECK(t.deviation <= 1e-9 * std::sqrt(10.0));
  } else {
    CHECK_THAT(near, Catch::Contains("too close to singular") && Catch::Contains("misses point"));
  }
}

TEST_CASE("through: wrong input names what is wrong", "[curves][through]") {
  CHECK_THAT(message_of({{0, 0}, {1, 1}}, {}), Catch::Contains("at least 3 points"));
  CHECK_THAT(message_of({{0, 0}, {1, 1}, {2, 0}}, {0, 0}), Catch::Contains("lambdas has 2 values"));
  CHECK_THROWS_AS(quasi_bspline_through({{0, 0}, {1, 1}, {2, 0}}, {1.5}), RangeError);
  CHECK_THAT(message_of({{0, 0}, {1, std::nan("")}, {2, 0}}, {}), Catch::Contains("not finite"));
  // Empty lambdas are all 0.
  const QuasiBSplineThrough t = quasi_bspline_through({{0, 0}, {3, 6}, {6, 0}}, {});
  CHECK(t.points[1].x() == Approx(3.0));
  CHECK(t.points[1].y() == Approx(9.0));  // (0 + 4 y + 0) / 6 = 6
}
