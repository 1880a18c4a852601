#include "geometry/mesh/weld.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "geometry/core/errors.h"
#include "geometry/mesh/validate.h"
#include "tests/geometry/mesh/shapes.h"

using namespace fabmesh;

TEST_CASE("weld: an STL-style cube welds back to 8 vertices and validates", "[mesh][weld]") {
  const TriangleSoup soup = test::unwelded(test::box());
  REQUIRE(soup.vertices.size() == 36);
  CHECK_FALSE(validate(soup).valid());  // unwelded: every edge is a boundary edge
  const WeldResult w = weld(soup);
  CHECK(w.merged_vertices == 28);
  CHECK(w.soup.vertices.size() == 8);
  CHECK(w.soup.triangles.size() == 12);
  const ValidationReport r = validate(w.soup);
  CHECK(r.valid());
  CHECK(r.genus == 0);
}

TEST_CASE("weld: keeps first-occurrence order and the lowest-index position", "[mesh][weld]") {
  TriangleSoup s;
  s.vertices = {{1, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}, {0, 1, 0}};
  s.triangles = {{0, 1, 3}, {2, 4, 3}};
  const WeldResult w = weld(s);
  CHECK(w.merged_vertices == 2);
  CHECK(w.soup.vertices == std::vector<Vec3>{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
  CHECK(w.soup.triangles[0] == w.soup.triangles[1]);
}

TEST_CASE("weld: +0.0 and -0.0 are equal coordinates, and neighbours a hair apart are not", "[mesh][weld]") {
  TriangleSoup s;
  s.vertices = {{0.0, 1, 1}, {-0.0, 1, 1}, {std::nextafter(0.0, 1.0), 1, 1}};
  s.triangles = {{0, 1, 2}};
  const WeldResult w = weld(s);
  CHECK(w.merged_vertices == 1);
  CHECK(w.soup.triangles[0][0] == w.soup.triangles[0][1]);  // now a degenerate face, for validation to report
  CHECK(validate(w.soup).degenerate_faces == 1);
}

TEST_CASE("weld: a tolerance merges close vertices transitively", "[mesh][weld]") {
  TriangleSoup s = test::unwelded(test::box());
  for (std::size_t i = 0; i < s.vertices.size(); ++i) s.vertices[i].x() += 1e-7 * static_cast<double>(i % 3);
  CHECK(weld(s).merged_vertices < 28);
  const WeldResult w = weld(s, WeldOptions{1e-6});
  CHECK(w.merged_vertices == 28);
  CHECK(validate(w.soup).valid());
  // A chain 0 - 0.6 - 1.2 with tolerance 0.7 is one vertex.
  TriangleSoup chain;
  chain.vertices = {{0, 0, 0}, {0.6, 0, 0}, {1.2, 0, 0}};
  CHECK(weld(chain, WeldOptions{0.7}).soup.vertices.size() == 1);
  CHECK(weld(chain, WeldOptions{0.5}).soup.vertices.size() == 3);
}

TEST_CASE("weld: a bad tolerance is a RangeError, and non-finite vertices never merge", "[mesh][weld]") {
  const TriangleSoup cube = test::box();
  CHECK_THROWS_AS(weld(cube, WeldOptions{-1.0}), RangeError);
  CHECK_THROWS_AS(weld(cube, WeldOptions{std::nan("")}), RangeError);
  TriangleSoup far = cube;
  far.vertices[0].x() = 1e300;
  CHECK_THROWS_AS(weld(far, WeldOptions{1e-300}), RangeError);
  TriangleSoup nan_soup;
  nan_soup.vertices = {{std::nan(""), 0, 0}, {std::nan(""), 0, 0}, {1, 1, 1}};
  CHECK(weld(nan_soup).merged_vertices == 0);
  CHECK(weld(nan_soup, WeldOptions{0.1}).merged_vertices == 0);
}
