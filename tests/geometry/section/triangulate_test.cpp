#include "geometry/section/triangulate.h"

#include <catch2/catch.hpp>

#include "geometry/core/errors.h"
#include "geometry/section/simple_polygon.h"
#include "tests/geometry/section/region_shapes.h"

using namespace fabmesh;
using namespace fabmesh::test;

namespace {

Region2 kitchen_region(double tolerance) {
  RegionOptions o;
  o.tolerance = tolerance;
  return build_region(rounded_rect(0, 0, 2400, 650, 80),
                      {{ellipse({600, 325}, 250, 180, 15), "holes[0] (ellipse)"},
                       {rounded_rect(1300, 150, 2000, 500, 40), "holes[1] (rounded_rect)"}},
                      o);
}

double triangle_area(const PlanarTriangulation& t, const std::array<std::uint32_t, 3>& f) {
  return 0.5 * cross2(t.vertices[f[1]] - t.vertices[f[0]], t.vertices[f[2]] - t.vertices[f[0]]);
}

double cycle_area(const PlanarTriangulation& t, const std::vector<std::uint32_t>& c) {
  std::vector<Vec2> pts;
  for (auto i : c) pts.push_back(t.vertices[i]);
  return 0.5 * signed_area2(pts);
}

}  // namespace

TEST_CASE("triangulate: the triangles tile the region and its boundary cycles are its loops",
          "[section][triangulate][countertop]") {
  const Region2 r = kitchen_region(0.5);
  const PlanarTriangulation t = triangulate(r);
  CHECK(t.steiner_points == 0);
  double sum = 0.0;
  for (const auto& f : t.triangles) {
    const double a = triangle_area(t, f);
    CHECK(a > 0.0);
    sum += a;
  }
  CHECK(sum == Approx(r.area).epsilon(1e-12));
  // Without refinement, the boundary is the region's loops: one outer (positive area) and two holes.
  REQUIRE(t.boundary.size() == 3);
  int outer = 0;
  double boundary_area = 0.0;
  std::size_t boundary_points = 0;
  for (const auto& c : t.boundary) {
    outer += cycle_area(t, c) > 0.0;
    boundary_area += cycle_area(t, c);
    boundary_points += c.size();
  }
  CHECK(outer == 1);
  CHECK(boundary_area == Approx(r.area).epsilon(1e-12));
  std::size_t loop_points = r.outer.size();
  for (const auto& h : r.holes) loop_points += h.size();
  CHECK(boundary_points == loop_points);
  CHECK(t.vertices.size() == loop_points);
  // Euler: a disc with 2 holes has V - E + F = 1 - 2; here F = T, E = (3T + B) / 2.
  const auto T = static_cast<long>(t.triangles.size()), B = static_cast<long>(boundary_points);
  CHECK(static_cast<long>(t.vertices.size()) - (3 * T + B) / 2 + T == -1);
}

TEST_CASE("triangulate: max_edge bounds every edge, the area stays that of the region",
          "[section][triangulate][countertop]") {
  const Region2 r = kitchen_region(0.5);
  TriangulateOptions o;
  o.max_edge = 60.0;
  const PlanarTriangulation t = triangulate(r, o);
  CHECK(t.steiner_points > 0);
  double sum = 0.0, longest = 0.0;
  for (const auto& f : t.triangles) {
    sum += triangle_area(t, f);
    CHECK(triangle_area(t, f) > 0.0);
    for (int i = 0; i < 3; ++i)
      longest = std::max(longest, (t.vertices[f[i]] - t.vertices[f[(i + 1) % 3]]).norm());
  }
  CHECK(longest <= o.max_edge * (1 + 1e-9));
  CHECK(sum == Approx(r.area).epsilon(1e-9));
  CHECK(t.boundary.size() == 3);
}

TEST_CASE("triangulate: a max_edge too small for the budget is a BudgetError",
          "[section][triangulate][countertop][errors]") {
  const Region2 r = kitchen_region(0.5);
  TriangulateOptions o;
  o.max_edge = 1.0;
  o.max_triangles = 100000;
  CHECK_THROWS_AS(triangulate(r, o), BudgetError);
  o.max_edge = -1.0;
  CHECK_THROWS_AS(triangulate(r, o), RangeError);
}

TEST_CASE("planar embedding: counter-clockwise triangles inside simple nested cycles, decided exactly",
          "[section][triangulate]") {
  const std::vector<Vec2> square = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const std::vector<std::array<std::uint32_t, 3>> two = {{0, 1, 2}, {0, 2, 3}};
  std::string why;
  CHECK(is_planar_embedding(square, two, {{0, 1, 2, 3}}, &why));
  CHECK_FALSE(is_planar_embedding(square, {{0, 2, 1}, {0, 2, 3}}, {{0, 1, 2, 3}}, &why));
  CHECK_THAT(why, Catch::Contains("triangle 0 is not counter-clockwise"));
  CHECK_FALSE(is_planar_embedding(square, two, {{3, 2, 1, 0}}, &why));
  CHECK_THAT(why, Catch::Contains("no counter-clockwise"));
  // A hole cycle (clockwise) must lie inside the outer one and outside the other holes.
  std::vector<Vec2> points = square;
  for (const Vec2& p : std::vector<Vec2>{{0.2, 0.2}, {0.2, 0.4}, {0.4, 0.4}, {0.4, 0.2}}) points.push_back(p);
  for (const Vec2& p : std::vector<Vec2>{{2.2, 0.2}, {2.2, 0.4}, {2.4, 0.4}, {2.4, 0.2}}) points.push_back(p);
  CHECK(is_planar_embedding(points, {}, {{0, 1, 2, 3}, {4, 5, 6, 7}}, &why));
  CHECK_FALSE(is_planar_embedding(points, {}, {{0, 1, 2, 3}, {8, 9, 10, 11}}, &why));
  CHECK_THAT(why, Catch::Contains("not inside the outer cycle"));
  // A cycle that crosses itself.
  CHECK_FALSE(is_planar_embedding(square, {}, {{0, 2, 1, 3}}, &why));
  CHECK_THAT(why, Catch::Contains("cross"));
}
