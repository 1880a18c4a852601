// pmp_check: CGAL Polygon Mesh Processing's own checks of an STL file, the
// peer of `fabmesh check` in bench/check_vs_pmp.sh. Prints each stage's wall
// time and the verdict as one JSON object.
//
//   pmp_check FILE.stl [--read cgal|fabmesh]
//
// Stages: read (CGAL::IO::read_STL, which merges equal points through a
// std::map; or fabmesh's parse_stl + exact weld), orient
// (orient_polygon_soup), to_mesh (polygon_soup_to_polygon_mesh into a
// Surface_mesh), closed (CGAL::is_closed), self_intersection
// (does_self_intersect<Parallel_tag>), outward (is_outward_oriented) and
// volume. The last two need a closed mesh and are skipped otherwise.
// Exit 0 for a valid mesh, 1 for an invalid one, 2 for bad input.

#ifndef CGAL_LINKED_WITH_TBB
#define CGAL_LINKED_WITH_TBB
#endif
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/STL.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <fmt/format.h>

#include <array>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "geometry/core/errors.h"
#include "geometry/core/stage_timer.h"
#include "geometry/mesh/weld.h"
#include "io/file.h"
#include "io/mesh/stl.h"

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
using Polygon = std::array<std::size_t, 3>;
namespace PMP = CGAL::Polygon_mesh_processing;

/// Reads `path` into a polygon soup with CGAL's reader or fabmesh's.
void read_soup(const std::string& path, bool cgal_reader, std::vector<Point>& points,
               std::vector<Polygon>& polygons) {
  if (cgal_reader) {
    if (!CGAL::IO::read_STL(path, points, polygons, CGAL::parameters::verbose(false))) {
      throw fabmesh::FileError(path, 0, 0, fmt::format("{}: CGAL::IO::read_STL failed", path));
    }
    return;
  }
  const fabmesh::TriangleSoup soup = fabmesh::weld(fabmesh::parse_stl(fabmesh::read_file(path), path)).soup;
  points.reserve(soup.vertices.size());
  for (const fabmesh::Vec3& p : soup.vertices) points.emplace_back(p.x(), p.y(), p.z());
  polygons.reserve(soup.triangles.size());
  for (const auto& t : soup.triangles) polygons.push_back({t[0], t[1], t[2]});
}

int check(const std::string& path, bool cgal_reader) {
  fabmesh::StageTimings timings;
  fabmesh::StageTimer timer(timings);
  std::vector<Point> points;
  std::vector<Polygon> polygons;
  read_soup(path, cgal_reader, points, polygons);
  timer.lap("read");
  nlohmann::ordered_json j;
  j["file"] = path;
  j["reader"] = cgal_reader ? "cgal" : "fabmesh";
  j["triangles"] = polygons.size();
  j["vertices"] = points.size();
  // false: some points had to be duplicated to make the soup orientable (non-manifold input).
  j["orientable"] = PMP::orient_polygon_soup(points, polygons);
  timer.lap("orient");
  SurfaceMesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  timer.lap("to_mesh");
  const bool closed = CGAL::is_closed(mesh);
  j["closed"] = closed;
  timer.lap("closed");
  const bool self_intersecting = PMP::does_self_intersect<CGAL::Parallel_tag>(mesh);
  j["self_intersecting"] = self_intersecting;
  timer.lap("self_intersection");
  bool outward = false;
  j["outward"] = outward;
  if (closed) {
    outward = PMP::is_outward_oriented(mesh);
    timer.lap("outward");
    j["outward"] = outward;
    j["volume"] = CGAL::to_double(PMP::volume(mesh));
    timer.lap("volume");
  }
  const bool valid = closed && !self_intersecting && outward && j["orientable"].get<bool>();
  j["valid"] = valid;
  nlohmann::ordered_json t = nlohmann::ordered_json::object();
  for (const auto& [stage, ms] : timings) t[stage] = ms;
  j["timings_ms"] = t;
  std::cout << j.dump(2) << "\n";
  return valid ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string usage = "usage: pmp_check FILE.stl [--read cgal|fabmesh]\n";
  if (argc != 2 && argc != 4) {
    std::cerr << usage;
    return 2;
  }
  bool cgal_reader = true;
  if (argc == 4) {
    const std::string option = argv[2];
    const std::string value = argv[3];
    if (option != "--read" || (value != "cgal" && value != "fabmesh")) {
      std::cerr << usage;
      return 2;
    }
    cgal_reader = value == "cgal";
  }
  try {
    return check(argv[1], cgal_reader);
  } catch (const std::exception& e) {
    std::cerr << "pmp_check: error: " << e.what() << "\n";
    return 2;
  }
}
