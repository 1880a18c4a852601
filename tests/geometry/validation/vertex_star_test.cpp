// The stars of high-degree vertices (vertex_star.h) in the fast
// self-intersection test, against the reference pair for pair: planar and
// conical fans, valid and with folded, crossing and apex-only overlapping
// faces, random soups with high-degree vertices; and the deadline.

#include "geometry/validation/detail/vertex_star.h"

#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <random>
#include <vector>

#include "geometry/validation/detail/self_intersect.h"
#include "geometry/validation/detail/self_intersect_reference.h"
#include "geometry/validation/validate.h"
#include "tests/geometry/validation/same_as_reference.h"

using namespace fabmesh;

using fabmesh::test::require_same;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// A convex polygon of `n` corners on a circle of radius 10 in the plane
/// z = 0, triangulated as a fan from corner 0 (as the OBJ reader does).
TriangleSoup polygon_fan(std::uint32_t n) {
  TriangleSoup s;
  for (std::uint32_t i = 0; i < n; ++i) {
    const double a = 2 * kPi * i / n;
    s.vertices.emplace_back(10 * std::cos(a), 10 * std::sin(a), 0.0);
  }
  for (std::uint32_t i = 1; i + 1 < n; ++i) s.triangles.push_back({0, i, i + 1});
  return s;
}

/// A closed cone: apex (vertex n) over a circle of n corners, the base a fan
/// from corner 0.
TriangleSoup cone(std::uint32_t n) {
  TriangleSoup s;
  for (std::uint32_t i = 0; i < n; ++i) {
    const double a = 2 * kPi * i / n;
    s.vertices.emplace_back(std::cos(a), std::sin(a), 0.0);
  }
  s.vertices.emplace_back(0.0, 0.0, 1.0);
  for (std::uint32_t i = 0; i < n; ++i) s.triangles.push_back({n, i, (i + 1) % n});
  for (std::uint32_t i = 1; i + 1 < n; ++i) s.triangles.push_back({0, i + 1, i});
  return s;
}

std::uint32_t add_vertex(TriangleSoup& s, double x, double y, double z) {
  s.vertices.emplace_back(x, y, z);
  return static_cast<std::uint32_t>(s.vertices.size() - 1);
}

}  // namespace

TEST_CASE("Stars are found around high-degree vertices with certified faces", "[vertex_star]") {
  const TriangleSoup fan = polygon_fan(100);
  const detail::VertexStars stars = detail::find_vertex_stars(fan, {});
  REQUIRE(stars.centres == std::vector<std::uint32_t>{0});
  REQUIRE(stars.offsets.back() == 98);
  TriangleSoup broken = fan;
  broken.triangles.push_back({0, 5, 5});  // a repeated index: not certified, no member
  const detail::VertexStars with_broken = detail::find_vertex_stars(broken, {});
  REQUIRE(with_broken.centres == std::vector<std::uint32_t>{0});
  REQUIRE(with_broken.offsets.back() == 98);
  REQUIRE(with_broken.group.back() == detail::kNoStar);
  std::vector<char> skip(fan.triangles.size(), 0);
  for (std::size_t f = 0; f < 70; ++f) skip[f] = 1;  // skipped faces take no part
  REQUIRE(detail::find_vertex_stars(fan, skip).centres.empty());
}

TEST_CASE("A planar fan is valid and a folded fan triangle is found", "[vertex_star][self_intersect]") {
  TriangleSoup fan = polygon_fan(500);
  REQUIRE(require_same(fan).count == 0);
  SECTION("folded over its neighbours") {
    fan.triangles[200] = {0, 201, 190};  // reversed and widened: covers faces 190 to 199
    REQUIRE(require_same(fan).count > 0);
  }
  SECTION("an extra face over ten fan faces") {
    fan.triangles.push_back({0, 300, 310});
    REQUIRE(require_same(fan).count >= 10);
  }
}

TEST_CASE("Two fan triangles overlapping only near the apex are found", "[vertex_star][self_intersect]") {
  TriangleSoup fan = polygon_fan(300);
  // A small triangle at the apex whose sector spans several fan faces: it
  // meets them only within 0.01 of the apex.
  const Vec3 apex = fan.vertices[0];
  const Vec3 towards_a = fan.vertices[100] - apex;
  const Vec3 towards_b = fan.vertices[110] - apex;
  const Vec3 a = apex + 1e-3 * towards_a;
  const Vec3 b = apex + 1e-3 * towards_b;
  const std::uint32_t ia = add_vertex(fan, a.x(), a.y(), a.z());
  const std::uint32_t ib = add_vertex(fan, b.x(), b.y(), b.z());
  fan.triangles.push_back({0, ia, ib});
  REQUIRE(require_same(fan).count >= 9);
}

