#include "tests/pipeline/pmp_verdict.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <array>
#include <vector>

namespace fabmesh::testing {

PmpVerdict pmp_verdict(const TriangleSoup& soup) {
  namespace PMP = CGAL::Polygon_mesh_processing;
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
  std::vector<Kernel::Point_3> points;
  points.reserve(soup.vertices.size());
  for (const Vec3& v : soup.vertices) points.emplace_back(v.x(), v.y(), v.z());
  std::vector<std::array<std::size_t, 3>> faces;
  faces.reserve(soup.triangles.size());
  for (const auto& t : soup.triangles) faces.push_back({t[0], t[1], t[2]});
  PmpVerdict verdict;
  verdict.polygon_mesh = PMP::is_polygon_soup_a_polygon_mesh(faces);
  if (!verdict.polygon_mesh) return verdict;
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, faces, mesh);
  verdict.closed = CGAL::is_closed(mesh);
  verdict.self_intersecting = PMP::does_self_intersect<CGAL::Parallel_if_available_tag>(mesh);
  if (verdict.closed) {
    auto component = mesh.add_property_map<Mesh::Face_index, std::size_t>("f:component", 0).first;
    if (PMP::connected_components(mesh, component) == 1) verdict.outward = PMP::is_outward_oriented(mesh);
  }
  return verdict;
}

}  // namespace fabmesh::testing
