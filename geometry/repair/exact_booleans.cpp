// CGAL Epeck: exact constructions, for the points where surfaces cross.

#include "geometry/repair/exact_booleans.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "geometry/section/region.h"
#include "geometry/section/triangulate.h"

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

/// A coordinate as a double, from its exact value: the lazy number's
/// interval is made tight first. (Without that, to_double takes the middle
/// of whatever interval the number has, which is tight only where a
/// predicate needed its exact value: a history that differs between runs
/// and threads, so the same input gave other points.)
double nearest(const Kernel::FT& x) {
  CGAL::exact(x);
  return CGAL::to_double(x);
}

/// The mesh with its exact points rounded to doubles (each within an ulp).
TriangleSoup rounded(const SurfaceMesh& mesh) {
  TriangleSoup soup;
  std::vector<std::uint32_t> index(mesh.number_of_vertices() + mesh.number_of_removed_vertices(), 0);
  for (const auto v : mesh.vertices()) {
    const Point& p = mesh.point(v);
    index[v.idx()] = static_cast<std::uint32_t>(soup.vertices.size());
    soup.vertices.emplace_back(nearest(p.x()), nearest(p.y()), nearest(p.z()));
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

// Whether p comes before q, coordinates compared in turn.
bool before(const Vec3& p, const Vec3& q) {
  return std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3);
}

// One planar region of a piece (coplanar triangles joined by edges) as
// loops, re-triangulated without CGAL's history: the loops start at their
// least point and are sorted, so the same region gives the same triangles.
// False (the triangles kept) when the region is not a polygon with holes
// that triangulates with its own points alone.
bool retriangulate(const TriangleSoup& soup, const std::vector<std::size_t>& group,
                   std::vector<std::array<std::uint32_t, 3>>& out) {
  const auto& tri0 = soup.triangles[group.front()];
  const Vec3 n = (soup.vertices[tri0[1]] - soup.vertices[tri0[0]])
                     .cross(soup.vertices[tri0[2]] - soup.vertices[tri0[0]]);
  int k = 0;
  for (int a = 1; a < 3; ++a) {
    if (std::abs(n[a]) > std::abs(n[k])) k = a;
  }
  const bool flip = n[k] < 0.0;
  // Its border: edges used once within it, u -> v (reversed when it faces -e_k).
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> used;
  for (std::size_t t : group) {
    const auto& tri = soup.triangles[t];
    for (int e = 0; e < 3; ++e)
      ++used[{std::min(tri[e], tri[(e + 1) % 3]), std::max(tri[e], tri[(e + 1) % 3])}];
  }
  std::map<std::uint32_t, std::uint32_t> next;
  for (std::size_t t : group) {
    const auto& tri = soup.triangles[t];
    for (int e = 0; e < 3; ++e) {
      std::uint32_t u = tri[e], v = tri[(e + 1) % 3];
      if (used[{std::min(u, v), std::max(u, v)}] != 1) continue;
      if (flip) std::swap(u, v);
      if (!next.emplace(u, v).second) return false;  // a vertex where the border touches itself
    }
  }
  const auto earlier = [&](std::uint32_t a, std::uint32_t b) {
    return before(soup.vertices[a], soup.vertices[b]);
  };
  std::vector<std::vector<std::uint32_t>> loops;
  std::set<std::uint32_t> left;
  for (const auto& [u, v] : next) left.insert(u);
  while (!left.empty()) {
    std::vector<std::uint32_t> loop;
    std::uint32_t u = *left.begin();
    while (left.erase(u) == 1) {
      loop.push_back(u);
      u = next.at(u);
    }
    if (u != loop.front()) return false;
    std::rotate(loop.begin(), std::min_element(loop.begin(), loop.end(), earlier), loop.end());
    loops.push_back(std::move(loop));
  }
  std::sort(loops.begin(), loops.end(),
            [&](const auto& a, const auto& b) { return earlier(a.front(), b.front()); });
  // In the plane across k: the outer loop counter-clockwise (largest area), the holes clockwise.
  const auto at = [&](std::uint32_t v) {
    const Vec3& p = soup.vertices[v];
    return Vec2(p[(k + 1) % 3], p[(k + 2) % 3]);
  };
  const auto area = [&](const std::vector<std::uint32_t>& loop) {
    double twice = 0.0;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Vec2 a = at(loop[i]), b = at(loop[(i + 1) % loop.size()]);
      twice += a.x() * b.y() - a.y() * b.x();
    }
    return 0.5 * twice;
  };
  std::size_t outer = 0;
  for (std::size_t i = 1; i < loops.size(); ++i) {
    if (area(loops[i]) > area(loops[outer])) outer = i;
  }
  Region2 region;
  std::map<std::pair<double, double>, std::uint32_t> vertex_at;
  std::size_t points = 0;
  for (std::size_t i = 0; i < loops.size(); ++i) {
    std::vector<Vec2> ring;
    for (std::uint32_t v : loops[i]) {
      ring.push_back(at(v));
      if (!vertex_at.emplace(std::make_pair(ring.back().x(), ring.back().y()), v).second) return false;
    }
    points += ring.size();
    if (i == outer) {
      if (!(area(loops[i]) > 0.0)) return false;
      region.outer = std::move(ring);
    } else {
      if (!(area(loops[i]) < 0.0)) return false;
      region.holes.push_back(std::move(ring));
    }
  }
  PlanarTriangulation t;
  try {
    t = triangulate(region);
  } catch (const std::exception&) {
    return false;
  }
  if (t.steiner_points != 0 || t.triangles.size() != points + 2 * region.holes.size() - 2) return false;
  for (const auto& tri : t.triangles) {
    std::array<std::uint32_t, 3> mapped{};
    for (int e = 0; e < 3; ++e) {
      const auto it = vertex_at.find({t.vertices[tri[e]].x(), t.vertices[tri[e]].y()});
      if (it == vertex_at.end()) return false;
      mapped[e] = it->second;
    }
    if (flip) std::swap(mapped[1], mapped[2]);
    out.push_back(mapped);
  }
  return true;
}

