#include "geometry/mesh/thicken.h"

#include <fmt/format.h>

#include <cmath>

#include "geometry/core/budget.h"
#include "geometry/core/error_checks.h"

namespace fabmesh {

std::size_t thickened_triangle_count(const Mesh& sheet) {
  std::size_t rim = 0;
  for (const auto h : sheet.halfedges()) rim += sheet.is_boundary(h) ? 1 : 0;
  return 2 * sheet.n_faces() + 2 * rim;
}

Mesh thicken(const Mesh& sheet, const std::vector<Vec3>& vertex_normals, const ThickenOptions& options) {
  require_positive("thickness", options.thickness);
  require_in_range("offset", options.offset, -1e12, 1e12);
  const std::size_t n = sheet.n_vertices();
  if (vertex_normals.size() != n) {
    throw RangeError("vertex_normals", static_cast<double>(vertex_normals.size()),
                     fmt::format("thicken: {} vertex normals for {} vertices", vertex_normals.size(), n));
  }
  const std::size_t triangles = thickened_triangle_count(sheet);
  require_within_budget(
      triangles, options.max_triangles,
      [&] { return fmt::format("the thickened shell needs {} triangles", triangles); },
      "raise max_triangles or the tolerance");
  Mesh solid;
  solid.reserve(2 * n, 3 * triangles / 2, triangles);
  const double lower = options.offset, upper = options.offset + options.thickness;
  auto along = [&](Mesh::VertexHandle v, double distance) {
    if (distance == 0.0) return sheet.point(v);
    const Vec3& nv = vertex_normals[static_cast<std::size_t>(v.idx())];
    return Mesh::Point(sheet.point(v) + distance * Mesh::Point(nv.x(), nv.y(), nv.z()));
  };
  for (const auto v : sheet.vertices()) solid.add_vertex(along(v, lower));
  for (const auto v : sheet.vertices()) solid.add_vertex(along(v, upper));
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

namespace fabmesh {

const char* to_string(ThickenSide side) {
  switch (side) {
    case ThickenSide::Normal:
      return "normal";
    case ThickenSide::Outward:
      return "outward";
    case ThickenSide::Inward:
      return "inward";
    case ThickenSide::Centered:
      return "centered";
  }
  return "normal";
}

double enclosed_volume(const Mesh& sheet) {
  Vec3 centroid = Vec3::Zero();
  std::size_t rim = 0;
  for (const auto h : sheet.halfedges()) {
    if (!sheet.is_boundary(h)) continue;
    const auto& p = sheet.point(sheet.from_vertex_handle(h));
    centroid += Vec3(p[0], p[1], p[2]);
    ++rim;
  }
  if (rim > 0) centroid /= static_cast<double>(rim);
  auto at = [&](Mesh::VertexHandle v) -> Vec3 {
    const auto& p = sheet.point(v);
    return Vec3(p[0], p[1], p[2]) - centroid;
  };
  double six_volume = 0.0;
  for (const auto f : sheet.faces()) {
    std::array<Vec3, 3> c;
    std::size_t k = 0;
    for (const auto v : sheet.fv_range(f)) c[k++] = at(v);
    six_volume += c[0].dot(c[1].cross(c[2]));
  }
  // The cap's triangles (from, to, centroid) add nothing: the centroid is the origin here.
  return six_volume / 6.0;
}

std::array<double, 2> shell_span(ThickenSide side, double thickness, double volume, double size) {
  require_positive("thickness", thickness);
  const bool tellable = std::abs(volume) > 1e-6 * size * size * size;
  if ((side == ThickenSide::Outward || side == ThickenSide::Inward) && !tellable) {
    throw GeometryError("thicken",
                        fmt::format("thicken: {} needs a surface that encloses a volume with its rim "
                                    "(a bowl, a tray); this one is flat (enclosed volume {:.3g}): use "
                                    "normal (along S_u x S_v) or centered",
                                    to_string(side), volume));
  }
  const bool normals_out = volume > 0.0;
  switch (side) {
    case ThickenSide::Normal:
      return {0.0, thickness};
    case ThickenSide::Outward:
      return normals_out ? std::array<double, 2>{0.0, thickness} : std::array<double, 2>{-thickness, 0.0};
    case ThickenSide::Inward:
      return normals_out ? std::array<double, 2>{-thickness, 0.0} : std::array<double, 2>{0.0, thickness};
    case ThickenSide::Centered:
      return {-0.5 * thickness, 0.5 * thickness};
  }
  return {0.0, thickness};
}

}  // namespace fabmesh
