// The fast self-intersection test against the reference, pair for pair, on
// meshes with every kind of contact: shared edges and vertices, exact
// coincidences, coplanar folds, touching and crossing faces, near-degenerate
// faces, and on closed meshes before and after random perturbations.

#include "geometry/validation/detail/self_intersect.h"

#include <tbb/task_arena.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "geometry/core/errors.h"
#include "geometry/mesh/halfedge_mesh.h"
#include "geometry/mesh/revolve.h"
#include "geometry/mesh/slab.h"
#include "geometry/section/region.h"
#include "geometry/validation/detail/self_intersect_reference.h"
#include "tests/geometry/mesh/shapes.h"
#include "tests/geometry/section/region_shapes.h"
#include "tests/geometry/validation/same_as_reference.h"
#include "tests/geometry/validation/sliver_shapes.h"

using namespace fabmesh;
using fabmesh::test::append;
using fabmesh::test::box;

using fabmesh::test::require_same;

namespace {

/// Portable random numbers (the standard distributions differ between libraries).
class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}
  /// Uniform in [0, n).
  std::uint32_t below(std::uint32_t n) { return static_cast<std::uint32_t>(engine_() % n); }
  /// Uniform in [0, 1).
  double unit() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  bool chance(double p) { return unit() < p; }

 private:
  std::mt19937_64 engine_;
};

/// Skip flags for faces whose corners repeat an index or are exactly
/// collinear (what validation skips); exact for the small dyadic coordinates
/// used here, conservative otherwise (the reference is not defined on them).
std::vector<char> degenerate_faces(const TriangleSoup& s) {
  std::vector<char> skip(s.triangles.size(), 0);
  for (std::size_t f = 0; f < s.triangles.size(); ++f) {
    const auto& t = s.triangles[f];
    const Vec3 n = (s.vertices[t[1]] - s.vertices[t[0]]).cross(s.vertices[t[2]] - s.vertices[t[0]]);
    skip[f] = t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || n.squaredNorm() == 0.0;
  }
  return skip;
}

/// A soup of `triangles` faces over a pool of points of one kind: small
/// integers, quarters, random doubles, or integers nudged by a few ulps.
TriangleSoup random_soup(Random& rng) {
  TriangleSoup s;
  const std::uint32_t points = 4 + rng.below(24);
  const std::uint32_t kind = rng.below(4);
  for (std::uint32_t i = 0; i < points; ++i) {
    Vec3 p;
    for (int k = 0; k < 3; ++k) {
      switch (kind) {
        case 0:
          p[k] = rng.below(4);
          break;
        case 1:
          p[k] = rng.below(9) / 4.0;
          break;
        case 2:
          p[k] = rng.unit() * 2.0;
          break;
        default: {
          p[k] = rng.below(3);
          for (std::uint32_t n = rng.below(3); n > 0; --n)
            p[k] = std::nextafter(p[k], rng.chance(0.5) ? 10.0 : -10.0);
        }
      }
    }
    s.vertices.push_back(p);
  }
  const std::uint32_t faces = 2 + rng.below(40);
  for (std::uint32_t f = 0; f < faces; ++f) {
    s.triangles.push_back({rng.below(points), rng.below(points), rng.below(points)});
  }
  return s;
}

/// `soup` with some vertices moved: by a few ulps, by a small or a large
/// random step, onto another vertex, or onto the midpoint of two others
/// (an exact coincidence or collinearity with dyadic coordinates).
TriangleSoup perturbed(TriangleSoup s, Random& rng) {
  const std::uint32_t n = static_cast<std::uint32_t>(s.vertices.size());
  const std::uint32_t moves = 1 + rng.below(6);
  for (std::uint32_t m = 0; m < moves; ++m) {
    Vec3& p = s.vertices[rng.below(n)];
    switch (rng.below(5)) {
      case 0:
        for (int k = 0; k < 3; ++k) p[k] = std::nextafter(p[k], rng.chance(0.5) ? 1e9 : -1e9);
        break;
      case 1:
        p += 1e-9 * Vec3(rng.unit() - 0.5, rng.unit() - 0.5, rng.unit() - 0.5);
        break;
      case 2:
        p += 0.6 * Vec3(rng.unit() - 0.5, rng.unit() - 0.5, rng.unit() - 0.5);
        break;
      case 3:
        p = s.vertices[rng.below(n)];
        break;
      default:
        p = 0.5 * (s.vertices[rng.below(n)] + s.vertices[rng.below(n)]);
    }
  }
  return s;
}

