// collapse_short_edges: hair-short edges (a cut a hair from a vertex) go, the
// surface stays closed and valid, no vertex moves, and a collapse that would
// pinch the surface is refused.

#include "geometry/mesh/short_edges.h"

#include <catch2/catch.hpp>
#include <cstdint>
#include <set>
#include <tuple>
#include <vector>

#include "geometry/mesh/volume.h"
#include "geometry/validation/validate.h"
#include "tests/geometry/mesh/shapes.h"

using namespace fabmesh;

namespace {

/// `soup` with its edge (a, b) split at a + t (b - a): each of the edge's two
/// faces in two, oriented as it was. The new vertex's index.
std::uint32_t split_edge(TriangleSoup& soup, std::uint32_t a, std::uint32_t b, double t) {
  const auto p = static_cast<std::uint32_t>(soup.vertices.size());
  soup.vertices.push_back(soup.vertices[a] + t * (soup.vertices[b] - soup.vertices[a]));
  const std::size_t faces = soup.triangles.size();
  int split = 0;
  for (std::size_t f = 0; f < faces; ++f) {
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t u = soup.triangles[f][i], v = soup.triangles[f][(i + 1) % 3],
                          w = soup.triangles[f][(i + 2) % 3];
      if ((u == a && v == b) || (u == b && v == a)) {
        soup.triangles[f] = {u, p, w};
        soup.triangles.push_back({p, v, w});
        ++split;
        break;
      }
    }
  }
  REQUIRE(split == 2);
  return p;
}

std::set<std::tuple<double, double, double>> points_of(const TriangleSoup& soup) {
  std::set<std::tuple<double, double, double>> points;
  for (const Vec3& p : soup.vertices) points.emplace(p.x(), p.y(), p.z());
  return points;
}

}  // namespace

TEST_CASE("short edges: a box's edge split a hair from its corner is a box again", "[mesh][short_edges]") {
  const TriangleSoup box = test::box();
  TriangleSoup split = box;
  const std::uint32_t a = split.triangles[0][0], b = split.triangles[0][1];
  split_edge(split, a, b, 1e-9);
  REQUIRE(split.triangles.size() == 14);

  TriangleSoup collapsed = split;
  CHECK(collapse_short_edges(collapsed, 1e-6) == 1);
  CHECK(collapsed.vertices.size() == box.vertices.size());
  CHECK(collapsed.triangles.size() == box.triangles.size());
  CHECK(points_of(collapsed) == points_of(box));  // the corner stayed, the hair's end went
  const ValidationReport report = validate(collapsed);
  CHECK(report.valid());
  CHECK(signed_volume(collapsed) == Approx(1.0).epsilon(1e-12));

  // An edge at least `length` long stays.
  TriangleSoup kept = split;
  CHECK(collapse_short_edges(kept, 0.5e-9) == 0);
  CHECK(kept.triangles == split.triangles);
  CHECK(kept.vertices == split.vertices);
}

TEST_CASE("short edges: many hairs on a sphere go, each removed point a hair from one that stays",
          "[mesh][short_edges]") {
  const TriangleSoup sphere = test::sphere(10.0, 24, 12);
  TriangleSoup hairy = sphere;
  // Hairs on edges apart from each other, and a chain: a point a hair from
  // the corner and another a hair beyond it, on the same edge.
  std::vector<std::uint32_t> added;
  for (std::size_t f = 0; f < hairy.triangles.size(); f += 37) {
    const std::uint32_t a = hairy.triangles[f][0], b = hairy.triangles[f][1];
    added.push_back(split_edge(hairy, a, b, 1e-9));
  }
  const std::uint32_t a = hairy.triangles[5][1], b = hairy.triangles[5][2];
  const std::uint32_t first = split_edge(hairy, a, b, 1e-9);
  split_edge(hairy, first, b, 1e-9);
  REQUIRE(validate(hairy).valid());

  TriangleSoup collapsed = hairy;
  const std::size_t hairs = added.size() + 2;
  CHECK(collapse_short_edges(collapsed, 1e-6) == hairs);
  CHECK(collapsed.vertices.size() == sphere.vertices.size());
  CHECK(collapsed.triangles.size() == sphere.triangles.size());
  CHECK(points_of(collapsed) == points_of(sphere));  // no vertex moved; every hair's end went
  CHECK(validate(collapsed).valid());
  CHECK(signed_volume(collapsed) == Approx(signed_volume(sphere)).epsilon(1e-9));
  // Deterministic: the same input, the same output.
  TriangleSoup again = hairy;
  collapse_short_edges(again, 1e-6);
  CHECK(again.vertices == collapsed.vertices);
  CHECK(again.triangles == collapsed.triangles);
}

TEST_CASE("short edges: a collapse that would pinch the surface is refused", "[mesh][short_edges]") {
  // A tetrahedron with two vertices a hair apart: collapsing them leaves two
  // faces back to back, no solid.
  TriangleSoup tetra;
  tetra.vertices = {Vec3(0, 0, 0), Vec3(1e-9, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  tetra.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  TriangleSoup collapsed = tetra;
  CHECK(collapse_short_edges(collapsed, 1e-6) == 0);
  CHECK(collapsed.triangles == tetra.triangles);

  // Two hairs at one corner of a box, along two of its edges (their ends a
  // hair from each other too): both go, the corner stays.
  TriangleSoup box = test::box();
  const std::uint32_t a = box.triangles[0][0], b = box.triangles[0][1], c = box.triangles[0][2];
  split_edge(box, a, b, 1e-9);
  split_edge(box, a, c, 1e-9);
  REQUIRE(validate(box).valid());
  CHECK(collapse_short_edges(box, 1e-6) == 2);
  CHECK(points_of(box) == points_of(test::box()));
  CHECK(box.triangles.size() == 12);
  CHECK(validate(box).valid());
}
