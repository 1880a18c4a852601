#include "geometry/surfaces/patch_network.h"

#include <catch2/catch.hpp>

#include "geometry/core/errors.h"
#include "tests/geometry/surfaces/test_networks.h"

using namespace fabmesh;

TEST_CASE("patch network: the h-bezier.md G2 join vector applied row by row", "[surfaces][network]") {
  const std::array<Vec3, 4> p{Vec3(0, 0, 0), Vec3(1, 2, 0), Vec3(3, 3, 1), Vec3(4, 1, 0)};
  PatchSpec a;
  a.name = "a";
  a.u = {1, 0.5, 0.5};
  a.v = {1.2, 0.1, 0.3};
  for (std::size_t i = 0; i < 4; ++i) {
    std::array<Vec3, 4> row;
    for (std::size_t j = 0; j < 4; ++j) row[j] = p[i] + Vec3(0, 0, 5.0 * static_cast<double>(j));
    a.points.push_back(row);
  }
  PatchSpec b;
  b.name = "b";
  b.u = {2, 0, -1};
  b.v = a.v;
  b.join = PatchJoin{0, PatchSide::UMax, Continuity::G2, 0.0, 1.0, 0.0};
  std::array<Vec3, 4> last;
  for (std::size_t j = 0; j < 4; ++j) last[j] = Vec3(8, 0, 5.0 * static_cast<double>(j));
  b.points = {last};
  const PatchNetwork net = build_patch_network({a, b});
  const Vec3 q1(6.11046163281, -3.22092326562, -2.11046163281),
      q2(7.46485801734, -25.0226570331, -14.9206226164);
  for (std::size_t j = 0; j < 4; ++j) {
    const Vec3 shift(0, 0, 5.0 * static_cast<double>(j));
    CHECK((net.patches[1].points()[0][j] - (p[3] + shift)).norm() < 1e-12);
    CHECK((net.patches[1].points()[1][j] - (q1 + shift)).norm() < 1e-9);
    CHECK((net.patches[1].points()[2][j] - (q2 + shift)).norm() < 1e-8);
  }
  REQUIRE(net.borders.size() == 1);
  CHECK(net.borders[0].declared == Continuity::G2);
  CHECK(net.borders[0].achieved == Continuity::G2);
  CHECK(net.borders[0].gap < 1e-12);
}

TEST_CASE("patch network: G1 joins have equal normals along every seam, declared or found",
          "[surfaces][network]") {
  const PatchNetwork net = build_patch_network(test::basin_specs());
  REQUIRE(net.patches.size() == 4);
  REQUIRE(net.borders.size() == 4);  // a-b, a-c, b-d declared; c-d found
  int found = 0;
  for (const SharedBorder& b : net.borders) {
    CHECK(b.gap < 1e-12);
    CHECK(b.normal_angle < 1e-6);
    CHECK(b.achieved >= Continuity::G1);
    if (b.declared == Continuity::None) {
      ++found;
      CHECK(b.a == 2);
      CHECK(b.b == 3);
      CHECK(b.side_a == PatchSide::UMax);
      CHECK(b.side_b == PatchSide::UMin);
    }
  }
  CHECK(found == 1);
}

TEST_CASE("patch network: u_min and v_min joins use the mirrored G1 formula", "[surfaces][network]") {
  auto specs = test::basin_specs();
  PatchSpec a = specs[0];
  PatchSpec left;
  left.name = "left";
  left.u = {1.7, 0.2, -0.4};
  left.join = PatchJoin{0, PatchSide::UMin, Continuity::G1, 2.0, 1.0, 0.0};
  left.points = {{Vec3(-2, -6, 0), Vec3(-1, -6, 0.3), Vec3(0, -6, 0.2), Vec3(1, -6, 0)},
                 {Vec3(-2, -5, 0), Vec3(-1, -5, 0.1), Vec3(0, -5, 0.1), Vec3(1, -5, 0)}};
  PatchSpec below;
  below.name = "below";
  below.join = PatchJoin{0, PatchSide::VMin, Continuity::G1, 0.5, 1.0, 0.0};
  below.points = {{Vec3(-6, -2, 0), Vec3(-6, -1, 0), Vec3(-6, 0, 0), Vec3(-6, 1, 0)}};
  below.join->continuity = Continuity::G2;  // one free column; k = 1, m = 0
  const PatchNetwork net = build_patch_network({a, left, below});
  const ControlNet& pa = net.patches[0].points();
  const ControlNet& pl = net.patches[1].points();
  for (std::size_t j = 0; j < 4; ++j) {
    CHECK((pl[3][j] - pa[0][j]).norm() < 1e-12);
    CHECK((pl[2][j] - (pa[0][j] + 2.0 * (pa[0][j] - pa[1][j]))).norm() < 1e-12);
  }
  CHECK((net.patches[2].points()[0][3] - pa[0][0]).norm() < 1e-12);
  for (const SharedBorder& b : net.borders) {
    CHECK(b.normal_angle < 1e-6);
    if (b.declared != Continuity::None) CHECK(b.achieved >= b.declared);
  }
}

TEST_CASE("patch network: a joined patch must share the border's parameterisation", "[surfaces][network]") {
  auto specs = test::basin_specs();
  specs[1].v = {1.5, 0, 0};  // b joins along u: its v parameters are the border's
  CHECK_THROWS_WITH(build_patch_network(specs), Catch::Contains("must share the border's parameterisation"));
  specs = test::basin_specs();
  specs[2].u.lambda = 0.3;  // c would meet... c joins a along v: u is the border direction
  CHECK_THROWS_AS(build_patch_network(specs), GeometryError);
}

TEST_CASE("patch network: bad joins are rejected", "[surfaces][network]") {
  auto specs = test::basin_specs();
  specs[1].points.pop_back();
  CHECK_THROWS_WITH(build_patch_network(specs), Catch::Contains("free rows"));
  specs = test::basin_specs();
  specs[1].join->to = 3;
  CHECK_THROWS_WITH(build_patch_network(specs), Catch::Contains("not an earlier patch"));
  specs = test::basin_specs();
  specs[1].join->gamma = 0.0;
  CHECK_THROWS_AS(build_patch_network(specs), RangeError);
}
