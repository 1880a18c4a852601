#include "geometry/validation/validate.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "geometry/core/errors.h"
#include "geometry/mesh/halfedge_mesh.h"
#include "geometry/mesh/volume.h"
#include "geometry/mesh/weld.h"
#include "geometry/validation/detail/self_intersect.h"
#include "tests/geometry/mesh/shapes.h"

using namespace fabmesh;
using fabmesh::test::append;
using fabmesh::test::box;

namespace {

const double kPi = std::acos(-1.0);

/// Everything that makes a mesh invalid is absent.
void require_clean(const ValidationReport& r) {
  CHECK(r.boundary_edges == 0);
  CHECK(r.non_manifold_edges == 0);
  CHECK(r.non_manifold_vertices == 0);
  CHECK(r.degenerate_faces == 0);
  CHECK(r.duplicate_faces == 0);
  CHECK_FALSE(r.self_intersecting);
  CHECK(r.consistently_oriented);
  CHECK(r.oriented_outward);
  CHECK(r.defects.empty());
  CHECK(r.valid());
}

}  // namespace

TEST_CASE("validate: a closed cube is valid, genus 0, with exact volume and area", "[mesh][validate]") {
  const ValidationReport r = validate(box(Vec3(-1, 2, 3), Vec3(1, 5, 4)));
  require_clean(r);
  CHECK(r.vertices == 8);
  CHECK(r.triangles == 12);
  CHECK(r.components == 1);
  REQUIRE(r.genus);
  CHECK(*r.genus == 0);
  CHECK(r.volume == Approx(2.0 * 3.0 * 1.0));
  CHECK(r.area == Approx(2 * (6.0 + 2.0 + 3.0)));
  CHECK(r.timings_ms.size() == 3);
}

TEST_CASE("validate: a UV sphere with pole vertices is genus 0 and encloses nearly 4/3 pi r^3",
          "[mesh][validate]") {
  const ValidationReport r = validate(test::sphere(2.0, 64, 32));
  require_clean(r);
  REQUIRE(r.genus);
  CHECK(*r.genus == 0);
  const double exact = 4.0 / 3.0 * kPi * 8.0;
  CHECK(r.volume < exact);  // inscribed polyhedron
  CHECK(r.volume == Approx(exact).epsilon(0.01));
  CHECK(r.area == Approx(4 * kPi * 4.0).epsilon(0.01));
}

TEST_CASE("validate: a torus is genus 1 with Pappus volume and area, also when rotated", "[mesh][validate]") {
  const double R = 3.0, r = 1.0;
  const TriangleSoup torus = test::torus(R, r, 96, 48);
  for (const TriangleSoup& soup : {torus, test::rotated(torus, Vec3(1, 2, 3), 0.7)}) {
    const ValidationReport rep = validate(soup);
    require_clean(rep);
    REQUIRE(rep.genus);
    CHECK(*rep.genus == 1);
    CHECK(rep.euler_characteristics == std::vector<long>{0});
    CHECK(rep.volume == Approx(2 * kPi * kPi * R * r * r).epsilon(0.01));
    CHECK(rep.area == Approx(4 * kPi * kPi * R * r).epsilon(0.01));
  }
}

TEST_CASE("validate: a slab with two holes is a double torus (genus 2), one hole genus 1",
          "[mesh][validate]") {
  for (int holes : {1, 2, 3}) {
    const TriangleSoup slab = test::slab_with_holes(holes);
    const ValidationReport r = validate(slab);
    require_clean(r);
    REQUIRE(r.genus);
    CHECK(*r.genus == holes);
    CHECK(r.volume == Approx(3.0 * (2 * holes + 1) - holes));  // one per voxel
  }
}

