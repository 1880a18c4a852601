// The connectivity analysis of a soup, also of a halfedge Mesh through
// to_soup (the way a Mesh is validated).

#include "geometry/validation/detail/topology.h"

#include <catch2/catch.hpp>

#include "geometry/curves/curve_spec.h"
#include "geometry/mesh/halfedge_mesh.h"
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

TEST_CASE("topology: a Mesh through to_soup has the facts of its soup, on valid meshes", "[mesh][topology]") {
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
  const Topology t = analyse_topology(to_soup(mesh));
  check_same(t, analyse_topology(build_vessel(construct_curve(spec), o).soup));
  CHECK(t.boundary_edges.count == 0);
  CHECK(t.non_manifold_vertices.count == 0);
  CHECK(t.duplicate_faces.count == 0);
  CHECK(t.components == 1);
  CHECK(t.euler_characteristics == std::vector<long>{2});
}

TEST_CASE("topology: holes, pinched vertices and duplicate pairs, in a soup and through a Mesh",
          "[mesh][topology]") {
  SECTION("a hole") {
    TriangleSoup s = tetrahedron(Vec3::Zero(), 0);
    s.triangles.pop_back();
    const SoupToMesh m = to_mesh(s);
    REQUIRE(m.refused_faces == 0);
    check_same(analyse_topology(to_soup(m.mesh)), analyse_topology(s));
    CHECK(analyse_topology(s).boundary_edges.count == 3);
  }
  SECTION("two triangles sharing only a vertex (two fans)") {
    // OpenMesh refuses closed fans meeting at a vertex (to_mesh counts those),
    // but represents open ones: the bowtie.
    TriangleSoup s;
    s.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(-1, 0, 0), Vec3(-1, -1, 0)};
    s.triangles = {{0, 1, 2}, {0, 3, 4}};
    const SoupToMesh m = to_mesh(s);
    REQUIRE(m.refused_faces == 0);
    check_same(analyse_topology(to_soup(m.mesh)), analyse_topology(s));
    CHECK(analyse_topology(s).non_manifold_vertices.count == 1);
    CHECK(analyse_topology(s).components == 1);
  }
  SECTION("a face and its reverse") {
    TriangleSoup s;
    s.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
    s.triangles = {{0, 1, 2}, {0, 2, 1}};
    const SoupToMesh m = to_mesh(s);
    REQUIRE(m.refused_faces == 0);
    check_same(analyse_topology(to_soup(m.mesh)), analyse_topology(s));
    CHECK(analyse_topology(s).duplicate_faces.count == 1);
  }
}

TEST_CASE("topology: boundary examples by vertex index or in face order, the same count",
          "[mesh][topology]") {
  TriangleSoup s;
  s.vertices = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 4, 0), Vec3(8, 8, 0)};
  s.triangles = {{2, 0, 1}, {1, 3, 2}};  // sides 2-0, 0-1, 1-2 | 1-3, 3-2, 2-1
  const auto mid = [&](std::uint32_t a, std::uint32_t b) {
    return Vec3(0.5 * (s.vertices[a] + s.vertices[b]));
  };
  const Topology by_vertex = analyse_topology(s, 5, ExampleOrder::ByVertex);
  const Topology by_face = analyse_topology(s, 5, ExampleOrder::ByFace);
  CHECK(by_vertex.boundary_edges.count == 4);
  CHECK(by_face.boundary_edges.count == 4);
  CHECK(by_vertex.boundary_edges.examples == std::vector<Vec3>{mid(0, 1), mid(0, 2), mid(1, 3), mid(2, 3)});
  CHECK(by_face.boundary_edges.examples == std::vector<Vec3>{mid(2, 0), mid(0, 1), mid(1, 3), mid(3, 2)});
  const Topology first_two = analyse_topology(s, 2, ExampleOrder::ByFace);
  CHECK(first_two.boundary_edges.count == 4);
  CHECK(first_two.boundary_edges.examples == std::vector<Vec3>{mid(2, 0), mid(0, 1)});
  check_same(by_vertex, by_face);
}
