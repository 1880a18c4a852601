#include "geometry/section/triangulate.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <fmt/format.h>

#include <cmath>
#include <deque>
#include <limits>
#include <stdexcept>

#include "geometry/core/budget.h"
#include "geometry/core/errors.h"

namespace fabmesh {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_2;
constexpr std::uint32_t kUnset = std::numeric_limits<std::uint32_t>::max();
using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, Kernel,
                                                       CGAL::Delaunay_mesh_vertex_base_2<Kernel>>;
using Fb = CGAL::Triangulation_face_base_with_info_2<int, Kernel, CGAL::Delaunay_mesh_face_base_2<Kernel>>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::No_constraint_intersection_tag>;
using Criteria = CGAL::Delaunay_mesh_size_criteria_2<Cdt>;
using Mesher = CGAL::Delaunay_mesher_2<Cdt, Criteria>;
using FaceHandle = Cdt::Face_handle;

// Nesting depth of every face: 0 for the unbounded component, +1 across each
// constrained edge. Faces at odd depth are inside the region (the loops are
// disjoint and the holes not nested, so depth is 1 inside, 2 in a hole).
void mark_domain(Cdt& cdt) {
  for (FaceHandle f : cdt.all_face_handles()) f->info() = -1;
  std::deque<std::pair<FaceHandle, int>> border{{cdt.infinite_face(), 0}};
  std::vector<FaceHandle> stack;
  while (!border.empty()) {
    const auto [start, level] = border.front();
    border.pop_front();
    if (start->info() != -1) continue;
    start->info() = level;
    stack.push_back(start);
    while (!stack.empty()) {
      const FaceHandle f = stack.back();
      stack.pop_back();
      for (int i = 0; i < 3; ++i) {
        const FaceHandle n = f->neighbor(i);
        if (n->info() != -1) continue;
        if (cdt.is_constrained(Cdt::Edge(f, i))) {
          border.emplace_back(n, level + 1);
        } else {
          n->info() = level;
          stack.push_back(n);
        }
      }
    }
  }
  for (FaceHandle f : cdt.all_face_handles()) f->set_in_domain(f->info() % 2 == 1);
}

// Delaunay refinement of the in-domain faces until every edge is <= max_edge,
// stopping with a BudgetError once the triangle budget is exceeded.
void refine(Cdt& cdt, const TriangulateOptions& options) {
  Mesher mesher(cdt, Criteria(0.125, options.max_edge));
  mesher.init(true);  // the domain is the one mark_domain set
  std::size_t steps = 0;
  while (mesher.try_one_step_refine_mesh()) {
    if (++steps % 4096 == 0 && cdt.number_of_faces() > 2 * options.max_triangles) {
      throw BudgetError(
          static_cast<double>(cdt.number_of_faces()), static_cast<double>(options.max_triangles),
          fmt::format("max_edge {} needs more than {} triangles, over the budget (raise max_triangles "
                      "or max_edge)",
                      options.max_edge, options.max_triangles));
    }
  }
  mark_domain(cdt);
}

// Boundary edges of the in-domain faces chained into cycles (region on the left).
std::vector<std::vector<std::uint32_t>> boundary_cycles(const Cdt& cdt, std::size_t vertex_count) {
  std::vector<std::uint32_t> next(vertex_count, kUnset);
  std::size_t edges = 0;
  for (const FaceHandle f : cdt.finite_face_handles()) {
    if (!f->is_in_domain()) continue;
    for (int i = 0; i < 3; ++i) {
      if (f->neighbor(i)->is_in_domain()) continue;
      const std::uint32_t a = f->vertex(Cdt::ccw(i))->info(), b = f->vertex(Cdt::cw(i))->info();
      if (next[a] != kUnset)
        throw std::logic_error("triangulate: a boundary vertex with two outgoing boundary edges");
      next[a] = b;
      ++edges;
    }
  }
  std::vector<std::vector<std::uint32_t>> cycles;
  std::vector<bool> seen(vertex_count, false);
  for (std::uint32_t s = 0; s < vertex_count; ++s) {
    if (next[s] == kUnset || seen[s]) continue;
    std::vector<std::uint32_t> cycle;
    for (std::uint32_t v = s; !seen[v]; v = next[v]) {
      if (next[v] == kUnset) throw std::logic_error("triangulate: an open boundary chain");
      seen[v] = true;
      cycle.push_back(v);
    }
    edges -= cycle.size();
    cycles.push_back(std::move(cycle));
  }
  if (edges != 0) throw std::logic_error("triangulate: boundary edges outside the cycles");
  return cycles;
}

}  // namespace

PlanarTriangulation triangulate(const Region2& region, const TriangulateOptions& options) {
  if (!std::isfinite(options.max_edge) || options.max_edge < 0.0) {
    throw RangeError("max_edge", options.max_edge,
                     fmt::format("max_edge = {} must be > 0", options.max_edge));
  }
  std::vector<Point> points;
  std::vector<std::pair<std::size_t, std::size_t>> constraints;
  for (const auto& loop : region_loops(region)) {
    const std::size_t first = points.size();
    for (std::size_t i = 0; i < loop.size(); ++i) {
      points.emplace_back(loop[i].x(), loop[i].y());
      constraints.emplace_back(first + i, first + (i + 1) % loop.size());
    }
  }
  if (options.max_edge > 0.0) {
    // A triangle whose longest edge is <= e has area <= sqrt(3)/4 e^2: a lower bound on the count.
    const double fewest = region.area / (std::sqrt(3.0) / 4.0 * options.max_edge * options.max_edge);
    require_within_budget(
        fewest, options.max_triangles,
        [&] { return fmt::format("max_edge {} needs at least {:.0f} triangles", options.max_edge, fewest); },
        "raise max_triangles or max_edge");
  }
  Cdt cdt;
  cdt.insert_constraints(points.begin(), points.end(), constraints.begin(), constraints.end());
  mark_domain(cdt);
  if (options.max_edge > 0.0) refine(cdt, options);

  PlanarTriangulation out;
  for (const auto v : cdt.finite_vertex_handles()) v->info() = kUnset;
  for (const FaceHandle f : cdt.finite_face_handles()) {
    if (!f->is_in_domain()) continue;
    std::array<std::uint32_t, 3> t{};
    for (int i = 0; i < 3; ++i) {
      const auto v = f->vertex(i);
      if (v->info() == kUnset) {
        v->info() = static_cast<std::uint32_t>(out.vertices.size());
        out.vertices.emplace_back(v->point().x(), v->point().y());
      }
      t[static_cast<std::size_t>(i)] = v->info();
    }
    // CGAL keeps every face positively oriented (exact predicate); the slab's embedding proof relies on it.
    if (CGAL::orientation(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point()) !=
        CGAL::LEFT_TURN) {
      throw std::logic_error("triangulate: a face is not counter-clockwise");
    }
    out.triangles.push_back(t);
  }
  require_within_budget(out.triangles.size(), options.max_triangles,
                        [&] { return fmt::format("the region needs {} triangles", out.triangles.size()); });
  out.boundary = boundary_cycles(cdt, out.vertices.size());
  out.steiner_points = out.vertices.size() > points.size() ? out.vertices.size() - points.size() : 0;
  return out;
}

}  // namespace fabmesh