TEST_CASE("validate: two disjoint closed boxes are valid with two components and genus 0",
          "[mesh][validate]") {
  TriangleSoup s = box();
  append(s, test::torus(3.0, 1.0, 32, 16));
  append(s, box(Vec3(10, 0, 0), Vec3(11, 1, 1)));
  const ValidationReport r = validate(s);
  require_clean(r);
  CHECK(r.components == 3);
  REQUIRE(r.genus);
  CHECK(*r.genus == 1);  // the sum over components
  CHECK(r.euler_characteristics == std::vector<long>{2, 0, 2});
}

TEST_CASE("validate: a hole is three boundary edges and no genus", "[mesh][validate]") {
  TriangleSoup s = box();
  s.triangles.pop_back();
  const ValidationReport r = validate(s);
  CHECK(r.boundary_edges == 3);
  CHECK(r.non_manifold_edges == 0);
  CHECK(r.non_manifold_vertices == 0);
  CHECK_FALSE(r.genus);
  CHECK_FALSE(r.valid());
  REQUIRE(r.find(Defect::BoundaryEdge));
  CHECK(r.find(Defect::BoundaryEdge)->count == 3);
  CHECK(r.find(Defect::BoundaryEdge)->examples.size() == 3);
  // Every example is the midpoint of an edge of the missing face (x = 1).
  for (const Vec3& p : r.find(Defect::BoundaryEdge)->examples) CHECK(p.x() == 1.0);
  CHECK(r.find(Defect::InsideOut) == nullptr);  // volume is not judged on an open mesh
}

TEST_CASE("validate: one flipped face gives three inconsistent edges", "[mesh][validate]") {
  TriangleSoup s = box();
  std::swap(s.triangles[4][1], s.triangles[4][2]);
  const ValidationReport r = validate(s);
  CHECK(r.inconsistent_edges == 3);
  CHECK_FALSE(r.consistently_oriented);
  CHECK(r.boundary_edges == 0);
  CHECK(r.non_manifold_edges == 0);
  CHECK_FALSE(r.genus);
  CHECK_FALSE(r.valid());
  REQUIRE(r.find(Defect::InconsistentOrientation));
}

TEST_CASE("validate: a T-junction leaves three boundary edges on the split edge", "[mesh][validate]") {
  // Split the top face's edge from (0,0,1) to (1,0,1) at its midpoint M, but
  // not the side face (y = 0) that shares the edge.
  TriangleSoup s = box();
  s.vertices.emplace_back(0.5, 0.0, 1.0);
  const std::uint32_t m = 8;
  // Top face was {4,5,6}, {5,7,6}; replace {4,5,6} by {4,m,6}, {m,5,6}.
  s.triangles[2] = {4, m, 6};
  s.triangles.push_back({m, 5, 6});
  const ValidationReport r = validate(s);
  CHECK(r.boundary_edges == 3);  // 4-5 on the side, 4-m and m-5 on the top
  CHECK(r.non_manifold_edges == 0);
  for (const Vec3& p : r.find(Defect::BoundaryEdge)->examples) {
    CHECK(p.y() == 0.0);
    CHECK(p.z() == 1.0);
  }
  CHECK_FALSE(r.valid());
}

TEST_CASE("validate: two cubes sharing an edge give one non-manifold edge and two non-manifold vertices",
          "[mesh][validate]") {
  TriangleSoup s = box();
  append(s, box(Vec3(1, 1, 0), Vec3(2, 2, 1)));
  const TriangleSoup welded = weld(s).soup;
  const ValidationReport r = validate(welded);
  CHECK(r.vertices == 14);
  CHECK(r.non_manifold_edges == 1);
  CHECK(r.non_manifold_vertices == 2);
  CHECK(r.boundary_edges == 0);
  CHECK(r.components == 1);
  CHECK_FALSE(r.self_intersecting);  // they touch only along the shared edge
  CHECK(r.find(Defect::NonManifoldEdge)->examples.at(0).isApprox(Vec3(1, 1, 0.5)));
  CHECK_FALSE(r.genus);
  CHECK_FALSE(r.valid());
}

