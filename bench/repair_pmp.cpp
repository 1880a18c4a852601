// A CGAL Polygon Mesh Processing repair pipeline, the peer of `fabmesh
// repair` in repair_vs_peers.sh: the steps CGAL's documentation chains for
// a soup from elsewhere. Reads any mesh fabmesh reads, writes OFF.
//
//   repair_pmp IN OUT.off   -> prints {"ms": ..., "faces": ..., "closed": ..., "stage": "..."}
//
// repair_polygon_soup (merge equal points, drop degenerate and duplicate
// polygons), orient_polygon_soup (orient, duplicate non-manifold vertices),
// polygon_soup_to_polygon_mesh, stitch_borders, every border cycle filled by
// triangulate_refine_and_fair_hole, experimental::remove_self_intersections,
// then orient_to_bound_a_volume when the mesh is closed and free of
// self-intersections.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/repair_self_intersections.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/stitch_borders.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <iterator>
#include <string>
#include <vector>

#include "io/file.h"
#include "io/mesh/off.h"
#include "io/mesh/read_mesh.h"

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: repair_pmp IN OUT.off\n");
    return 2;
  }
  const fabmesh::TriangleSoup soup = fabmesh::read_mesh(argv[1]);
  const auto start = std::chrono::steady_clock::now();
  std::vector<Point> points;
  for (const fabmesh::Vec3& v : soup.vertices) points.emplace_back(v.x(), v.y(), v.z());
  std::vector<std::vector<std::size_t>> polygons;
  for (const auto& t : soup.triangles) polygons.push_back({t[0], t[1], t[2]});
  std::string stage = "done";
  PMP::repair_polygon_soup(points, polygons);
  PMP::orient_polygon_soup(points, polygons);
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  PMP::stitch_borders(mesh);
  std::vector<Mesh::Halfedge_index> borders;
  PMP::extract_boundary_cycles(mesh, std::back_inserter(borders));
  for (const auto h : borders) {
    if (!mesh.is_border(h)) continue;  // filled with an earlier cycle
    std::vector<Mesh::Face_index> faces;
    std::vector<Mesh::Vertex_index> vertices;
    PMP::triangulate_refine_and_fair_hole(mesh, h, std::back_inserter(faces), std::back_inserter(vertices));
  }
  try {
    if (PMP::does_self_intersect(mesh) && !PMP::experimental::remove_self_intersections(mesh))
      stage = "self-intersections left";
  } catch (const std::exception& e) {
    stage = std::string("remove_self_intersections threw: ") + e.what();
  }
  const bool closed = CGAL::is_closed(mesh);
  if (closed && !PMP::does_self_intersect(mesh)) PMP::orient_to_bound_a_volume(mesh);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  fabmesh::TriangleSoup out;
  std::vector<std::uint32_t> index(mesh.number_of_vertices() + mesh.number_of_removed_vertices());
  for (const auto v : mesh.vertices()) {
    index[v.idx()] = static_cast<std::uint32_t>(out.vertices.size());
    const Point& p = mesh.point(v);
    out.vertices.emplace_back(p.x(), p.y(), p.z());
  }
  for (const auto f : mesh.faces()) {
    std::array<std::uint32_t, 3> t{};
    int k = 0;
    for (const auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) {
      if (k < 3) t[static_cast<std::size_t>(k)] = index[v.idx()];
      ++k;
    }
    if (k == 3) out.triangles.push_back(t);
  }
  fabmesh::write_off(out, argv[2]);
  std::printf("{\"ms\": %.1f, \"faces\": %zu, \"closed\": %s, \"stage\": \"%s\"}\n", ms, out.triangles.size(),
              closed ? "true" : "false", stage.c_str());
  return 0;
}
