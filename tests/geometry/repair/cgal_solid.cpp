#include "tests/geometry/repair/cgal_solid.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <array>
#include <vector>

namespace fabmesh::testing {

CgalSolid cgal_solid(const TriangleSoup& soup) {
  namespace PMP = CGAL::Polygon_mesh_processing;
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
  std::vector<Kernel::Point_3> points;
  for (const Vec3& v : soup.vertices) points.emplace_back(v.x(), v.y(), v.z());
  std::vector<std::array<std::size_t, 3>> faces;
  for (const auto& t : soup.triangles) faces.push_back({t[0], t[1], t[2]});
  CgalSolid verdict;
  verdict.polygon_mesh = PMP::is_polygon_soup_a_polygon_mesh(faces);
  if (!verdict.polygon_mesh) return verdict;
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, faces, mesh);
  verdict.closed = CGAL::is_closed(mesh);
  verdict.self_intersecting = PMP::does_self_intersect(mesh);
  if (verdict.closed && !verdict.self_intersecting) {
    verdict.bounds_a_volume = PMP::does_bound_a_volume(mesh);
    verdict.volume = PMP::volume(mesh);
  }
  return verdict;
}

}  // namespace fabmesh::testing