TEST_CASE("validate: two tetrahedra sharing a vertex give one non-manifold vertex", "[mesh][validate]") {
  TriangleSoup s = test::tetrahedron(Vec3(0, 0, 0), 1.0, +1);
  append(s, test::tetrahedron(Vec3(0, 0, 0), 1.0, -1));
  const TriangleSoup welded = weld(s).soup;
  const ValidationReport r = validate(welded);
  CHECK(r.vertices == 7);
  CHECK(r.non_manifold_vertices == 1);
  CHECK(r.find(Defect::NonManifoldVertex)->examples.at(0) == Vec3(0, 0, 0));
  CHECK(r.non_manifold_edges == 0);
  CHECK(r.boundary_edges == 0);
  CHECK(r.components == 1);
  CHECK(r.consistently_oriented);
  CHECK(r.oriented_outward);
  CHECK_FALSE(r.self_intersecting);
  CHECK_FALSE(r.valid());
}

TEST_CASE("validate: two crossing triangles are exactly one intersecting pair", "[mesh][validate]") {
  TriangleSoup s;
  s.vertices = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, -1}, {0.5, 0.5, 1}, {3, 3, 0}};
  s.triangles = {{0, 1, 2}, {3, 5, 4}};
  const ValidationReport r = validate(s);
  CHECK(r.self_intersecting);
  CHECK(r.intersecting_pairs == 1);
  CHECK(r.find(Defect::SelfIntersection)->count == 1);
}

TEST_CASE("validate: overlapping closed cubes self-intersect but are otherwise clean", "[mesh][validate]") {
  TriangleSoup s = box();
  append(s, box(Vec3(0.5, 0.25, 0.25), Vec3(1.5, 0.75, 0.75)));
  const ValidationReport r = validate(s);
  CHECK(r.self_intersecting);
  CHECK(r.intersecting_pairs > 0);
  CHECK(r.boundary_edges == 0);
  CHECK(r.non_manifold_edges == 0);
  CHECK(r.components == 2);
  CHECK_FALSE(r.valid());
  // The parallel and the sequential search find the same pairs.
  SelfIntersectOptions sequential;
  sequential.parallel = false;
  SelfIntersectOptions parallel;
  CHECK(find_self_intersections(s, {}, sequential).pairs == find_self_intersections(s, {}, parallel).pairs);
}

TEST_CASE("validate: coplanar faces folding back over a shared edge intersect", "[mesh][validate]") {
  TriangleSoup s;
  s.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.8, 0.6, 0}};
  s.triangles = {{0, 1, 2}, {0, 3, 1}};  // both on the same side of edge 0-1
  CHECK(validate(s).intersecting_pairs == 1);
  s.vertices[3] = {0.5, -1, 0};  // now on the other side: a flat, valid fold-out
  CHECK(validate(s).intersecting_pairs == 0);
}

TEST_CASE("validate: a duplicate face is counted once, in either orientation", "[mesh][validate]") {
  for (bool flipped : {false, true}) {
    TriangleSoup s = box();
    auto copy = s.triangles[0];
    if (flipped) std::swap(copy[1], copy[2]);
    s.triangles.push_back(copy);
    const ValidationReport r = validate(s);
    CHECK(r.duplicate_faces == 1);
    CHECK(r.non_manifold_edges == 3);  // the face's edges now have three faces
    CHECK_FALSE(r.self_intersecting);  // duplicates are reported as duplicates only
    CHECK_FALSE(r.valid());
  }
}

