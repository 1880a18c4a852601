#include "geometry/mesh/weld.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <functional>
#include <iterator>
#include <numeric>
#include <random>

#include "geometry/core/errors.h"
#include "geometry/validation/validate.h"
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

namespace {

/// Portable random numbers (the standard distributions differ between libraries).
class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}
  std::uint32_t below(std::uint32_t n) { return static_cast<std::uint32_t>(engine_() % n); }
  double unit() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

 private:
  std::mt19937_64 engine_;
};

/// The documented semantics, by brute force: vertices i < j are one group
/// when a chain of steps with computed distance <= tol (or, with tol = 0,
/// exactly equal coordinates) links them; non-finite vertices are alone;
/// each group keeps its lowest index, in order of first occurrence.
WeldResult brute_force_weld(const TriangleSoup& soup, double tol) {
  const std::size_t n = soup.vertices.size();
  std::vector<std::uint32_t> rep(n);
  std::iota(rep.begin(), rep.end(), 0u);
  std::function<std::uint32_t(std::uint32_t)> root = [&](std::uint32_t i) {
    return rep[i] == i ? i : rep[i] = root(rep[i]);
  };
  for (std::uint32_t i = 0; i < n; ++i) {
    const Vec3& p = soup.vertices[i];
    if (!p.allFinite()) continue;
    for (std::uint32_t j = 0; j < i; ++j) {
      const Vec3& q = soup.vertices[j];
      if (!q.allFinite()) continue;
      const bool close = tol > 0.0 ? (q - p).norm() <= tol : q == p;
      if (!close) continue;
      const std::uint32_t a = root(i);
      const std::uint32_t b = root(j);
      rep[std::max(a, b)] = std::min(a, b);
    }
  }
  WeldResult w;
  std::vector<std::uint32_t> index(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    if (root(i) == i) {
      index[i] = static_cast<std::uint32_t>(w.soup.vertices.size());
      w.soup.vertices.push_back(soup.vertices[i]);
    } else {
      index[i] = index[root(i)];
    }
  }
  for (const auto& t : soup.triangles) w.soup.triangles.push_back({index[t[0]], index[t[1]], index[t[2]]});
  w.merged_vertices = n - w.soup.vertices.size();
  return w;
}

/// Points on a grid of `step` (exactly representable), some repeated, some
/// with -0.0, a few non-finite, in clusters so that tolerances of a few
/// steps chain some of them and not others; one triangle per three points.
TriangleSoup random_points(Random& rng, double step) {
  TriangleSoup s;
  const std::uint32_t n = 3 * (1 + rng.below(60));
  for (std::uint32_t i = 0; i < n; ++i) {
    Vec3 p;
    if (i > 0 && rng.below(4) == 0) {
      p = s.vertices[rng.below(i)];  // an exact repeat
    } else {
      for (int k = 0; k < 3; ++k) p[k] = step * (static_cast<double>(rng.below(9)) - 4.0);
    }
    if (rng.below(20) == 0) p.x() = -0.0 * p.x();  // -0.0 or +0.0
    if (rng.below(40) == 0) p.y() = rng.below(2) ? std::nan("") : INFINITY;
    s.vertices.push_back(p);
  }
  for (std::uint32_t i = 0; i + 2 < n; i += 3) s.triangles.push_back({i, i + 1, i + 2});
  return s;
}

void require_same_weld(const TriangleSoup& s, double tol) {
  const WeldResult got = weld(s, WeldOptions{tol});
  const WeldResult expected = brute_force_weld(s, tol);
  REQUIRE(got.merged_vertices == expected.merged_vertices);
  REQUIRE(got.soup.triangles == expected.soup.triangles);
  REQUIRE(got.soup.vertices.size() == expected.soup.vertices.size());
  for (std::size_t i = 0; i < got.soup.vertices.size(); ++i) {
    const Vec3& a = got.soup.vertices[i];
    const Vec3& b = expected.soup.vertices[i];
    REQUIRE(std::memcmp(a.data(), b.data(), sizeof(double) * 3) ==
            0);  // the same vertex, NaN and -0.0 included
  }
}

}  // namespace

TEST_CASE("weld: exact and tolerance welds equal the brute-force closure on random points", "[mesh][weld]") {
  Random rng(42);
  for (int trial = 0; trial < 400; ++trial) {
    INFO("trial " << trial);
    const double step = trial % 2 ? 0.25 : 0.1;  // dyadic: distances exactly at the tolerance occur
    const TriangleSoup s = random_points(rng, step);
    require_same_weld(s, 0.0);
    // Tolerances at, between and beyond the grid distances (step, step * sqrt 2, ...).
    for (const double k : {0.5, 1.0, std::sqrt(2.0), 2.0, 3.0, 7.0, 100.0}) require_same_weld(s, k * step);
  }
}

