#include "api/src/soup.h"

#include <fmt/format.h>

#include "api/src/detail.h"

namespace fabmesh::api::detail {
namespace {

template <class Index>
void copy_triangles(const Index* indices, std::size_t count, std::size_t vertex_count,
                    fabmesh::TriangleSoup& soup) {
  soup.triangles.resize(count);
  for (std::size_t f = 0; f < count; ++f) {
    for (std::size_t k = 0; k < 3; ++k) {
      const Index i = indices[3 * f + k];
      if (i < 0 || static_cast<std::uint64_t>(i) >= vertex_count) {
        bad_argument("triangles",
                     fmt::format("triangle {} corner {} is vertex {}, not one of the {} vertices", f, k,
                                 static_cast<long long>(i), vertex_count));
      }
      soup.triangles[f][k] = static_cast<std::uint32_t>(i);
    }
  }
}

}  // namespace

Mesh public_mesh(const fabmesh::TriangleSoup& soup) {
  Mesh mesh;
  mesh.vertices.reserve(soup.vertices.size());
  for (const Vec3& p : soup.vertices) mesh.vertices.push_back({p.x(), p.y(), p.z()});
  mesh.triangles.assign(soup.triangles.begin(), soup.triangles.end());
  return mesh;
}

MeshView view_of(const Mesh& mesh) {
  static_assert(sizeof(Point) == 3 * sizeof(double), "a Point is three packed doubles");
  static_assert(sizeof(Triangle) == 3 * sizeof(std::uint32_t), "a Triangle is three packed indices");
  MeshView view;
  view.vertices = mesh.vertices.empty() ? nullptr : mesh.vertices.front().data();
  view.vertex_count = mesh.vertices.size();
  // Indices below 2^31 read the same as int32; larger ones do not fit the soup's numbering anyway.
  view.triangles32 =
      mesh.triangles.empty() ? nullptr : reinterpret_cast<const std::int32_t*>(mesh.triangles.front().data());
  view.triangle_count = mesh.triangles.size();
  return view;
}

fabmesh::TriangleSoup internal_soup(const MeshView& view) {
  if (view.vertex_count > 0 && view.vertices == nullptr) bad_argument("vertices", "no array for the rows");
  if (view.triangle_count > 0 && view.triangles == nullptr && view.triangles32 == nullptr)
    bad_argument("triangles", "no array for the rows");
  if (view.vertex_count > std::uint64_t{1} << 32)
    bad_argument("vertices", fmt::format("{} vertices, more than 32-bit indices number", view.vertex_count));
  fabmesh::TriangleSoup soup;
  soup.vertices.resize(view.vertex_count);
  for (std::size_t v = 0; v < view.vertex_count; ++v) {
    const double* p = view.vertices + 3 * v;
    soup.vertices[v] = Vec3(p[0], p[1], p[2]);
  }
  if (view.triangles != nullptr) {
    copy_triangles(view.triangles, view.triangle_count, view.vertex_count, soup);
  } else {
    copy_triangles(view.triangles32, view.triangle_count, view.vertex_count, soup);
  }
  return soup;
}

}  // namespace fabmesh::api::detail
