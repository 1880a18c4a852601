#include "geometry/section/simple_polygon.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

#include <algorithm>

namespace fabmesh {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_2;
using Segment2 = Kernel::Segment_2;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 2, std::size_t>;

Point point_of(const Vec2& p) { return {p.x(), p.y()}; }

struct Edge {
  std::size_t chain;  // which polyline
  std::size_t local;  // edge index within it
  Segment2 segment;
};

struct Chain {
  const std::vector<Vec2>* points;
  bool closed;
  std::size_t edges() const { return closed ? points->size() : points->size() - 1; }
};

// The shared end point of two edges of one chain, when they are neighbours.
std::optional<std::size_t> shared_vertex(const Chain& c, std::size_t i, std::size_t j) {
  if (i > j) std::swap(i, j);
  if (j == i + 1) return j;
  if (c.closed && i == 0 && j == c.edges() - 1 && c.edges() > 2) return std::size_t{0};
  return std::nullopt;
}

std::optional<EdgeCrossing> find_crossing_in(const std::vector<Chain>& chains) {
  std::vector<Edge> edges;
  std::vector<Box> boxes;
  std::vector<std::size_t> first_edge;  // global index of each chain's first edge
  for (std::size_t c = 0; c < chains.size(); ++c) {
    first_edge.push_back(edges.size());
    const auto& pts = *chains[c].points;
    if (pts.size() < 2) continue;
    for (std::size_t i = 0; i < chains[c].edges(); ++i) {
      const Vec2& a = pts[i];
      const Vec2& b = pts[(i + 1) % pts.size()];
      if (a == b) return EdgeCrossing{edges.size(), edges.size(), a};  // zero-length edge
      double lo[2] = {std::min(a.x(), b.x()), std::min(a.y(), b.y())};
      double hi[2] = {std::max(a.x(), b.x()), std::max(a.y(), b.y())};
      boxes.emplace_back(lo, hi, edges.size());
      edges.push_back({c, i, Segment2(Point(a.x(), a.y()), Point(b.x(), b.y()))});
    }
    if (chains[c].closed && chains[c].edges() == 2) {
      return EdgeCrossing{first_edge[c], first_edge[c] + 1, pts[1]};  // a two-edge loop folds on itself
    }
  }
  std::vector<std::pair<std::size_t, std::size_t>> hits;
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& ba, const Box& bb) {
    std::size_t i = ba.info(), j = bb.info();
    if (i > j) std::swap(i, j);
    const Edge& ei = edges[i];
    const Edge& ej = edges[j];
    if (ei.chain == ej.chain) {
      if (const auto v = shared_vertex(chains[ei.chain], ei.local, ej.local)) {
        // Neighbours share one end point; they may not fold back over each other.
        const Vec2& s = (*chains[ei.chain].points)[*v];
        const Point sp(s.x(), s.y());
        const Point pi = ei.segment.source() == sp ? ei.segment.target() : ei.segment.source();
        const Point pj = ej.segment.source() == sp ? ej.segment.target() : ej.segment.source();
        if (CGAL::collinear(pi, sp, pj) && !CGAL::collinear_are_strictly_ordered_along_line(pi, sp, pj)) {
          hits.emplace_back(i, j);
        }
        return;
      }
    }
    if (CGAL::do_intersect(ei.segment, ej.segment)) hits.emplace_back(i, j);
  });
  if (hits.empty()) return std::nullopt;
  const auto first = *std::min_element(hits.begin(), hits.end());
  const Segment2& s = edges[first.second].segment;
  const Vec2 where(0.5 * (s.source().x() + s.target().x()), 0.5 * (s.source().y() + s.target().y()));
  return EdgeCrossing{first.first, first.second, where};
}

// The point of segment [a, b] nearest to p, as its parameter in [0, 1].
double nearest_parameter(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double length2 = d.squaredNorm();
  return length2 > 0.0 ? std::clamp((p - a).dot(d) / length2, 0.0, 1.0) : 0.0;
}

// The polygon's arc length at each vertex, and its whole length last.
std::vector<double> arc_lengths(const std::vector<Vec2>& points) {
  std::vector<double> s(points.size() + 1, 0.0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    s[i + 1] = s[i] + (points[(i + 1) % points.size()] - points[i]).norm();
  }
  return s;
}

}  // namespace

