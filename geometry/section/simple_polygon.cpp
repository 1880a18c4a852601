#include "geometry/section/simple_polygon.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

#include <algorithm>

namespace fabmesh {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_2;
using Segment2 = Kernel::Segment_2;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 2, std::size_t>;

Point to_point(const Vec2& v) { return {v.x(), v.y()}; }

}  // namespace

double signed_area2(const std::vector<Vec2>& p) {
  double a = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) a += cross2(p[i], p[(i + 1) % p.size()]);
  return a;
}

std::optional<EdgeCrossing> find_crossing(const std::vector<Vec2>& points, bool closed) {
  const std::size_t n = points.size();
  if (n < 2) return std::nullopt;
  const std::size_t edges = closed ? n : n - 1;
  std::vector<Segment2> segs;
  std::vector<Box> boxes;
  segs.reserve(edges);
  boxes.reserve(edges);
  for (std::size_t i = 0; i < edges; ++i) {
    const Vec2& a = points[i];
    const Vec2& b = points[(i + 1) % n];
    if (a == b) return EdgeCrossing{i, i, a};  // zero-length edge
    segs.emplace_back(to_point(a), to_point(b));
    double lo[2] = {std::min(a.x(), b.x()), std::min(a.y(), b.y())};
    double hi[2] = {std::max(a.x(), b.x()), std::max(a.y(), b.y())};
    boxes.emplace_back(lo, hi, i);
  }
  auto adjacent = [&](std::size_t i, std::size_t j) {
    if (i > j) std::swap(i, j);
    return j == i + 1 || (closed && i == 0 && j == edges - 1 && edges > 2);
  };
  std::vector<std::pair<std::size_t, std::size_t>> hits;
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& a, const Box& b) {
    std::size_t i = a.info(), j = b.info();
    if (i > j) std::swap(i, j);
    if (adjacent(i, j)) {
      // Adjacent edges share one end point; they may not overlap beyond it.
      const std::size_t shared = (j == i + 1) ? i + 1 : 0;
      const Point& s = to_point(points[shared % n]);
      const Point& pi = segs[i].source() == s ? segs[i].target() : segs[i].source();
      const Point& pj = segs[j].source() == s ? segs[j].target() : segs[j].source();
      if (CGAL::collinear(pi, s, pj) && !CGAL::collinear_are_strictly_ordered_along_line(pi, s, pj)) {
        hits.emplace_back(i, j);
      }
      return;
    }
    if (CGAL::do_intersect(segs[i], segs[j])) hits.emplace_back(i, j);
  });
  if (edges == 2 && closed) hits.emplace_back(0, 1);  // a two-edge "polygon" folds on itself
  if (hits.empty()) return std::nullopt;
  const auto first = *std::min_element(hits.begin(), hits.end());
  const Vec2 where = 0.5 * (points[first.second] + points[(first.second + 1) % n]);
  return EdgeCrossing{first.first, first.second, where};
}

}  // namespace fabmesh