/// A section revolved into a closed mesh (what the vessel builder makes).
TriangleSoup revolved(int segments) {
  const std::vector<std::vector<Vec2>> loops = {{{0, 0}, {2, 0}, {2.5, 1}, {1.5, 2}, {1.2, 3}, {0, 3}}};
  return revolve(loops, RevolveOptions{segments}).soup;
}

/// A torus with one coordinate of 1e-35: the faces around it are outside
/// the filter's range and go to the exact test, the others do not.
TriangleSoup torus_with_tiny_coordinate() {
  TriangleSoup s = test::torus(3, 1, 40, 20);
  s.vertices[0].y() = 1e-35;  // was 0
  return s;
}

/// Faces of a voxel slab folded flat: vertex v moved within its face plane.
TriangleSoup coplanar_fold(Random& rng) {
  TriangleSoup s = test::slab_with_holes(1 + static_cast<int>(rng.below(2)));
  const std::uint32_t n = static_cast<std::uint32_t>(s.vertices.size());
  for (std::uint32_t m = 0; m < 2; ++m) {
    Vec3& p = s.vertices[rng.below(n)];
    const int axis = static_cast<int>(rng.below(3));
    p[axis] += (static_cast<double>(rng.below(5)) - 2.0) / 2.0;  // stays in the planes of the other axes
  }
  return s;
}

}  // namespace

TEST_CASE("self-intersection: the fast test equals the reference on the defect shapes",
          "[mesh][self_intersect]") {
  std::vector<TriangleSoup> shapes;
  TriangleSoup s = box();
  shapes.push_back(s);     // 1 a clean cube
  s.triangles.pop_back();  // 2 a cube with a hole
  shapes.push_back(s);
  s = box();
  append(s, box(Vec3(1, 1, 0), Vec3(2, 2, 1)));  // 3 two cubes touching along an edge
  shapes.push_back(s);
  s = box();
  append(s, box(Vec3(1, 0, 0), Vec3(2, 1, 1)));  // 4 two cubes touching face to face
  shapes.push_back(s);
  s = test::tetrahedron(Vec3(0, 0, 0), 1.0, +1);
  append(s, test::tetrahedron(Vec3(0, 0, 0), 1.0, -1));  // 5 two tetrahedra at one point
  shapes.push_back(s);
  s = box();
  append(s, box(Vec3(0.5, 0.25, 0.25), Vec3(1.5, 0.75, 0.75)));  // 6 overlapping cubes
  shapes.push_back(s);
  s = box();
  append(s, box(Vec3(0.25, 0.25, 0.25), Vec3(0.75, 0.75, 0.75)));  // 7 nested cubes
  shapes.push_back(s);
  s = TriangleSoup{};
  s.vertices = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, -1}, {0.5, 0.5, 1}, {3, 3, 0}};
  s.triangles = {{0, 1, 2}, {3, 5, 4}};  // 8 two crossing triangles
  shapes.push_back(s);
  s = TriangleSoup{};
  s.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.8, 0.6, 0}};
  s.triangles = {{0, 1, 2}, {0, 3, 1}};  // 9 a coplanar fold over a shared edge
  shapes.push_back(s);
  s.vertices[3] = {0.5, -1, 0};  // 10 a flat fold-out
  shapes.push_back(s);
  s = box();
  s.triangles.push_back({s.triangles[0][0], s.triangles[0][2], s.triangles[0][1]});  // 11 a duplicate face
  shapes.push_back(s);
  s = box();
  s.vertices.emplace_back(0.5, 0.0, 1.0);  // 12 a collinear sliver closing a split edge
  s.triangles[2] = {4, 8, 6};
  s.triangles.push_back({8, 5, 6});
  s.triangles.push_back({4, 5, 8});
  shapes.push_back(s);
  shapes.push_back(test::unwelded(box()));  // 13 an unwelded cube: every contact is a touch
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    INFO("shape " << i + 1);
    require_same(shapes[i], degenerate_faces(shapes[i]));
    require_same(shapes[i], {});
  }
}

TEST_CASE("self-intersection: the fast test equals the reference on closed meshes",
          "[mesh][self_intersect]") {
  for (const TriangleSoup& s : {test::torus(3, 1, 40, 20), test::sphere(2, 32, 16), test::slab_with_holes(3),
                                revolved(48), test::rotated(test::torus(3, 1.2, 30, 17), Vec3(1, 2, 3), 0.7),
                                test::countertop_slab(), torus_with_tiny_coordinate()}) {
    const SelfIntersections r = find_self_intersections(s);
    CHECK(r.count == 0);
    require_same(s, {});
  }
  // Two tori through each other: many pairs, fewer kept than counted.
  TriangleSoup two = test::torus(3, 1, 40, 20);
  append(two, test::rotated(test::torus(3, 1, 40, 20), Vec3(1, 0, 0), 1.5707963267948966));
  require_same(two, {}, 7);
  const SelfIntersections r = find_self_intersections(two);
  CHECK(r.count > 7);
}