/// `soup` (closed, from CGAL) in a form its history does not change: each
/// planar region re-triangulated from its own points (CGAL's corefinement
/// breaks ties between cocircular points by an order that differs between
/// runs and threads), the points sorted, each triangle starting at its
/// least point, the triangles sorted. The same solid gives the same bytes.
TriangleSoup canonical(const TriangleSoup& soup) {
  using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
  const auto point = [&](std::uint32_t v) {
    const Vec3& p = soup.vertices[v];
    return Epick::Point_3(p.x(), p.y(), p.z());
  };
  const std::size_t count = soup.triangles.size();
  // Coplanar triangles across an edge, joined (union-find).
  std::vector<std::size_t> parent(count);
  for (std::size_t t = 0; t < count; ++t) parent[t] = t;
  const std::function<std::size_t(std::size_t)> root = [&](std::size_t t) {
    while (parent[t] != t) t = parent[t] = parent[parent[t]];
    return t;
  };
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> by_edge;
  for (std::size_t t = 0; t < count; ++t) {
    const auto& tri = soup.triangles[t];
    for (int e = 0; e < 3; ++e) by_edge[{tri[e], tri[(e + 1) % 3]}] = t;
  }
  for (std::size_t t = 0; t < count; ++t) {
    const auto& tri = soup.triangles[t];
    for (int e = 0; e < 3; ++e) {
      const auto it = by_edge.find({tri[(e + 1) % 3], tri[e]});
      if (it == by_edge.end() || it->second < t) continue;
      const auto& other = soup.triangles[it->second];
      std::uint32_t far = other[0];
      for (std::uint32_t v : other) {
        if (v != tri[e] && v != tri[(e + 1) % 3]) far = v;
      }
      if (CGAL::orientation(point(tri[0]), point(tri[1]), point(tri[2]), point(far)) == CGAL::COPLANAR) {
        parent[root(it->second)] = root(t);
      }
    }
  }
  std::map<std::size_t, std::vector<std::size_t>> groups;
  for (std::size_t t = 0; t < count; ++t) groups[root(t)].push_back(t);
  std::vector<std::array<std::uint32_t, 3>> triangles;
  triangles.reserve(count);
  for (const auto& [first, group] : groups) {
    std::vector<std::array<std::uint32_t, 3>> made;
    if (group.size() > 1 && retriangulate(soup, group, made)) {
      triangles.insert(triangles.end(), made.begin(), made.end());
    } else {
      for (std::size_t t : group) triangles.push_back(soup.triangles[t]);
    }
  }
  // The points used, sorted; each triangle from its least point; the triangles sorted.
  std::vector<std::uint32_t> order;
  std::vector<bool> used(soup.vertices.size(), false);
  for (const auto& tri : triangles) {
    for (std::uint32_t v : tri) used[v] = true;
  }
  for (std::uint32_t v = 0; v < soup.vertices.size(); ++v) {
    if (used[v]) order.push_back(v);
  }
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t a, std::uint32_t b) { return before(soup.vertices[a], soup.vertices[b]); });
  TriangleSoup out;
  std::vector<std::uint32_t> index(soup.vertices.size(), 0);
  for (std::uint32_t v : order) {
    index[v] = static_cast<std::uint32_t>(out.vertices.size());
    out.vertices.push_back(soup.vertices[v]);
  }
  for (auto tri : triangles) {
    for (std::uint32_t& v : tri) v = index[v];
    std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()), tri.end());
    out.triangles.push_back(tri);
  }
  std::sort(out.triangles.begin(), out.triangles.end());
  return out;
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
                                                      const std::vector<std::vector<TriangleSoup>>& holes,
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
      pieces.push_back(canonical(rounded(piece)));
      if (i < holes.size()) {
        for (const TriangleSoup& hole : holes[i])
          rest = boolean_of(rest, exact_mesh(hole), 0, "the rest less a hole");
      }
    }
    if (rest.is_empty() || !CGAL::is_closed(rest)) {
      say(why, "the main piece is empty or open");
      return std::nullopt;
    }
    pieces.front() = canonical(rounded(rest));
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
      out.push_back(canonical(rounded(cell)));
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
