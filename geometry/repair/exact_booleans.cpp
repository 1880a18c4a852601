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
#include <cmath>
#include <exception>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

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

namespace {

// One boolean (0 difference, 1 intersection, 2 union) on fresh copies of
// both operands, since corefinement refines them; throws when the result
// would not be a manifold surface, naming `what`.
SurfaceMesh boolean_of(const SurfaceMesh& a, const SurfaceMesh& b, int op, const char* what) {
  SurfaceMesh x = a, y = b, out;
  const bool ok = op == 0   ? PMP::corefine_and_compute_difference(x, y, out)
                  : op == 1 ? PMP::corefine_and_compute_intersection(x, y, out)
                            : PMP::corefine_and_compute_union(x, y, out);
  if (!ok) throw std::runtime_error(std::string(what) + " would not be a manifold surface");
  return out;
}

}  // namespace

std::optional<std::vector<TriangleSoup>> carve_pieces(const TriangleSoup& block, const TriangleSoup& part,
                                                      const std::vector<std::vector<TriangleSoup>>& regions,
                                                      const std::vector<std::vector<TriangleSoup>>& added,
                                                      const std::vector<TriangleSoup>& holes,
                                                      std::string* why) {
  try {
    SurfaceMesh rest = boolean_of(exact_mesh(block), exact_mesh(part), 0, "the block less the part");
    std::vector<TriangleSoup> pieces(1);
    for (std::size_t i = 0; i < regions.size(); ++i) {
      if (regions[i].empty()) throw std::runtime_error("a region without a solid");
      SurfaceMesh region = exact_mesh(regions[i].front());
      for (std::size_t j = 1; j < regions[i].size(); ++j) {
        region = boolean_of(region, exact_mesh(regions[i][j]), 2, "a region");
      }
      SurfaceMesh piece = boolean_of(rest, region, 1, "a piece");
      rest = boolean_of(rest, region, 0, "the rest of the block");
      if (i < added.size()) {
        for (const TriangleSoup& a : added[i])
          piece = boolean_of(piece, exact_mesh(a), 2, "a piece with a pin");
      }
      if (piece.is_empty() || !CGAL::is_closed(piece)) {
        say(why, "piece " + std::to_string(i + 1) + " is empty or open");
        return std::nullopt;
      }
      pieces.push_back(rounded(piece));
    }
    for (const TriangleSoup& hole : holes)
      rest = boolean_of(rest, exact_mesh(hole), 0, "the rest less a hole");
    if (rest.is_empty() || !CGAL::is_closed(rest)) {
      say(why, "the main piece is empty or open");
      return std::nullopt;
    }
    pieces.front() = rounded(rest);
    return pieces;
  } catch (const std::exception& e) {
    say(why, std::string("CGAL's corefinement failed: ") + e.what());
    return std::nullopt;
  }
}

std::optional<std::vector<TriangleSoup>> cut_cells(const TriangleSoup& solid,
                                                   const std::vector<TriangleSoup>& cells,
                                                   const std::vector<std::vector<TriangleSoup>>& added,
                                                   const std::vector<std::vector<TriangleSoup>>& removed,
                                                   std::string* why) {
  try {
    const SurfaceMesh whole = exact_mesh(solid);
    std::vector<TriangleSoup> out;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      SurfaceMesh cell = boolean_of(whole, exact_mesh(cells[i]), 1, "a cell");
      if (cell.is_empty()) {
        out.emplace_back();
        continue;
      }
      if (i < added.size()) {
        for (const TriangleSoup& a : added[i]) cell = boolean_of(cell, exact_mesh(a), 2, "a cell with a pin");
      }
      if (i < removed.size()) {
        for (const TriangleSoup& r : removed[i])
          cell = boolean_of(cell, exact_mesh(r), 0, "a cell less a hole");
      }
      if (!CGAL::is_closed(cell)) {
        say(why, "cell " + std::to_string(i + 1) + " is open");
        return std::nullopt;
      }
      out.push_back(rounded(cell));
    }
    return out;
  } catch (const std::exception& e) {
    say(why, std::string("CGAL's corefinement failed: ") + e.what());
    return std::nullopt;
  }
}

namespace {

// A floating-point filter for a sum of products: the computed value's sign
// is exact once it exceeds `bound`; otherwise none.
int filtered(double value, double bound) {
  if (value > bound) return 1;
  if (-value > bound) return -1;
  return 2;
}

constexpr double kFilter = 64.0 * std::numeric_limits<double>::epsilon();

}  // namespace

int exact_facing(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 u = b - a, v = c - a;
  const double value = u.cross(v).dot(d);
  const double bound = kFilter * u.lpNorm<1>() * v.lpNorm<1>() * d.lpNorm<1>();
  const int s = filtered(value, bound);
  if (s != 2) return s;
  const Point pa(a.x(), a.y(), a.z()), pb(b.x(), b.y(), b.z()), pc(c.x(), c.y(), c.z());
  const Kernel::Vector_3 vd(d.x(), d.y(), d.z());
  return static_cast<int>(CGAL::sign(CGAL::cross_product(pb - pa, pc - pa) * vd));
}

int exact_side(const Vec3& p, const Vec3& o, const Vec3& d) {
  const double value = (p - o).dot(d);
  const double bound = kFilter * (p.lpNorm<1>() + o.lpNorm<1>()) * d.lpNorm<1>();
  const int s = filtered(value, bound);
  if (s != 2) return s;
  const Kernel::Vector_3 vd(d.x(), d.y(), d.z());
  return static_cast<int>(CGAL::sign((Point(p.x(), p.y(), p.z()) - Point(o.x(), o.y(), o.z())) * vd));
}

}  // namespace fabmesh
