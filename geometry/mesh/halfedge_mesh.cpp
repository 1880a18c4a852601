#include "geometry/mesh/halfedge_mesh.h"

#include <vector>

namespace fabmesh {

TriangleSoup to_soup(const Mesh& mesh) {
  TriangleSoup soup;
  std::vector<std::uint32_t> dense(mesh.n_vertices(), 0);
  soup.vertices.reserve(mesh.n_vertices());
  for (const auto v : mesh.vertices()) {  // skips deleted vertices
    dense[v.idx()] = static_cast<std::uint32_t>(soup.vertices.size());
    const auto& p = mesh.point(v);
    soup.vertices.emplace_back(p[0], p[1], p[2]);
  }
  soup.triangles.reserve(mesh.n_faces());
  std::vector<std::uint32_t> loop;
  for (const auto f : mesh.faces()) {
    loop.clear();
    for (const auto v : mesh.fv_range(f)) loop.push_back(dense[v.idx()]);
    for (std::size_t k = 1; k + 1 < loop.size(); ++k) {
      soup.triangles.push_back({loop[0], loop[k], loop[k + 1]});
    }
  }
  return soup;
}

SoupToMesh to_mesh(const TriangleSoup& soup) {
  require_indices_in_range(soup);
  SoupToMesh result;
  Mesh& mesh = result.mesh;
  mesh.reserve(soup.vertices.size(), 3 * soup.triangles.size() / 2, soup.triangles.size());
  std::vector<Mesh::VertexHandle> handles;
  handles.reserve(soup.vertices.size());
  for (const Vec3& p : soup.vertices) handles.push_back(mesh.add_vertex(Mesh::Point(p.x(), p.y(), p.z())));
  for (const auto& t : soup.triangles) {
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) {
      ++result.refused_faces;
      continue;
    }
    const auto f = mesh.add_face(handles[t[0]], handles[t[1]], handles[t[2]]);
    if (!f.is_valid()) ++result.refused_faces;
  }
  return result;
}

}  // namespace fabmesh
