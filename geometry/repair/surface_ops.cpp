// CGAL Epick: exact predicates over double coordinates. The hole filling
// builds a Surface_mesh whose vertex i and face f are the soup's (CGAL
// appends what it adds), so patches map back by index.

#include "geometry/repair/surface_ops.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <iterator>
#include <set>

#include "geometry/core/errors.h"

namespace fabmesh {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
using Face = SurfaceMesh::Face_index;
using Halfedge = SurfaceMesh::Halfedge_index;
using Vertex = SurfaceMesh::Vertex_index;

Point point(const Vec3& p) { return Point(p.x(), p.y(), p.z()); }

std::vector<Point> points_of(const TriangleSoup& soup) {
  std::vector<Point> points;
  points.reserve(soup.vertices.size());
  for (const Vec3& v : soup.vertices) points.push_back(point(v));
  return points;
}

std::vector<std::array<std::size_t, 3>> faces_of(const TriangleSoup& soup) {
  std::vector<std::array<std::size_t, 3>> faces;
  faces.reserve(soup.triangles.size());
  for (const auto& t : soup.triangles) faces.push_back({t[0], t[1], t[2]});
  return faces;
}

/// The soup as a Surface_mesh with vertex i = soup vertex i and face f = soup face f.
SurfaceMesh surface_mesh(const TriangleSoup& soup) {
  const auto faces = faces_of(soup);
  if (!PMP::is_polygon_soup_a_polygon_mesh(faces))
    throw InputError("fill_holes: the surface is not an oriented manifold (internal: repair order)");
  SurfaceMesh mesh;
  for (const Vec3& v : soup.vertices) mesh.add_vertex(point(v));
  for (const auto& t : soup.triangles) {
    if (mesh.add_face(Vertex(t[0]), Vertex(t[1]), Vertex(t[2])) == SurfaceMesh::null_face())
      throw InputError("fill_holes: a face could not be added (internal: repair order)");
  }
  return mesh;
}

TriangleSoup soup_of(const SurfaceMesh& mesh) {
  TriangleSoup soup;
  soup.vertices.reserve(mesh.number_of_vertices());
  for (const Vertex v : mesh.vertices()) {
    const Point& p = mesh.point(v);
    soup.vertices.emplace_back(p.x(), p.y(), p.z());
  }
  for (const Face f : mesh.faces()) {
    std::array<std::uint32_t, 3> t{};
    int k = 0;
    for (const Vertex v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
      t[k++] = static_cast<std::uint32_t>(v.idx());
    soup.triangles.push_back(t);
  }
  return soup;
}

FilledHole describe_hole(const SurfaceMesh& mesh, Halfedge h) {
  FilledHole hole;
  hole.border_vertex = static_cast<std::uint32_t>(mesh.target(h).idx());
  for (const Halfedge b : CGAL::halfedges_around_face(h, mesh)) {
    const Point& p = mesh.point(mesh.target(b));
    hole.centre += Vec3(p.x(), p.y(), p.z());
    ++hole.border_edges;
  }
  hole.centre /= static_cast<double>(hole.border_edges);
  return hole;
}

/// Fills every hole, the holes in `plain` without refining or fairing.
HoleFilling fill_once(const TriangleSoup& soup, const std::set<std::size_t>& plain,
                      const std::set<std::size_t>& skip, const HoleFillOptions& options,
                      std::vector<std::vector<Face>>& patches) {
  SurfaceMesh mesh = surface_mesh(soup);
  std::vector<Halfedge> borders;
  PMP::extract_boundary_cycles(mesh, std::back_inserter(borders));
  HoleFilling result;
  patches.assign(borders.size(), {});
  for (std::size_t i = 0; i < borders.size(); ++i) {
    FilledHole hole = describe_hole(mesh, borders[i]);
    if (skip.count(i) == 0) {
      std::vector<Vertex> added;
      if (options.refine_and_fair && plain.count(i) == 0) {
        hole.faired = std::get<0>(PMP::triangulate_refine_and_fair_hole(
            mesh, borders[i], std::back_inserter(patches[i]), std::back_inserter(added)));
      } else {
        PMP::triangulate_hole(mesh, borders[i], std::back_inserter(patches[i]));
      }
      hole.faces_added = patches[i].size();
      hole.vertices_added = added.size();
      hole.filled = !patches[i].empty();
    }
    result.holes.push_back(hole);
  }
  result.soup = soup_of(mesh);
  return result;
}

constexpr std::uint32_t kNoHole = static_cast<std::uint32_t>(-1);

/// The holes whose patch meets another face other than at shared vertices and edges.
std::set<std::size_t> crossing_patches(const HoleFilling& filled,
                                       const std::vector<std::vector<Face>>& patches) {
  std::vector<std::uint32_t> hole_of(filled.soup.triangles.size(), kNoHole);
  for (std::size_t i = 0; i < patches.size(); ++i) {
    for (const Face f : patches[i]) hole_of[f.idx()] = static_cast<std::uint32_t>(i);
  }
  std::set<std::size_t> bad;
  for (const auto& [f, g] : intersecting_faces(filled.soup)) {
    if (hole_of[f] != kNoHole) bad.insert(hole_of[f]);
    if (hole_of[g] != kNoHole) bad.insert(hole_of[g]);
  }
  return bad;
}

}  // namespace

bool corners_collinear(const Vec3& a, const Vec3& b, const Vec3& c) {
  return CGAL::collinear(point(a), point(b), point(c));
}

HoleFilling fill_holes(const TriangleSoup& soup, const HoleFillOptions& options) {
  // A patch that crosses the surface is tried again flat (minimal area, no
  // new vertices), then left out.
  std::set<std::size_t> plain, skip;
  std::vector<std::vector<Face>> patches;
  for (int attempt = 0; attempt < 3; ++attempt) {
    HoleFilling filled = fill_once(soup, plain, skip, options, patches);
    const std::set<std::size_t> bad = crossing_patches(filled, patches);
    if (bad.empty()) return filled;
    for (const std::size_t i : bad) {
      if (options.refine_and_fair && plain.count(i) == 0) {
        plain.insert(i);
      } else {
        skip.insert(i);
      }
    }
  }
  HoleFilling filled = fill_once(soup, plain, skip, options, patches);
  const std::set<std::size_t> bad = crossing_patches(filled, patches);
  if (bad.empty()) return filled;
  skip.insert(bad.begin(), bad.end());
  return fill_once(soup, plain, skip, options, patches);
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> intersecting_faces(const TriangleSoup& soup) {
  std::vector<Point> points = points_of(soup);
  std::vector<std::array<std::size_t, 3>> faces = faces_of(soup);
  if (!PMP::is_polygon_soup_a_polygon_mesh(faces)) PMP::orient_polygon_soup(points, faces);
  SurfaceMesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, faces, mesh);
  std::vector<std::pair<Face, Face>> pairs;
  PMP::self_intersections<CGAL::Parallel_if_available_tag>(mesh, std::back_inserter(pairs));
  std::vector<std::pair<std::uint32_t, std::uint32_t>> result;
  result.reserve(pairs.size());
  for (const auto& [f, g] : pairs) {
    const auto a = static_cast<std::uint32_t>(f.idx()), b = static_cast<std::uint32_t>(g.idx());
    result.emplace_back(std::min(a, b), std::max(a, b));
  }
  std::sort(result.begin(), result.end());
  return result;
}

}  // namespace fabmesh
