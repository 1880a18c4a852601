#include "geometry/mould/release.h"

#include <catch2/catch.hpp>
#include <cmath>

using namespace fabmesh;

TEST_CASE("release: a cavity boundary that never rises walking down releases, a fold is reported",
          "[mould][release]") {
  // Opening, reservoir, a belly and a neck (radius up and down), a flat floor to the axis: no undercut.
  const std::vector<Vec2> vase = {{2, 10}, {2, 8}, {1.2, 7}, {3, 4}, {3, 4}, {2.5, 1}, {2, 1}, {0, 1}};
  CHECK(find_undercuts(vase, {}).empty());
  // A lip curling down outside the rim: (3, 7) lies below the later (2.8, 7.5).
  const std::vector<Vec2> curl = {{2, 10}, {2, 8}, {3, 7}, {2.8, 7.5}, {2, 4}, {0, 4}};
  const auto u = find_undercuts(curl, {});
  REQUIRE(u.size() == 2);
  CHECK(u[0].point == Vec2(3, 7));
  CHECK(u[1].point == Vec2(2.8, 7.5));
  CHECK(u[0].part == MouldPartKind::Side);
  CHECK_THAT(describe_undercuts(u), Catch::Contains("(r 3, z 7), (r 2.8, z 7.5)"));
}

TEST_CASE("release: a base part releases when the cavity inside it never widens toward the axis",
          "[mould][release]") {
  // From the cut (2, 2) toward the axis: narrowing then flat floor; then a foot groove that narrows downward.
  CHECK(find_undercuts({}, {{2, 2}, {1.5, 1}, {0, 1}}).empty());
  CHECK(find_undercuts({}, {{3, 2}, {2.5, 0}, {2, 1}, {0, 1}}).empty());
  // Widening downward: (3, 0.5) is farther out than the cut point (2, 2).
  const auto u = find_undercuts({}, {{2, 2}, {3, 0.5}, {0, 0.5}});
  REQUIRE(u.size() == 2);
  CHECK(u[0].part == MouldPartKind::Base);
  CHECK(u[1].point == Vec2(3, 0.5));
  CHECK_THAT(describe_undercuts(u), Catch::Contains("base part cannot be pulled down"));
}

TEST_CASE("release: a bump leaves a socket pulled at alpha exactly when r_s cos(alpha) >= r",
          "[mould][release][keys]") {
  CHECK(key_pull_angle(2) == 0.0);
  CHECK(key_pull_angle(3) == Approx(M_PI / 6).epsilon(1e-15));
  CHECK(keys_release(2, 6.0, 6.0));
  const double r = 6.0, limit = r / std::cos(M_PI / 6);
  CHECK(keys_release(3, r, limit * (1 + 1e-12)));
  CHECK_FALSE(keys_release(3, r, limit * (1 - 1e-12)));
  // The bound is attained: the base-circle point at polar angle alpha, pulled at alpha, crosses the split
  // plane exactly r / cos(alpha) from the centre (2D section through the pull direction).
  const double alpha = key_pull_angle(3);
  const Vec2 p(r * std::cos(alpha), r * std::sin(alpha)), d(std::sin(alpha), -std::cos(alpha));
  const double t = p.y() / std::cos(alpha);
  CHECK((p + t * d).y() == Approx(0.0).margin(1e-12));
  CHECK((p + t * d).norm() == Approx(limit).epsilon(1e-12));
}
