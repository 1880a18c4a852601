#include "geometry/mesh/sweep.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "geometry/core/errors.h"
#include "geometry/mesh/revolve.h"
#include "geometry/validation/validate.h"

using namespace fabmesh;

namespace {

SweepPath uniform_path(int m, bool closed, double span) {
  SweepPath p;
  const int samples = closed ? m : m + 1;
  for (int j = 0; j < samples; ++j) {
    const double a = span * j / m;
    p.directions.emplace_back(std::cos(a), std::sin(a));
  }
  p.closed = closed;
  return p;
}

}  // namespace

TEST_CASE("sweep: a closed sweep is revolve's mesh, a valid solid of the same volume", "[mesh][sweep]") {
  SweepSection s;
  s.loop = {{0, 0}, {2, 0}, {3, 1}, {1.5, 2}, {2, 4}, {0, 4}};
  const SweptSurface swept = sweep_section(s, uniform_path(48, true, 2 * M_PI));
  const ValidationReport a = validate(swept.soup);
  CHECK(a.valid());
  CHECK(a.genus == 0);
  RevolveOptions ro;
  ro.segments = 48;
  const ValidationReport b = validate(revolve({s.loop}, ro).soup);
  CHECK(swept.soup.triangles.size() == static_cast<std::size_t>(b.triangles));
  CHECK(a.volume == Approx(b.volume).epsilon(1e-12));
  CHECK(a.area == Approx(b.area).epsilon(1e-12));
}

TEST_CASE("sweep: outline vertices on a square make its flat sides exact", "[mesh][sweep]") {
  // A rectangle [0, 1] x [0, 2] whose outer edge follows a square of half side 1, sampled at its corners
  // and between them: the closed sweep is exactly the box 2 x 2 x 2.
  SweepSection s;
  s.loop = {{0, 0}, {1, 0}, {1, 2}, {0, 2}};
  s.on_outline = {0, 1, 1, 0};
  SweepPath p;
  p.closed = true;
  for (int j = 0; j < 16; ++j) {
    const double a = 2 * M_PI * j / 16;
    p.directions.emplace_back(std::cos(a), std::sin(a));
    const Vec2 d = p.directions.back();
    p.outline.push_back(j % 4 == 2 ? Vec2(std::copysign(1.0, d.x()), std::copysign(1.0, d.y()))
                                   : d / std::max(std::abs(d.x()), std::abs(d.y())));
  }
  const SweptSurface swept = sweep_section(s, p);
  const ValidationReport r = validate(swept.soup);
  CHECK(r.valid());
  CHECK(r.volume == Approx(8.0).epsilon(1e-14));
  CHECK(r.area == Approx(24.0).epsilon(1e-14));
}

TEST_CASE("sweep: a partial sweep leaves both end sections open along the loop's edges", "[mesh][sweep]") {
  SweepSection s;
  s.loop = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  const SweptSurface swept = sweep_section(s, uniform_path(10, false, M_PI / 2));
  ValidationOptions untested;
  untested.check_self_intersections = false;
  const ValidationReport r = validate(swept.soup, untested);
  // The open ends: the three off-axis loop edges at each end (the axis edge has no lateral face).
  CHECK(r.boundary_edges == 6);
  CHECK(swept.first[0] == swept.last[0]);  // pole vertices are shared
  CHECK(swept.first[1] != swept.last[1]);
}

TEST_CASE("sweep: an outline vertex joined by a sloping edge is refused", "[mesh][sweep]") {
  SweepSection s;
  s.loop = {{0, 0}, {2, 0}, {2, 1}, {1, 2}, {0, 2}};
  s.on_outline = {0, 1, 1, 0, 0};
  SweepPath p = uniform_path(8, true, 2 * M_PI);
  for (const Vec2& d : p.directions) p.outline.push_back(2.0 * d);
  CHECK_THROWS_AS(sweep_section(s, p), GeometryError);
}

TEST_CASE("sweep: an open edge gets no faces, and its two rings are given sample by sample",
          "[mesh][sweep]") {
  // An annulus section (r 1 to 2, z 0 to 1) with its top edge, from (2, 1) in to (1, 1), left open.
  SweepSection s;
  s.loop = {{1, 0}, {2, 0}, {2, 1}, {1, 1}};
  s.open_edge = 2;
  const int m = 24;
  const SweptSurface swept = sweep_section(s, uniform_path(m, true, 2 * M_PI));
  CHECK(swept.soup.triangles.size() == swept_triangle_count(s, m, true));
  CHECK(swept.soup.triangles.size() == static_cast<std::size_t>(3 * 2 * m));
  REQUIRE(swept.open_from.size() == static_cast<std::size_t>(m));
  REQUIRE(swept.open_to.size() == static_cast<std::size_t>(m));
  for (int j = 0; j < m; ++j) {
    const Vec3& from = swept.soup.vertices[swept.open_from[static_cast<std::size_t>(j)]];
    const Vec3& to = swept.soup.vertices[swept.open_to[static_cast<std::size_t>(j)]];
    CHECK(std::hypot(from.x(), from.y()) == Approx(2.0));
    CHECK(std::hypot(to.x(), to.y()) == Approx(1.0));
    CHECK(from.z() == 1.0);
    CHECK(to.z() == 1.0);
  }
  // The open top: two circles of m boundary edges each, and nothing else open.
  ValidationOptions untested;
  untested.check_self_intersections = false;
  CHECK(validate(swept.soup, untested).boundary_edges == static_cast<std::size_t>(2 * m));
}

TEST_CASE("sweep: an open edge that slopes, or ends on the axis, is refused", "[mesh][sweep]") {
  SweepSection s;
  s.loop = {{0, 0}, {2, 0}, {2, 1}, {1, 2}, {0, 2}};
  s.open_edge = 2;  // (2, 1) to (1, 2): sloping
  CHECK_THROWS_AS(sweep_section(s, uniform_path(8, true, 2 * M_PI)), GeometryError);
  s.open_edge = 3;  // (1, 2) to (0, 2): on the axis
  CHECK_THROWS_AS(sweep_section(s, uniform_path(8, true, 2 * M_PI)), GeometryError);
  s.open_edge = 7;  // no such edge
  CHECK_THROWS_AS(sweep_section(s, uniform_path(8, true, 2 * M_PI)), RangeError);
}