TEST_CASE("validate: zero-area faces are degenerate, by repeated index or collinear corners",
          "[mesh][validate]") {
  SECTION("a repeated index") {
    TriangleSoup s = box();
    s.triangles.push_back({0, 0, 7});
    const ValidationReport r = validate(s);
    CHECK(r.degenerate_faces == 1);
    CHECK(r.boundary_edges == 0);  // not a triangle: it takes no part in topology
    CHECK_FALSE(r.valid());
  }
  SECTION("collinear corners closing a split edge") {
    // Top face split at M on edge 4-5; the sliver {4, 5, m} closes the gap.
    TriangleSoup s = box();
    s.vertices.emplace_back(0.5, 0.0, 1.0);
    const std::uint32_t m = 8;
    s.triangles[2] = {4, m, 6};
    s.triangles.push_back({m, 5, 6});
    s.triangles.push_back({4, 5, m});
    const ValidationReport r = validate(s);
    CHECK(r.degenerate_faces == 1);
    CHECK(r.boundary_edges == 0);
    CHECK(r.non_manifold_edges == 0);
    CHECK(r.find(Defect::DegenerateFace)->examples.at(0).isApprox(Vec3(0.5, 0, 1)));
    CHECK(r.volume == Approx(1.0));
    CHECK_FALSE(r.valid());
  }
}

TEST_CASE("validate: an inside-out closed mesh is consistent but not outward", "[mesh][validate]") {
  TriangleSoup s = box();
  for (auto& t : s.triangles) std::swap(t[1], t[2]);
  const ValidationReport r = validate(s);
  CHECK(r.consistently_oriented);
  CHECK_FALSE(r.oriented_outward);
  CHECK(r.volume == Approx(-1.0));
  REQUIRE(r.find(Defect::InsideOut));
  CHECK(r.defects.size() == 1);
  CHECK_FALSE(r.valid());
}

TEST_CASE("validate: an empty soup and non-finite vertices are invalid, never a crash", "[mesh][validate]") {
  CHECK(validate(TriangleSoup{}).find(Defect::Empty));
  CHECK_FALSE(validate(TriangleSoup{}).valid());
  TriangleSoup s = box();
  s.vertices[3].x() = std::nan("");
  const ValidationReport r = validate(s);
  CHECK(r.non_finite_vertices == 1);
  CHECK(r.self_intersection == IntersectionCheck::NotRun);
  CHECK_FALSE(r.valid());
}

TEST_CASE("validate: an index out of range is an InputError", "[mesh][validate]") {
  TriangleSoup s = box();
  s.triangles.push_back({0, 1, 8});
  CHECK_THROWS_AS(validate(s), InputError);
}

TEST_CASE("validate: skipping the self-intersection test never yields valid", "[mesh][validate]") {
  ValidationOptions options;
  options.check_self_intersections = false;
  const ValidationReport r = validate(box(), options);
  CHECK(r.defects.empty());
  CHECK_FALSE(r.valid());
}

TEST_CASE("require_valid: throws ValidationFailed listing every defect, passes a valid mesh",
          "[mesh][validate]") {
  CHECK_NOTHROW(require_valid(validate(box()), "cube"));
  TriangleSoup s = box();
  s.triangles.pop_back();
  s.triangles.push_back({0, 0, 1});
  try {
    require_valid(validate(s), "vessel 'cup'");
    FAIL("no exception");
  } catch (const ValidationFailed& e) {
    const std::string message = e.what();
    CHECK(message.find("vessel 'cup'") == 0);
    CHECK(message.find("3 boundary edges") != std::string::npos);
    CHECK(message.find("1 degenerate faces") != std::string::npos);
  }
}

TEST_CASE("validate: a Mesh (through to_soup) and its soup give the same report", "[mesh][validate]") {
  const TriangleSoup torus = test::torus(2.0, 0.5, 24, 12);
  const SoupToMesh converted = to_mesh(torus);
  CHECK(converted.refused_faces == 0);
  const ValidationReport a = validate(to_soup(converted.mesh));
  const ValidationReport b = validate(torus);
  CHECK(a.valid());
  CHECK(a.genus == b.genus);
  CHECK(a.volume == Approx(b.volume));
  // The same faces with the same orientation (OpenMesh may start each face at another corner).
  auto canonical = [](std::vector<std::array<std::uint32_t, 3>> tris) {
    for (auto& t : tris) std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    return tris;
  };
  CHECK(canonical(to_soup(converted.mesh).triangles) == canonical(torus.triangles));
}

