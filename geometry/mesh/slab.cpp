#include "geometry/mesh/slab.h"

#include <fmt/format.h>

#include "geometry/core/errors.h"

namespace fabmesh {

std::size_t slab_triangle_count(const PlanarTriangulation& t) {
  std::size_t walls = 0;
  for (const auto& loop : t.boundary) walls += 2 * loop.size();
  return 2 * t.triangles.size() + walls;
}

Mesh extrude(const PlanarTriangulation& t, double thickness) {
  require_positive("thickness", thickness);
  const std::size_t n = t.vertices.size();
  const std::size_t faces = slab_triangle_count(t);
  Mesh mesh;
  mesh.reserve(2 * n, 3 * faces / 2, faces);
  // Bottom copy i, top copy n + i.
  for (const Vec2& p : t.vertices) mesh.add_vertex(Mesh::Point(p.x(), p.y(), 0.0));
  for (const Vec2& p : t.vertices) mesh.add_vertex(Mesh::Point(p.x(), p.y(), thickness));
  auto vh = [](std::size_t i) { return Mesh::VertexHandle(static_cast<int>(i)); };
  auto add = [&](std::size_t a, std::size_t b, std::size_t c) {
    if (!mesh.add_face(vh(a), vh(b), vh(c)).is_valid()) {
      throw std::logic_error(
          fmt::format("extrude: face ({}, {}, {}) refused: the triangulation is not a manifold "
                      "disc with holes",
                      a, b, c));
    }
  };
  for (const auto& f : t.triangles) add(n + f[0], n + f[1], n + f[2]);  // top, normal +z
  for (const auto& f : t.triangles) add(f[0], f[2], f[1]);              // bottom, normal -z
  // Walls: boundary edge a -> b has the region on its left, so the outside is on its right.
  for (const auto& loop : t.boundary) {
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const std::size_t a = loop[i], b = loop[(i + 1) % loop.size()];
      add(a, b, n + b);
      add(a, n + b, n + a);
    }
  }
  return mesh;
}

SlabMesh build_slab(const Region2& region, const SlabOptions& options) {
  require_positive("thickness", options.thickness);
  TriangulateOptions to;
  to.max_edge = options.max_edge;
  to.max_triangles = options.max_triangles / 2;
  PlanarTriangulation triangulation = triangulate(region, to);
  const std::size_t triangles = slab_triangle_count(triangulation);
  if (triangles > options.max_triangles) {
    throw BudgetError(
        static_cast<double>(triangles), static_cast<double>(options.max_triangles),
        fmt::format("the slab needs {} triangles, over the budget of {} (raise max_triangles, the "
                    "tolerance or max_edge)",
                    triangles, options.max_triangles));
  }
  EmbeddingProof proof{
      region.proof +
      fmt::format("; top and bottom are a CGAL constrained Delaunay triangulation of that region "
                  "({} faces, each counter-clockwise by the exact orientation predicate) at z = {} "
                  "and z = 0, walls vertical over its {} boundary cycle(s), which meet only at shared "
                  "vertices: an extruded planar embedding",
                  triangulation.triangles.size(), options.thickness, triangulation.boundary.size())};
  // Braced initialisers run in order: the mesh is extruded (in place) before the triangulation moves.
  return SlabMesh{extrude(triangulation, options.thickness), std::move(triangulation), std::move(proof)};
}

}  // namespace fabmesh
