// certify_planar_patches: faces in one axis plane proven pairwise apart as a
// whole (a countertop's top and bottom), and never when they fold or
// overlap; the self-intersection test stays the reference's either way.

#include "geometry/validation/detail/planar_patch.h"

#include <catch2/catch.hpp>
#include <set>

#include "geometry/mesh/halfedge_mesh.h"
#include "geometry/mesh/slab.h"
#include "geometry/section/region.h"
#include "tests/geometry/mesh/shapes.h"
#include "tests/geometry/section/region_shapes.h"
#include "tests/geometry/validation/same_as_reference.h"
#include "tests/geometry/validation/sliver_shapes.h"

using namespace fabmesh;
using fabmesh::detail::certify_planar_patches;
using fabmesh::detail::kNoPatch;

namespace {

/// The faces of `s` with every corner at height z.
std::set<std::uint32_t> faces_at(const TriangleSoup& s, double z) {
  std::set<std::uint32_t> out;
  for (std::uint32_t f = 0; f < s.triangles.size(); ++f) {
    const auto& t = s.triangles[f];
    if (s.vertices[t[0]].z() == z && s.vertices[t[1]].z() == z && s.vertices[t[2]].z() == z) out.insert(f);
  }
  return out;
}

}  // namespace

TEST_CASE("planar patches: a countertop's top and bottom are certified, every face of them",
          "[mesh][validate][patches]") {
  const TriangleSoup s = test::countertop_slab();
  const auto patches = certify_planar_patches(s, {});
  REQUIRE(patches.axis.size() >= 2);
  double top = 0.0;
  for (const Vec3& p : s.vertices) top = std::max(top, p.z());
  for (const double z : {0.0, top}) {
    const auto faces = faces_at(s, z);
    REQUIRE(faces.size() > 64);
    const std::uint32_t id = s.triangles.empty() ? kNoPatch : patches.patch[*faces.begin()];
    REQUIRE(id != kNoPatch);
    CHECK(patches.axis[id] == 2);
    CHECK(patches.level[id] == z);
    for (const std::uint32_t f : faces) CHECK(patches.patch[f] == id);
  }
  test::require_same(s);
}

TEST_CASE("planar patches: a fold in the plane, or a second patch on top, is never certified",
          "[mesh][validate][patches]") {
  const TriangleSoup s = test::countertop_slab();
  double top = 0.0;
  for (const Vec3& p : s.vertices) top = std::max(top, p.z());
  {  // a vertex of the top moved across its neighbours, in the plane: faces fold over each other
    TriangleSoup folded = s;
    const auto faces = faces_at(s, top);
    const std::uint32_t v = s.triangles[*faces.begin()][0];
    folded.vertices[v].x() += 700.0;
    const auto patches = certify_planar_patches(folded, {});
    for (const std::uint32_t f : faces_at(folded, top)) CHECK(patches.patch[f] == kNoPatch);
    CHECK(test::require_same(folded).count > 0);
  }
  {  // a box standing on the top, its bottom in the top's plane and facing down: two layers there
    TriangleSoup stacked = s;
    TriangleSoup cube = test::box(Vec3(600, 250, top), Vec3(700, 350, top + 50));
    test::append(stacked, cube);
    const auto patches = certify_planar_patches(stacked, {}, 1);
    for (const std::uint32_t f : faces_at(stacked, top)) CHECK(patches.patch[f] == kNoPatch);
    CHECK(test::require_same(stacked).count > 0);
  }
  {  // a square patch lying inside the top, facing up like it: covered twice
    TriangleSoup doubled = s;
    const auto n = static_cast<std::uint32_t>(doubled.vertices.size());
    for (const Vec3& p : {Vec3(600, 250, top), Vec3(700, 250, top), Vec3(700, 350, top), Vec3(600, 350, top)})
      doubled.vertices.push_back(p);
    doubled.triangles.push_back({n, n + 1, n + 2});
    doubled.triangles.push_back({n, n + 2, n + 3});
    const auto patches = certify_planar_patches(doubled, {}, 1);
    for (const std::uint32_t f : faces_at(doubled, top)) CHECK(patches.patch[f] == kNoPatch);
    CHECK(test::require_same(doubled).count > 0);
  }
}