TEST_CASE("weld: a mesh of float coordinates (every STL) welds as one of doubles does", "[mesh][weld]") {
  // The weld keys a mesh whose coordinates are all floats by those floats
  // (half the memory). One coordinate that is not a float sends the whole
  // mesh through the doubles: two doubles that round to one float must not merge.
  TriangleSoup near;
  near.vertices = {{1, 0, 0}, {1 + std::ldexp(1.0, -30), 0, 0}, {0, 1, 0}, {1, 0, 0}};
  near.triangles = {{0, 1, 2}, {3, 2, 1}};
  CHECK(weld(near).merged_vertices == 1);  // only the exact repeat of vertex 0
  require_same_weld(near, 0.0);

  // Float coordinates of every kind: extremes, subnormals, -0.0, repeats,
  // non-finite ones; the same groups as the brute force, and the same
  // again with one vertex that is not a float added at the end.
  Random rng(7);
  const float specials[] = {0.0F, -0.0F, 1.0F, -1.0F, 3.0e38F, -3.0e38F, 1.0e-40F, -1.0e-40F, 0.1F, 1e-7F};
  for (int trial = 0; trial < 200; ++trial) {
    INFO("trial " << trial);
    TriangleSoup s;
    const std::uint32_t n = 3 * (1 + rng.below(40));
    for (std::uint32_t i = 0; i < n; ++i) {
      Vec3 p;
      if (i > 0 && rng.below(3) == 0) {
        p = s.vertices[rng.below(i)];
        if (rng.below(4) == 0) p.z() = -0.0 * p.z();
      } else {
        for (int k = 0; k < 3; ++k)
          p[k] = specials[rng.below(static_cast<std::uint32_t>(std::size(specials)))];
      }
      if (rng.below(30) == 0) p.y() = rng.below(2) ? std::nan("") : -INFINITY;
      s.vertices.push_back(p);
    }
    for (std::uint32_t i = 0; i + 2 < n; i += 3) s.triangles.push_back({i, i + 1, i + 2});
    require_same_weld(s, 0.0);
    TriangleSoup mixed = s;
    mixed.vertices.push_back({0.1, 0.2, 0.3});  // not floats
    mixed.vertices.push_back(s.vertices[0]);
    mixed.vertices.push_back({0.1, 0.2, 0.3});
    mixed.triangles.push_back({n, n + 1, n + 2});
    require_same_weld(mixed, 0.0);
    const WeldResult a = weld(s);
    const WeldResult b = weld(mixed);
    REQUIRE(b.soup.triangles.size() == a.soup.triangles.size() + 1);
    REQUIRE(std::equal(a.soup.triangles.begin(), a.soup.triangles.end(), b.soup.triangles.begin()));
  }
}

TEST_CASE("weld: points on both sides of a cell boundary and at negative coordinates chain correctly",
          "[mesh][weld]") {
  // A chain along each axis through 0, with steps exactly the tolerance:
  // every link is within tolerance (computed distance == tol).
  for (int axis = 0; axis < 3; ++axis) {
    TriangleSoup s;
    for (int i = -20; i <= 20; ++i) {
      Vec3 p(0.3, -0.7, 1.1);
      p[axis] = 0.125 * i;
      s.vertices.push_back(p);
    }
    for (std::uint32_t i = 0; i + 2 < s.vertices.size(); i += 3) s.triangles.push_back({i, i + 1, i + 2});
    CHECK(weld(s, WeldOptions{0.125}).soup.vertices.size() == 1);
    CHECK(weld(s, WeldOptions{0.1249}).soup.vertices.size() == s.vertices.size());
    require_same_weld(s, 0.125);
  }
}

TEST_CASE("weld: a tolerance larger than the model merges every vertex of a large mesh in linear time",
          "[mesh][weld][time-bounded]") {
  // 1e5 STL triangles: 3e5 vertices, all in one grid cell of the old
  // tolerance weld, which compared them pairwise (4.5e10 distances: minutes).
  // ctest stops this test after 60 s (tests/CMakeLists.txt).
  const TriangleSoup torus = test::unwelded(test::torus(3, 1, 250, 200));
  REQUIRE(torus.vertices.size() == 300000);
  const WeldResult all = weld(torus, WeldOptions{100.0});
  CHECK(all.soup.vertices.size() == 1);
  CHECK(all.merged_vertices == torus.vertices.size() - 1);
  // Two such tori 1000 apart stay two vertices; 20 apart (closer than the tolerance), one.
  TriangleSoup two = torus;
  TriangleSoup moved = torus;
  for (Vec3& p : moved.vertices) p.x() += 1000.0;
  test::append(two, moved);
  CHECK(weld(two, WeldOptions{100.0}).soup.vertices.size() == 2);
  for (Vec3& p : two.vertices) {
    if (p.x() > 500.0) p.x() -= 980.0;
  }
  CHECK(weld(two, WeldOptions{100.0}).soup.vertices.size() == 1);
  // A fine tolerance on the same mesh restores the exact weld's vertices.
  CHECK(weld(torus, WeldOptions{1e-9}).soup.vertices.size() == 250 * 200);
}
