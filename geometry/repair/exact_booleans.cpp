// CGAL Epeck: exact constructions, for the points where surfaces cross.

#include "geometry/repair/exact_booleans.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <array>
#include <exception>

namespace fabmesh {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;

SurfaceMesh exact_mesh(const TriangleSoup& soup) {
  std::vector<Point> points;
  points.reserve(soup.vertices.size());
  for (const Vec3& v : soup.vertices) points.emplace_back(v.x(), v.y(), v.z());
  std::vector<std::array<std::size_t, 3>> faces;
  faces.reserve(soup.triangles.size());
  for (const auto& t : soup.triangles) faces.push_back({t[0], t[1], t[2]});
  SurfaceMesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, faces, mesh);
  return mesh;
}

/// The mesh with its exact points rounded to the nearest doubles.
TriangleSoup rounded(const SurfaceMesh& mesh) {
  TriangleSoup soup;
  std::vector<std::uint32_t> index(mesh.number_of_vertices() + mesh.number_of_removed_vertices(), 0);
  for (const auto v : mesh.vertices()) {
    const Point& p = mesh.point(v);
    index[v.idx()] = static_cast<std::uint32_t>(soup.vertices.size());
    soup.vertices.emplace_back(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
  }
  for (const auto f : mesh.faces()) {
    std::array<std::uint32_t, 3> t{};
    int k = 0;
    for (const auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) {
      if (k < 3) t[k] = index[v.idx()];
      ++k;
    }
    if (k == 3) soup.triangles.push_back(t);
  }
  return soup;
}

/// Whether every vertex of `shells` is on `solid` or inside it (exact): a
/// union or an autorefinement keeps every point of its input's surface
/// there; one that lost a part of it is refused.
bool keeps_all(const SurfaceMesh& solid, const std::vector<TriangleSoup>& shells) {
  const CGAL::Side_of_triangle_mesh<SurfaceMesh, Kernel> side(solid);
  for (const TriangleSoup& shell : shells) {
    for (const Vec3& v : shell.vertices) {
      if (side(Point(v.x(), v.y(), v.z())) == CGAL::ON_UNBOUNDED_SIDE) return false;
    }
  }
  return true;
}

void say(std::string* why, const std::string& text) {
  if (why != nullptr) *why = text;
}

}  // namespace

std::optional<TriangleSoup> unite_shells(const std::vector<TriangleSoup>& shells, std::string* why) {
  if (shells.empty()) return TriangleSoup{};
  try {
    SurfaceMesh result = exact_mesh(shells.front());
    for (std::size_t i = 1; i < shells.size(); ++i) {
      SurfaceMesh next = exact_mesh(shells[i]);
      if (!PMP::does_bound_a_volume(next) || !PMP::does_bound_a_volume(result)) {
        say(why, "a shell does not bound a volume");
        return std::nullopt;
      }
      SurfaceMesh united;
      if (!PMP::corefine_and_compute_union(result, next, united)) {
        say(why, "the union would not be a manifold surface");
        return std::nullopt;
      }
      result = std::move(united);
    }
    if (!keeps_all(result, shells)) {
      say(why, "CGAL's union left a vertex of a shell outside it");
      return std::nullopt;
    }
    return rounded(result);
  } catch (const std::exception& e) {
    say(why, std::string("CGAL's corefinement failed: ") + e.what());
    return std::nullopt;
  }
}

std::optional<TriangleSoup> resolve_self_intersections(const TriangleSoup& shell, std::string* why) {
  try {
    SurfaceMesh mesh = exact_mesh(shell);
    if (!PMP::experimental::autorefine_and_remove_self_intersections(mesh)) {
      say(why, "CGAL's autorefinement could not remove every self-intersection");
      return std::nullopt;
    }
    if (PMP::does_self_intersect(mesh) || !CGAL::is_closed(mesh)) {
      say(why, "still self-intersecting or open after CGAL's autorefinement");
      return std::nullopt;
    }
    if (!keeps_all(mesh, {shell})) {
      say(why, "CGAL's autorefinement removed a part of the shell (a vertex of it is now outside)");
      return std::nullopt;
    }
    return rounded(mesh);
  } catch (const std::exception& e) {
    say(why, std::string("CGAL's autorefinement failed: ") + e.what());
    return std::nullopt;
  }
}

}  // namespace fabmesh
