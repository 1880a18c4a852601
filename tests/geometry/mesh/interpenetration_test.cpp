// interpenetrating_pairs: overlap of insides, never touching.

#include "geometry/mesh/interpenetration.h"

#include <catch2/catch.hpp>

#include "tests/geometry/mesh/shapes.h"

using namespace fabmesh;

namespace {

using Pairs = std::vector<std::pair<std::size_t, std::size_t>>;

Pairs pairs_of(const std::vector<TriangleSoup>& solids) {
  std::vector<const TriangleSoup*> pointers;
  for (const TriangleSoup& s : solids) pointers.push_back(&s);
  return interpenetrating_pairs(pointers).pairs;
}

TriangleSoup moved(TriangleSoup soup, const Vec3& by) {
  for (Vec3& p : soup.vertices) p += by;
  return soup;
}

}  // namespace

TEST_CASE("interpenetration: touching on a face, an edge or a corner is not overlap", "[mesh][objects]") {
  const TriangleSoup cube = test::box();
  CHECK(pairs_of({cube, moved(cube, Vec3(1, 0, 0))}).empty());
  CHECK(pairs_of({cube, moved(cube, Vec3(1, 1, 0))}).empty());
  CHECK(pairs_of({cube, moved(cube, Vec3(1, 1, 1))}).empty());
  CHECK(pairs_of({cube, moved(cube, Vec3(0.5, 1, 0.5))}).empty());  // a face half on another
  CHECK(pairs_of({cube, moved(cube, Vec3(3, 0, 0))}).empty());
}

TEST_CASE("interpenetration: a corner inside, crossing edges or coinciding faces are overlap",
          "[mesh][objects]") {
  const TriangleSoup cube = test::box();
  CHECK(pairs_of({cube, moved(cube, Vec3(0.5, 0.5, 0.5))}) == Pairs{{0, 1}});
  CHECK(pairs_of({cube, cube}) == Pairs{{0, 1}});                          // faces coincide, facing alike
  CHECK(pairs_of({cube, moved(cube, Vec3(0.5, 0, 0))}) == Pairs{{0, 1}});  // sliding along a face
  const TriangleSoup along_x = test::box(Vec3(0, 1, 0), Vec3(3, 2, 1));
  const TriangleSoup along_y = test::box(Vec3(1, 0, -0.5), Vec3(2, 3, 1.5));
  CHECK(pairs_of({along_x, along_y}) == Pairs{{0, 1}});  // no corner inside: edges cross faces
  CHECK(pairs_of({test::box(Vec3(-1, -1, -1), Vec3(2, 2, 2)), cube}) == Pairs{{0, 1}});  // one inside
}

TEST_CASE("interpenetration: null entries are not judged, pairs come in order", "[mesh][objects]") {
  const TriangleSoup cube = test::box();
  const TriangleSoup inside = moved(cube, Vec3(0.5, 0.5, 0.5));
  const TriangleSoup far = moved(cube, Vec3(5, 0, 0));
  const TriangleSoup far_inside = moved(cube, Vec3(5.5, 0.5, 0.5));
  CHECK(interpenetrating_pairs({&cube, nullptr, &inside}).pairs == Pairs{{0, 2}});
  CHECK(interpenetrating_pairs({&far, &cube, &far_inside, &inside}).pairs == Pairs{{0, 2}, {1, 3}});
  CHECK(interpenetrating_pairs({}).pairs.empty());
  CHECK(interpenetrating_pairs({&cube, &inside}).complete);
}

TEST_CASE("interpenetration: the work bound stops a pile of bodies", "[mesh][objects]") {
  std::vector<TriangleSoup> pile;
  for (int i = 0; i < 50; ++i)
    pile.push_back(moved(test::box(Vec3(0, 0, 0), Vec3(10, 1, 1)), Vec3(0.01 * i, 0, 0)));
  std::vector<const TriangleSoup*> pointers;
  for (const TriangleSoup& s : pile) pointers.push_back(&s);
  const Interpenetration all = interpenetrating_pairs(pointers);
  CHECK(all.complete);
  CHECK(all.pairs.size() == 50 * 49 / 2);
  const Interpenetration bounded = interpenetrating_pairs(pointers, 250);  // 10 pairs of 24 triangles and 1
  CHECK_FALSE(bounded.complete);
  CHECK(bounded.pairs.size() == 10);
  CHECK(interpenetration_work_bound(1000) == 116000);
}