TEST_CASE("self-intersection: coordinates beyond float range never reach the empty padding of the hierarchy",
          "[mesh][self_intersect]") {
  // A fuzzer's cube (12 faces: 3 leaves padded to 4) with a corner at 1e300:
  // its boxes reached both float infinities and so "overlapped" the empty
  // padding leaf, whose lanes hold no face.
  for (const double far : {1e300, -1e300, 1e39, 3.5e38}) {
    TriangleSoup s = box();
    REQUIRE(s.triangles.size() == 12);
    s.vertices[0] = Vec3(far, -far, far);
    INFO("far corner " << far);
    require_same(s, degenerate_faces(s));
    TriangleSoup two = box();
    append(two, s);
    require_same(two, degenerate_faces(two));
  }
}

TEST_CASE("self-intersection: the fast test equals the reference on thousands of random soups",
          "[mesh][self_intersect]") {
  Random rng(20261123);
  for (int trial = 0; trial < 3000; ++trial) {
    const TriangleSoup s = random_soup(rng);
    INFO("trial " << trial);
    require_same(s, degenerate_faces(s), 1 + rng.below(20));
  }
}

TEST_CASE("self-intersection: the fast test equals the reference on perturbed closed meshes",
          "[mesh][self_intersect]") {
  Random rng(7);
  const std::vector<TriangleSoup> bases = {test::torus(3, 1, 12, 8),
                                           test::sphere(1, 10, 6),
                                           box(),
                                           test::slab_with_holes(2),
                                           revolved(10),
                                           test::voxels({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {1, 1, 1}})};
  for (int trial = 0; trial < 1500; ++trial) {
    const TriangleSoup s = trial % 5 == 4 ? coplanar_fold(rng) : perturbed(bases[rng.below(6)], rng);
    INFO("trial " << trial);
    require_same(s, degenerate_faces(s), 1 + rng.below(20));
  }
}

TEST_CASE("self-intersection: a capped search counts exactly count_limit pairs, whatever the threads",
          "[mesh][self_intersect]") {
  // A pile of crossing triangles: every pair intersects.
  TriangleSoup pile;
  for (int i = 0; i < 60; ++i) {
    const auto b = static_cast<std::uint32_t>(pile.vertices.size());
    const double a = 0.05 * i;
    pile.vertices.push_back({std::cos(a), std::sin(a), -1});
    pile.vertices.push_back({-std::cos(a), -std::sin(a), -1});
    pile.vertices.push_back({0, 0, 1 + 0.01 * i});
    pile.triangles.push_back({b, b + 1, b + 2});
  }
  require_same(pile, {});  // 1770 pairs, under the reference's deterministic bound
  SelfIntersectOptions options;
  options.count_limit = 500;
  options.max_pairs = 30;
  const SelfIntersections expected = find_self_intersections_reference(pile, {}, options);
  const SelfIntersections parallel = find_self_intersections(pile, {}, options);
  options.parallel = false;
  const SelfIntersections sequential = find_self_intersections(pile, {}, options);
  CHECK(expected.capped);
  CHECK(parallel.capped);
  CHECK(parallel.count == 500);
  CHECK(parallel.count == expected.count);
  CHECK(parallel.pairs == sequential.pairs);
  CHECK(parallel.pairs.size() == 30);
  // The same count and pairs on 1, 2 and 3 threads.
  options.parallel = true;
  for (const int threads : {1, 2, 3}) {
    tbb::task_arena arena(threads);
    const SelfIntersections r = arena.execute([&] { return find_self_intersections(pile, {}, options); });
    CHECK(r.count == parallel.count);
    CHECK(r.pairs == parallel.pairs);
  }
  options.count_limit = 0;
  CHECK(find_self_intersections(pile, {}, options).count == 0);
}

TEST_CASE("self-intersection: bad input is an InputError", "[mesh][self_intersect]") {
  TriangleSoup s = box();
  s.vertices[3].x() = std::nan("");
  CHECK_THROWS_AS(find_self_intersections(s), InputError);
  s = box();
  s.triangles[0][1] = 99;
  CHECK_THROWS_AS(find_self_intersections(s), InputError);
  CHECK_THROWS_AS(find_self_intersections(box(), std::vector<char>(3, 0)), InputError);
}
