#include "geometry/repair/tracked_soup.h"

#include <numeric>

namespace fabmesh {

TrackedSoup track(const TriangleSoup& soup) {
  TrackedSoup mesh{soup, std::vector<std::uint32_t>(soup.triangles.size()),
                   std::vector<std::uint32_t>(soup.vertices.size())};
  std::iota(mesh.face_origin.begin(), mesh.face_origin.end(), 0u);
  std::iota(mesh.vertex_origin.begin(), mesh.vertex_origin.end(), 0u);
  return mesh;
}

void remove_faces(TrackedSoup& mesh, const std::vector<bool>& remove) {
  std::size_t kept = 0;
  for (std::size_t f = 0; f < mesh.soup.triangles.size(); ++f) {
    if (remove[f]) continue;
    mesh.soup.triangles[kept] = mesh.soup.triangles[f];
    mesh.face_origin[kept] = mesh.face_origin[f];
    ++kept;
  }
  mesh.soup.triangles.resize(kept);
  mesh.face_origin.resize(kept);
}

void compact_vertices(TrackedSoup& mesh) {
  std::vector<std::uint32_t> index(mesh.soup.vertices.size(), kNoIndex);
  for (const auto& t : mesh.soup.triangles) {
    for (const std::uint32_t v : t) index[v] = 0;
  }
  std::uint32_t next = 0;
  for (std::size_t v = 0; v < index.size(); ++v) {
    if (index[v] == kNoIndex) continue;
    index[v] = next;
    mesh.soup.vertices[next] = mesh.soup.vertices[v];
    mesh.vertex_origin[next] = mesh.vertex_origin[v];
    ++next;
  }
  mesh.soup.vertices.resize(next);
  mesh.vertex_origin.resize(next);
  for (auto& t : mesh.soup.triangles) {
    for (std::uint32_t& v : t) v = index[v];
  }
}

RepairPlace face_place(const TrackedSoup& mesh, std::uint32_t f) {
  const auto& t = mesh.soup.triangles[f];
  const auto& p = mesh.soup.vertices;
  return RepairPlace{mesh.face_origin[f], kNoIndex, (p[t[0]] + p[t[1]] + p[t[2]]) / 3.0, {}};
}

RepairPlace vertex_place(const TrackedSoup& mesh, std::uint32_t v) {
  return RepairPlace{kNoIndex, mesh.vertex_origin[v], mesh.soup.vertices[v], {}};
}

std::uint32_t add_vertex(TrackedSoup& mesh, const Vec3& p, std::uint32_t like) {
  mesh.soup.vertices.push_back(p);
  mesh.vertex_origin.push_back(like == kNoIndex ? kNoIndex : mesh.vertex_origin[like]);
  return static_cast<std::uint32_t>(mesh.soup.vertices.size() - 1);
}

}  // namespace fabmesh
