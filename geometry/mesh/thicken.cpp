#include "geometry/mesh/thicken.h"

#include <fmt/format.h>

#include "geometry/core/errors.h"

namespace fabmesh {

std::size_t thickened_triangle_count(const Mesh& sheet) {
  std::size_t rim = 0;
  for (const auto h : sheet.halfedges()) rim += sheet.is_boundary(h) ? 1 : 0;
  return 2 * sheet.n_faces() + 2 * rim;
}

Mesh thicken(const Mesh& sheet, const std::vector<Vec3>& vertex_normals, const ThickenOptions& options) {
  require_positive("thickness", options.thickness);
  const std::size_t n = sheet.n_vertices();
  if (vertex_normals.size() != n) {
    throw RangeError("vertex_normals", static_cast<double>(vertex_normals.size()),
                     fmt::format("thicken: {} vertex normals for {} vertices", vertex_normals.size(), n));
  }
  const std::size_t triangles = thickened_triangle_count(sheet);
  if (triangles > options.max_triangles) {
    throw BudgetError(static_cast<double>(triangles), static_cast<double>(options.max_triangles),
                      fmt::format("the thickened shell needs {} triangles, over the budget of {} (raise "
                                  "max_triangles or the tolerance)",
                                  triangles, options.max_triangles));
  }
  Mesh solid;
  solid.reserve(2 * n, 3 * triangles / 2, triangles);
  for (const auto v : sheet.vertices()) solid.add_vertex(sheet.point(v));
  for (const auto v : sheet.vertices()) {
    const Vec3& nv = vertex_normals[static_cast<std::size_t>(v.idx())];
    solid.add_vertex(sheet.point(v) + options.thickness * Mesh::Point(nv.x(), nv.y(), nv.z()));
  }
  auto base = [](Mesh::VertexHandle v) { return v; };
  auto offset = [n](Mesh::VertexHandle v) { return Mesh::VertexHandle(v.idx() + static_cast<int>(n)); };
  std::size_t refused = 0;
  auto add = [&](Mesh::VertexHandle a, Mesh::VertexHandle b, Mesh::VertexHandle c) {
    if (!solid.add_face(a, b, c).is_valid()) ++refused;
  };
  for (const auto f : sheet.faces()) {
    std::array<Mesh::VertexHandle, 3> c;
    std::size_t k = 0;
    for (const auto v : sheet.fv_range(f)) c[k++] = v;
    add(offset(c[0]), offset(c[1]), offset(c[2]));
    add(base(c[0]), base(c[2]), base(c[1]));
  }
  // Side walls: the sheet's face runs a -> b along a boundary edge; the
  // reversed sheet has b -> a, the offset sheet a' -> b', so the wall takes
  // a -> b and b' -> a'.
  for (const auto h : sheet.halfedges()) {
    if (!sheet.is_boundary(h)) continue;
    const auto inside = sheet.opposite_halfedge_handle(h);
    const auto a = sheet.from_vertex_handle(inside), b = sheet.to_vertex_handle(inside);
    add(base(a), base(b), offset(b));
    add(base(a), offset(b), offset(a));
  }
  if (refused > 0) {
    throw GeometryError("thicken", fmt::format("thicken: {} faces of the shell could not be connected (the "
                                               "sheet is not manifold at its border)",
                                               refused));
  }
  return solid;
}

}  // namespace fabmesh