std::optional<PolygonNeck> find_neck(const std::vector<Vec2>& points, double width, double detour) {
  const std::size_t n = points.size();
  if (n < 4 || !(width > 0.0)) return std::nullopt;
  const std::vector<double> s = arc_lengths(points);
  const double total = s[n];
  std::vector<Box> boxes;
  boxes.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& a = points[i];
    const Vec2& b = points[(i + 1) % n];
    // Each box grown by half the width: boxes of edges within `width` meet.
    double lo[2] = {std::min(a.x(), b.x()) - 0.5 * width, std::min(a.y(), b.y()) - 0.5 * width};
    double hi[2] = {std::max(a.x(), b.x()) + 0.5 * width, std::max(a.y(), b.y()) + 0.5 * width};
    boxes.emplace_back(lo, hi, i);
  }
  std::optional<PolygonNeck> narrowest;
  // Vertex v of one edge against the other edge e (v not on e).
  auto try_vertex = [&](std::size_t v, std::size_t e, std::size_t edge_of_v) {
    if (v == e || v == (e + 1) % n) return;
    const Vec2& a = points[e];
    const Vec2& b = points[(e + 1) % n];
    const double t = nearest_parameter(points[v], a, b);
    const Vec2 q = a + t * (b - a);
    const double distance = (points[v] - q).norm();
    if (distance >= width || (narrowest && distance >= narrowest->distance)) return;
    const double along = std::abs(s[e] + t * (s[e + 1] - s[e]) - s[v]);
    if (std::min(along, total - along) <= detour * width) return;
    const bool v_first = edge_of_v < e;
    narrowest = v_first ? PolygonNeck{edge_of_v, e, distance, points[v], q}
                        : PolygonNeck{e, edge_of_v, distance, q, points[v]};
  };
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& ba, const Box& bb) {
    const std::size_t i = ba.info(), j = bb.info();
    for (const std::size_t v : {i, (i + 1) % n}) try_vertex(v, j, i);
    for (const std::size_t v : {j, (j + 1) % n}) try_vertex(v, i, j);
  });
  return narrowest;
}

double signed_area2(const std::vector<Vec2>& p) {
  double a = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) a += cross2(p[i], p[(i + 1) % p.size()]);
  return a;
}

std::optional<EdgeCrossing> find_crossing(const std::vector<Vec2>& points, bool closed) {
  if (points.size() < 2) return std::nullopt;
  return find_crossing_in({Chain{&points, closed}});
}

std::optional<EdgeCrossing> find_crossing(const std::vector<std::vector<Vec2>>& loops) {
  std::vector<Chain> chains;
  chains.reserve(loops.size());
  for (const auto& l : loops) chains.push_back({&l, true});
  return find_crossing_in(chains);
}

bool is_planar_embedding(const std::vector<Vec2>& points,
                         const std::vector<std::array<std::uint32_t, 3>>& triangles,
                         const std::vector<std::vector<std::uint32_t>>& cycles, std::string* why) {
  const auto fail = [why](std::string reason) {
    if (why != nullptr) *why = std::move(reason);
    return false;
  };
  const auto at = [&points](std::uint32_t i) { return Point(points[i].x(), points[i].y()); };
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& f = triangles[t];
    if (CGAL::orientation(at(f[0]), at(f[1]), at(f[2])) != CGAL::LEFT_TURN)
      return fail("triangle " + std::to_string(t) + " is not counter-clockwise");
  }
  std::vector<std::vector<Vec2>> loops;
  std::vector<std::vector<Point>> polygons;
  for (const auto& cycle : cycles) {
    loops.emplace_back();
    polygons.emplace_back();
    for (const std::uint32_t i : cycle) {
      loops.back().push_back(points[i]);
      polygons.back().push_back(at(i));
    }
  }
  if (find_crossing(loops)) return fail("boundary cycles cross or touch");
  // A simple polygon's orientation, exactly: the turn at its lowest-leftmost vertex.
  const auto counter_clockwise = [](const std::vector<Point>& p) {
    return CGAL::orientation_2(p.begin(), p.end(), Kernel()) == CGAL::COUNTERCLOCKWISE;
  };
  std::size_t outer = polygons.size();
  for (std::size_t c = 0; c < polygons.size(); ++c) {
    if (!counter_clockwise(polygons[c])) continue;
    if (outer != polygons.size()) return fail("more than one counter-clockwise (outer) cycle");
    outer = c;
  }
  if (outer == polygons.size()) return fail("no counter-clockwise (outer) cycle");
  for (std::size_t c = 0; c < polygons.size(); ++c) {
    if (c == outer) continue;
    const Point& first = polygons[c].front();
    if (CGAL::bounded_side_2(polygons[outer].begin(), polygons[outer].end(), first, Kernel()) !=
        CGAL::ON_BOUNDED_SIDE)
      return fail("hole cycle " + std::to_string(c) + " is not inside the outer cycle");
    for (std::size_t d = 0; d < polygons.size(); ++d) {
      if (d == outer || d == c) continue;
      if (CGAL::bounded_side_2(polygons[d].begin(), polygons[d].end(), first, Kernel()) !=
          CGAL::ON_UNBOUNDED_SIDE)
        return fail("hole cycle " + std::to_string(c) + " is inside hole cycle " + std::to_string(d));
    }
  }
  return true;
}

int side_of_line(const Vec2& a, const Vec2& b, const Vec2& p) {
  switch (CGAL::orientation(point_of(a), point_of(b), point_of(p))) {
    case CGAL::LEFT_TURN:
      return 1;
    case CGAL::RIGHT_TURN:
      return -1;
    default:
      return 0;
  }
}

int point_in_polygon(const std::vector<Vec2>& polygon, const Vec2& p) {
  std::vector<Point> points;
  points.reserve(polygon.size());
  for (const Vec2& q : polygon) points.push_back(point_of(q));
  switch (CGAL::bounded_side_2(points.begin(), points.end(), point_of(p), Kernel())) {
    case CGAL::ON_BOUNDED_SIDE:
      return 1;
    case CGAL::ON_BOUNDARY:
      return 0;
    default:
      return -1;
  }
}

}  // namespace fabmesh
