#include "geometry/mesh/halfedge_topology.h"

#include <catch2/catch.hpp>

#include "geometry/curves/curve_spec.h"
#include "geometry/mesh/soup.h"
#include "geometry/mesh/topology.h"
#include "geometry/mesh/vessel.h"

using namespace fabmesh;

namespace {

void check_same(const Topology& a, const Topology& b) {
  CHECK(a.referenced_vertices == b.referenced_vertices);
  CHECK(a.edges == b.edges);
  CHECK(a.boundary_edges.count == b.boundary_edges.count);
  CHECK(a.non_manifold_edges.count == b.non_manifold_edges.count);
  CHECK(a.non_manifold_vertices.count == b.non_manifold_vertices.count);
  CHECK(a.inconsistent_edges.count == b.inconsistent_edges.count);
  CHECK(a.duplicate_faces.count == b.duplicate_faces.count);
  CHECK(a.components == b.components);
  CHECK(a.euler_characteristics == b.euler_characteristics);
}

TriangleSoup tetrahedron(const Vec3& o, std::uint32_t base) {
  TriangleSoup s;
  s.vertices = {o, o + Vec3(1, 0, 0), o + Vec3(0, 1, 0), o + Vec3(0, 0, 1)};
  s.triangles = {{base + 0, base + 2, base + 1},
                 {base + 0, base + 1, base + 3},
                 {base + 0, base + 3, base + 2},
                 {base + 1, base + 2, base + 3}};
  return s;
}

}  // namespace

TEST_CASE("halfedge topology agrees with the soup analysis on valid meshes", "[mesh][topology]") {
  CurveSpec spec;
  spec.family = CurveFamily::QuasiBSpline;
  spec.bspline_points = {{1.5, 6}, {1, 5}, {2, 4}, {3, 3}, {1.5, 2}};
  VesselOptions o;
  o.tolerance = 0.02;
  o.mode = BodyMode::Shell;
  o.wall = 0.3;
  const SoupToMesh built = to_mesh(build_vessel(construct_curve(spec), o).soup);
  REQUIRE(built.refused_faces == 0);
  const Mesh& mesh = built.mesh;
  const Topology t = analyse_topology(mesh);
  check_same(t, analyse_topology(to_soup(mesh)));
  CHECK(t.euler_characteristics == std::vector<long>{2});
}

TEST_CASE("halfedge topology finds holes, pinched vertices and duplicate pairs like the soup analysis",
          "[mesh][topology]") {
  SECTION("a hole") {
    TriangleSoup s = tetrahedron(Vec3::Zero(), 0);
    s.triangles.pop_back();
    const SoupToMesh m = to_mesh(s);
    REQUIRE(m.refused_faces == 0);
    check_same(analyse_topology(m.mesh), analyse_topology(s));
    CHECK(analyse_topology(m.mesh).boundary_edges.count == 3);
  }
  SECTION("two triangles sharing only a vertex (two fans)") {
    // OpenMesh refuses closed fans meeting at a vertex (to_mesh counts those),
    // but represents open ones: the bowtie.
    TriangleSoup s;
    s.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(-1, 0, 0), Vec3(-1, -1, 0)};
    s.triangles = {{0, 1, 2}, {0, 3, 4}};
    const SoupToMesh m = to_mesh(s);
    REQUIRE(m.refused_faces == 0);
    check_same(analyse_topology(m.mesh), analyse_topology(s));
    CHECK(analyse_topology(m.mesh).non_manifold_vertices.count == 1);
    CHECK(analyse_topology(m.mesh).components == 1);
  }
  SECTION("a face and its reverse") {
    TriangleSoup s;
    s.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
    s.triangles = {{0, 1, 2}, {0, 2, 1}};
    const SoupToMesh m = to_mesh(s);
    REQUIRE(m.refused_faces == 0);
    check_same(analyse_topology(m.mesh), analyse_topology(s));
    CHECK(analyse_topology(m.mesh).duplicate_faces.count == 1);
  }
}