TEST_CASE("A cone apex of many faces is valid, and a crossing face is found",
          "[vertex_star][self_intersect]") {
  TriangleSoup c = cone(400);
  REQUIRE(require_same(c).count == 0);
  ValidationReport report = validate(c);
  REQUIRE(report.valid());
  SECTION("a face from the apex whose far edge crosses the cone's side") {
    const std::uint32_t p = add_vertex(c, 0.2, 0.01, 0.5);  // inside the cone
    const std::uint32_t q = add_vertex(c, 1.0, 0.05, 0.5);  // outside
    c.triangles.push_back({400, p, q});
    REQUIRE(require_same(c).count > 0);
  }
  SECTION("an apex face pushed inside its neighbours") {
    c.vertices[200] = Vec3(-0.2, 0.0, 0.2);
    require_same(c);
  }
}

/// A closed cylinder (radius 10, height 5) over n rim vertices, each cap a
/// fan from one rim vertex (vertices 0 and n).
TriangleSoup fan_cylinder(std::uint32_t n) {
  TriangleSoup s;
  for (const double z : {0.0, 5.0}) {
    for (std::uint32_t i = 0; i < n; ++i) {
      const double a = 2 * kPi * i / n;
      s.vertices.emplace_back(10 * std::cos(a), 10 * std::sin(a), z);
    }
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    s.triangles.push_back({i, j, n + j});
    s.triangles.push_back({i, n + j, n + i});
  }
  for (std::uint32_t i = 1; i + 1 < n; ++i) {
    s.triangles.push_back({0, i + 1, i});
    s.triangles.push_back({n, n + i, n + i + 1});
  }
  return s;
}

TEST_CASE("A cylinder with fan caps is valid, and faces crossing a cap away from its apex are found",
          "[vertex_star][self_intersect]") {
  TriangleSoup c = fan_cylinder(300);
  REQUIRE(require_same(c).count == 0);
  REQUIRE(validate(c).valid());
  SECTION("a face through both caps, far from the apexes") {
    const std::uint32_t a = add_vertex(c, -5, 0.5, -1);
    const std::uint32_t b = add_vertex(c, -5, -0.5, -1);
    const std::uint32_t t = add_vertex(c, -5, 0, 6);
    c.triangles.push_back({a, b, t});
    REQUIRE(require_same(c).count >= 2);
  }
  SECTION("a face from an apex of one cap through the other") {
    const std::uint32_t a = add_vertex(c, -9, 1, 6);
    const std::uint32_t b = add_vertex(c, -9, -1, 6);
    c.triangles.push_back({0, a, b});
    REQUIRE(require_same(c).count > 0);
  }
  SECTION("a sliver at an apex, touching it, across its fan") {
    const std::uint32_t a = add_vertex(c, 10, 1e-35, 0);  // not filterable: no member of the star
    const std::uint32_t b = add_vertex(c, -9, 0, 0);
    c.triangles.push_back({0, a, b});
    REQUIRE(require_same(c).count > 0);
  }
}

TEST_CASE("Random soups with high-degree vertices agree with the reference",
          "[vertex_star][self_intersect]") {
  std::mt19937_64 rng(7);
  const auto below = [&](std::uint32_t n) { return static_cast<std::uint32_t>(rng() % n); };
  for (int round = 0; round < 60; ++round) {
    TriangleSoup s;
    const std::uint32_t points = 40 + below(60);
    const bool grid = round % 2 == 0;  // exact coplanarities and coincidences
    for (std::uint32_t i = 0; i < points; ++i) {
      Vec3 p;
      for (int k = 0; k < 3; ++k) p[k] = grid ? below(5) / 2.0 : static_cast<double>(rng() >> 11) * 0x1.0p-53;
      if (round % 3 == 0) p.z() = 0.0;  // a planar soup: coplanar fans
      s.vertices.push_back(p);
    }
    const std::uint32_t faces = 150 + below(150);
    for (std::uint32_t f = 0; f < faces; ++f) {
      const std::uint32_t hub = below(4) == 0 ? below(points) : below(3);
      std::uint32_t b = below(points);
      std::uint32_t c = below(points);
      if (b == hub || c == hub || b == c) continue;
      s.triangles.push_back({hub, b, c});
    }
    std::vector<char> skip(s.triangles.size(), 0);
    for (std::size_t f = 0; f < s.triangles.size(); ++f) {
      const auto& t = s.triangles[f];
      skip[f] =
          (s.vertices[t[1]] - s.vertices[t[0]]).cross(s.vertices[t[2]] - s.vertices[t[0]]).squaredNorm() == 0;
    }
    REQUIRE_FALSE(detail::find_vertex_stars(s, skip).centres.empty());
    require_same(s, skip);
  }
}

TEST_CASE("A self-intersection test past its deadline says it is incomplete",
          "[vertex_star][self_intersect]") {
  const TriangleSoup c = cone(400);
  SelfIntersectOptions options;
  options.deadline = std::chrono::steady_clock::now();
  const SelfIntersections found = find_self_intersections(c, {}, options);
  REQUIRE(found.incomplete);
  REQUIRE(found.count == 0);
  ValidationOptions budget;
  budget.max_self_intersection_seconds = 1e-9;
  const ValidationReport report = validate(c, budget);
  REQUIRE(report.self_intersection_timed_out);
  REQUIRE(report.self_intersection == IntersectionCheck::NotRun);
  REQUIRE_FALSE(report.valid());
  REQUIRE_FALSE(describe_defects(report).empty());
}
