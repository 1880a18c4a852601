#include "geometry/surfaces/hbezier_patch.h"

#include <catch2/catch.hpp>
#include <random>

#include "geometry/core/errors.h"

using namespace fabmesh;

namespace {

// P_ij = e_i (unit vectors, P_3j = 0) for every j: the v direction is
// degenerate and S(s, t) = (h0, h1, h2)(u = alpha s).
ControlNet basis_net() {
  ControlNet p{};
  for (std::size_t j = 0; j < 4; ++j) {
    p[0][j] = Vec3(1, 0, 0);
    p[1][j] = Vec3(0, 1, 0);
    p[2][j] = Vec3(0, 0, 1);
    p[3][j] = Vec3(0, 0, 0);
  }
  return p;
}

ControlNet wavy_net() {
  ControlNet p{};
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = 0; j < 4; ++j)
      p[i][j] = Vec3(static_cast<double>(i), static_cast<double>(j),
                     std::sin(1.3 * static_cast<double>(i * j)) + 0.2 * static_cast<double>(i));
  return p;
}

}  // namespace

TEST_CASE("hbezier patch: a degenerate v direction reproduces the h-bezier.md basis test vectors",
          "[surfaces][patch]") {
  struct Row {
    double alpha, lambda, mu, u;
    std::array<double, 4> h;
  };
  const Row rows[] = {
      {1, 0, 0, 0.5, {0.120406174496, 0.379593825504, 0.379593825504, 0.120406174496}},
      {2, 1, 1, 1, {0.0565217506727, 0.443478249327, 0.443478249327, 0.0565217506727}},
  };
  for (const Row& r : rows) {
    const HBezierPatch patch(basis_net(), {r.alpha, r.lambda, r.mu}, {0.7, 0.3, -0.5});
    for (double t : {0.0, 0.3, 1.0}) {
      const Vec3 s = patch.point(r.u / r.alpha, t);
      CHECK(s.x() == Approx(r.h[0]).margin(1e-11));
      CHECK(s.y() == Approx(r.h[1]).margin(1e-11));
      CHECK(s.z() == Approx(r.h[2]).margin(1e-11));
      CHECK(1.0 - s.x() - s.y() - s.z() == Approx(r.h[3]).margin(1e-11));
    }
  }
}

TEST_CASE("hbezier patch: the tensor basis is a partition of unity", "[surfaces][patch]") {
  ControlNet same{};
  for (auto& row : same) row.fill(Vec3(2.5, -1.0, 7.0));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0), shape(-2.0, 1.0), alpha(0.001, 10.0);
  for (int k = 0; k < 50; ++k) {
    const HBezierPatch p(same, {alpha(rng), shape(rng), shape(rng)}, {alpha(rng), shape(rng), shape(rng)});
    const double s = unit(rng), t = unit(rng);
    const PatchJet j = p.jet(s, t);
    CHECK((j.point - Vec3(2.5, -1.0, 7.0)).norm() < 1e-9);
    CHECK(j.ds.norm() < 1e-8);
    CHECK(j.dt.norm() < 1e-8);
    CHECK(j.dst.norm() < 1e-7);
  }
}

TEST_CASE("hbezier patch: interpolates its corners and has the analytic derivatives", "[surfaces][patch]") {
  const ControlNet net = wavy_net();
  const HBezierPatch p(net, {1.5, 0.4, -1.0}, {3.0, -0.5, 0.8});
  CHECK((p.point(0, 0) - net[0][0]).norm() < 1e-12);
  CHECK((p.point(1, 0) - net[3][0]).norm() < 1e-12);
  CHECK((p.point(0, 1) - net[0][3]).norm() < 1e-12);
  CHECK((p.point(1, 1) - net[3][3]).norm() < 1e-12);
  const double h = 1e-6;
  for (double s : {0.1, 0.5, 0.9}) {
    for (double t : {0.2, 0.7}) {
      const PatchJet j = p.jet(s, t);
      CHECK((j.ds - (p.point(s + h, t) - p.point(s - h, t)) / (2 * h)).norm() < 1e-6);
      CHECK((j.dt - (p.point(s, t + h) - p.point(s, t - h)) / (2 * h)).norm() < 1e-6);
      CHECK((j.dss - (p.jet(s + h, t).ds - p.jet(s - h, t).ds) / (2 * h)).norm() < 1e-5);
      CHECK((j.dst - (p.jet(s, t + h).ds - p.jet(s, t - h).ds) / (2 * h)).norm() < 1e-5);
      CHECK((j.dtt - (p.jet(s, t + h).dt - p.jet(s, t - h).dt) / (2 * h)).norm() < 1e-5);
      const Vec3 n = p.normal(s, t);
      CHECK(n.norm() == Approx(1.0));
      CHECK(std::abs(n.dot(j.ds)) < 1e-9 * j.ds.norm());
      CHECK(n.dot(j.ds.cross(j.dt)) > 0.0);
    }
  }
}

TEST_CASE("hbezier patch: parameters out of range are rejected naming the value", "[surfaces][patch]") {
  const ControlNet net = wavy_net();
  CHECK_THROWS_AS(HBezierPatch(net, {0.0, 0, 0}, {1, 0, 0}), RangeError);
  CHECK_THROWS_AS(HBezierPatch(net, {10.5, 0, 0}, {1, 0, 0}), RangeError);
  CHECK_THROWS_AS(HBezierPatch(net, {1, 0, 1.2}, {1, 0, 0}), RangeError);
  CHECK_THROWS_WITH(HBezierPatch(net, {1, 0, 0}, {1, -3.3, 0}), Catch::Contains("v.lambda = -3.3"));
  CHECK_NOTHROW(HBezierPatch(net, {1, -3.2, 1}, {1, 0, 0}));  // lambda*(1) = -3.2053
}

TEST_CASE("hbezier patch: jets and normals from grid-line weights are the pointwise ones, bit for bit",
          "[surfaces][patch]") {
  // A collapsed side too (row 0 one point), where the normal is taken inside.
  ControlNet net = wavy_net();
  for (std::size_t j = 0; j < 4; ++j) net[0][j] = Vec3(0, 0, 0);
  const HBezierPatch patch(net, {1.3, 0.2, -0.4}, {0.7, -0.5, 0.3});
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<std::pair<double, double>> at{{0.0, 0.0}, {0.0, 0.6}, {1.0, 1.0}, {0.25, 0.0}};
  for (int k = 0; k < 200; ++k) at.emplace_back(unit(rng), unit(rng));
  for (const auto& [s, t] : at) {
    const PatchJet direct = patch.jet(s, t);
    const PatchJet gridded = patch.jet(patch.u_weights(s), patch.v_weights(t));
    CHECK(gridded.point == direct.point);
    CHECK(gridded.ds == direct.ds);
    CHECK(gridded.dt == direct.dt);
    CHECK(gridded.dss == direct.dss);
    CHECK(gridded.dst == direct.dst);
    CHECK(gridded.dtt == direct.dtt);
    CHECK(patch.normal(gridded, s, t) == patch.normal(s, t));
  }
  // On the collapsed side the normal is still a unit vector.
  CHECK(patch.normal(patch.jet(0.0, 0.6), 0.0, 0.6).norm() == Approx(1.0));
}
