#include "geometry/surfaces/tessellate.h"

#include <catch2/catch.hpp>
#include <random>

#include "geometry/core/errors.h"
#include "geometry/mesh/halfedge_mesh.h"
#include "geometry/validation/validate.h"
#include "tests/geometry/mesh/point_triangle.h"
#include "tests/geometry/surfaces/test_networks.h"

using namespace fabmesh;
using fabmesh::test::point_triangle_distance;

namespace {

Vec3 pos(const Mesh& m, Mesh::VertexHandle v) {
  const auto& q = m.point(v);
  return {q[0], q[1], q[2]};
}

double distance_to_mesh(const Mesh& m, const Vec3& p) {
  double best = 1e300;
  for (const auto f : m.faces()) {
    std::array<Vec3, 3> c;
    std::size_t k = 0;
    for (const auto v : m.fv_range(f)) c[k++] = pos(m, v);
    best = std::min(best, point_triangle_distance(p, c[0], c[1], c[2]));
  }
  return best;
}

}  // namespace

TEST_CASE("tessellate: a G1 network becomes one conforming sheet whose only boundary is the outer border",
          "[surfaces][tessellate]") {
  const PatchNetwork net = build_patch_network(test::basin_specs());
  TessellateOptions o;
  o.tolerance = 0.01;
  const SurfaceTessellation t = tessellate(net, o);
  const ValidationReport r = validate(to_soup(t.mesh));
  // Open, but otherwise clean: manifold, consistently oriented, no degenerate or crossing faces.
  REQUIRE(r.defects.size() == 1);
  CHECK(r.defects[0].kind == Defect::BoundaryEdge);
  CHECK(r.components == 1);
  CHECK(r.non_manifold_edges == 0);
  CHECK(r.non_manifold_vertices == 0);
  CHECK(r.consistently_oriented);
  CHECK_FALSE(r.self_intersecting);
  REQUIRE(r.euler_characteristics.size() == 1);
  CHECK(r.euler_characteristics[0] == 1);  // a disk
  // Every boundary edge lies on the rim (z = 0), and every rim vertex is on the boundary.
  std::size_t boundary = 0;
  for (const auto h : t.mesh.halfedges()) {
    if (!t.mesh.is_boundary(h)) continue;
    ++boundary;
    CHECK(std::abs(pos(t.mesh, t.mesh.from_vertex_handle(h)).z()) < 1e-12);
    CHECK(std::abs(pos(t.mesh, t.mesh.to_vertex_handle(h)).z()) < 1e-12);
  }
  CHECK(boundary == r.boundary_edges);
  for (const auto v : t.mesh.vertices()) {
    if (std::abs(pos(t.mesh, v).z()) < 1e-12) CHECK(t.mesh.is_boundary(v));
  }
  // Shared borders use the same samples on both sides.
  for (const SharedBorder& b : net.borders) {
    const bool u = b.side_a == PatchSide::UMin || b.side_a == PatchSide::UMax;
    CHECK((u ? t.t_breaks[b.a] : t.s_breaks[b.a]).size() == (u ? t.t_breaks[b.b] : t.s_breaks[b.b]).size());
  }
  CHECK(t.normals.size() == t.mesh.n_vertices());
}

TEST_CASE("tessellate: the mesh is within tolerance of the exact surface, and finer for a smaller one",
          "[surfaces][tessellate]") {
  const PatchNetwork net = build_patch_network(test::basin_specs());
  std::size_t previous = 0;
  for (double tolerance : {0.05, 0.01}) {
    TessellateOptions o;
    o.tolerance = tolerance;
    const SurfaceTessellation t = tessellate(net, o);
    CHECK(t.max_deviation <= tolerance);
    CHECK(t.mesh.n_faces() > previous);
    previous = t.mesh.n_faces();
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double worst = 0.0;
    for (int k = 0; k < 120; ++k) {
      const auto& p = net.patches[static_cast<std::size_t>(k) % net.patches.size()];
      worst = std::max(worst, distance_to_mesh(t.mesh, p.point(unit(rng), unit(rng))));
    }
    CHECK(worst <= tolerance);
    CHECK(worst <= t.max_deviation);
  }
}

TEST_CASE("tessellate: the triangle budget is enforced", "[surfaces][tessellate]") {
  const PatchNetwork net = build_patch_network(test::basin_specs());
  TessellateOptions o;
  o.tolerance = 1e-5;
  o.max_triangles = 5000;
  CHECK_THROWS_AS(tessellate(net, o), BudgetError);
  o.tolerance = 0.0;
  CHECK_THROWS_AS(tessellate(net, o), RangeError);
}