TEST_CASE("to_mesh: faces OpenMesh refuses are counted, never dropped silently", "[mesh][soup]") {
  TriangleSoup s;
  s.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  s.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}, {2, 2, 1}};  // a third face on edge 0-1, a repeated index
  const SoupToMesh m = to_mesh(s);
  CHECK(m.refused_faces == 2);
  CHECK(m.mesh.n_faces() + m.refused_faces == s.triangles.size());
}

TEST_CASE("validate: a builder's proofs replace the connectivity analysis and the 3D test",
          "[mesh][validate]") {
  const TriangleSoup s = box();
  ValidationOptions proven;
  proven.topology = TopologyProof{"a box by construction", 1, {2}};
  proven.embedding = EmbeddingProof{"a convex box", 0.25};
  const ValidationReport r = validate(s, proven);
  const ValidationReport full = validate(s);
  CHECK(r.valid());
  CHECK(r.self_intersection == IntersectionCheck::ProvenByConstruction);
  CHECK(r.embedding_proof == "a convex box");
  CHECK(r.embedding_margin == 0.25);
  CHECK(r.topology_proof == "a box by construction");
  CHECK(r.genus == full.genus);
  CHECK(r.volume == full.volume);
  CHECK(r.area == full.area);
  CHECK(r.volume == signed_volume(s));
  // A proof about the exact construction says nothing about NaNs.
  TriangleSoup nan = s;
  nan.vertices[0].x() = std::nan("");
  const ValidationReport bad = validate(nan, proven);
  CHECK(bad.self_intersection == IntersectionCheck::NotRun);
  CHECK_FALSE(bad.valid());
}

TEST_CASE("validate: a moved copy takes its proofs from the original's report only", "[mesh][validate]") {
  const TriangleSoup s = box();
  const ValidationReport report = validate(s);
  ValidationOptions options;
  options.moved_from = MovedFrom{&s, &report};
  CHECK(validate(s, options).valid());
  options.embedding = EmbeddingProof{"a convex box", 0.25};
  CHECK_THROWS_AS(validate(s, options), InputError);
}

TEST_CASE("fit_for: fabrication needs a valid mesh, viewing tolerates only an open border",
          "[mesh][validate]") {
  const ValidationReport closed = validate(box());
  CHECK(fit_for(closed, MeshPurpose::Fabrication));
  CHECK(fit_for(closed, MeshPurpose::Viewing));
  TriangleSoup open = box();
  open.triangles.pop_back();
  const ValidationReport holed = validate(open);
  CHECK_FALSE(fit_for(holed, MeshPurpose::Fabrication));
  CHECK(fit_for(holed, MeshPurpose::Viewing));
  CHECK(fit_for(holed, MeshPurpose::Drawing));
  open.triangles.push_back({0, 0, 1});  // a degenerate face besides the border
  CHECK_FALSE(fit_for(validate(open), MeshPurpose::Viewing));
  ValidationOptions untested;
  untested.check_self_intersections = false;
  CHECK_FALSE(fit_for(validate(box(), untested), MeshPurpose::Viewing));
}

TEST_CASE("valid_when_moved: unmoved, or moved less than the embedding margin", "[mesh][validate]") {
  ValidationOptions proven;
  proven.embedding = EmbeddingProof{"a convex box", 0.25};
  const ValidationReport r = validate(box(), proven);
  CHECK(valid_when_moved(r, 0.0));
  CHECK(valid_when_moved(r, 0.2));
  CHECK_FALSE(valid_when_moved(r, 0.25));
  const ValidationReport tested = validate(box());  // no margin: only an exact copy stays proven
  CHECK(valid_when_moved(tested, 0.0));
  CHECK_FALSE(valid_when_moved(tested, 1e-12));
  TriangleSoup open = box();
  open.triangles.pop_back();
  CHECK_FALSE(valid_when_moved(validate(open), 0.0));
}
