#include "geometry/section/region.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <optional>

#include "geometry/core/error_checks.h"
#include "geometry/sampling/sample_curve.h"
#include "geometry/section/curve_clearance.h"
#include "geometry/section/simple_polygon.h"

namespace fabmesh {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_2;

std::string at(const Vec2& p) { return fmt::format("({:.6g}, {:.6g})", p.x(), p.y()); }

// At a loop's key, near `p`.
ErrorLocation near(const std::string& key, const Vec2& p) { return ErrorLocation{key, {}, {p.x(), p.y()}}; }

// One sampled loop and where each of its points lies on its curve.
struct Loop {
  std::string label;
  std::string key;
  const CompositeCurve* curve = nullptr;
  std::vector<Vec2> points;
  std::vector<CurveParam> params;
};

// "outline segment 3 (tbezier)": the curve segment an edge of a loop samples.
std::string edge_name(const Loop& loop, std::size_t edge) {
  const std::size_t s = loop.params[edge].segment;
  return fmt::format("{} segment {} ({})", loop.label, s, to_string(loop.curve->segments()[s].kind()));
}

// The closed curve's joints all meet (the closing one included).
void require_closed(const CompositeCurve& curve, const std::string& label) {
  if (!curve.closed()) {
    throw GeometryError(ErrorLocation{}, fmt::format("{} must be a closed curve (closed: true)", label));
  }
  for (const JointReport& j : curve.joints()) {
    if (j.achieved != Continuity::None) continue;
    const Vec2 end = curve.segments()[j.before].point(1.0);
    const Vec2 start = curve.segments()[j.after].point(0.0);
    if (j.closing) {
      throw GeometryError(ErrorLocation{},
                          fmt::format("{} does not close: its last segment ({}) ends at {}, {:.6g} from its "
                                      "start {} (closing joint)",
                                      label, j.before, at(end), j.gap, at(start)));
    }
    throw GeometryError(ErrorLocation{},
                        fmt::format("{} has a gap of {:.6g} between segment {} (ends at {}) and segment {} "
                                    "(starts at {})",
                                    label, j.gap, j.before, at(end), j.after, at(start)));
  }
}

// Throws for the first crossing among all loops, naming both sides.
void require_disjoint(const std::vector<Loop>& loops) {
  std::vector<std::vector<Vec2>> points;
  points.reserve(loops.size());
  for (const Loop& l : loops) points.push_back(l.points);
  const auto crossing = find_crossing(points);
  if (!crossing) return;
  auto locate = [&](std::size_t edge) {
    std::size_t loop = 0;
    while (edge >= loops[loop].points.size()) edge -= loops[loop++].points.size();
    return std::pair{loop, edge};
  };
  const auto [la, ea] = locate(crossing->first);
  const auto [lb, eb] = locate(crossing->second);
  const std::string where = at(crossing->where);
  if (la == lb) {
    const Loop& l = loops[la];
    throw GeometryError(near(l.key, crossing->where),
                        fmt::format("{} crosses itself near {}: {} meets {}", l.label, where,
                                    edge_name(l, ea), edge_name(l, eb)));
  }
  const Loop& a = loops[std::min(la, lb)];
  const Loop& b = loops[std::max(la, lb)];
  if (std::min(la, lb) == 0) {
    throw GeometryError(near(b.key, crossing->where),
                        fmt::format("{} crosses or touches the outline near {} ({})", b.label, where,
                                    edge_name(a, la == 0 ? ea : eb)));
  }
  throw GeometryError(near(b.key, crossing->where),
                      fmt::format("{} overlaps {} near {}", b.label, a.label, where));
}

std::vector<Point> to_cgal(const std::vector<Vec2>& pts) {
  std::vector<Point> out;
  out.reserve(pts.size());
  for (const Vec2& p : pts) out.emplace_back(p.x(), p.y());
  return out;
}

// With no crossings, a loop is inside another exactly when one of its points
// is. A point can be inside a hole only within the hole's bounding box: each
// hole is tested against the first points in its box (found among the points
// sorted by x), not every other hole, so that thousands of holes take time
// near-linear in their number. Holes and points are taken in index order, so
// the error names the same pair as testing every pair would.
void require_nesting(const std::vector<Loop>& loops) {
  const std::vector<Point> outer = to_cgal(loops[0].points);
  for (std::size_t i = 1; i < loops.size(); ++i) {
    const Vec2& p = loops[i].points.front();
    const Point q(p.x(), p.y());
    if (CGAL::bounded_side_2(outer.begin(), outer.end(), q, Kernel()) != CGAL::ON_BOUNDED_SIDE) {
      throw GeometryError(
          ErrorLocation{},
          fmt::format("{} is not inside the outline: its point {} lies outside it", loops[i].label, at(p)));
    }
  }
  std::vector<std::size_t> by_x;  // holes by their first point's x
  for (std::size_t j = 1; j < loops.size(); ++j) by_x.push_back(j);
  const auto x_of = [&](std::size_t j) { return loops[j].points.front().x(); };
  std::sort(by_x.begin(), by_x.end(), [&](std::size_t a, std::size_t b) { return x_of(a) < x_of(b); });
  for (std::size_t i = 1; i < loops.size(); ++i) {
    Vec2 lo = loops[i].points.front(), hi = lo;
    for (const Vec2& v : loops[i].points) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
    const auto first = std::lower_bound(by_x.begin(), by_x.end(), lo.x(),
                                        [&](std::size_t j, double x) { return x_of(j) < x; });
    std::vector<std::size_t> in_box;
    for (auto it = first; it != by_x.end() && x_of(*it) <= hi.x(); ++it) {
      const double y = loops[*it].points.front().y();
      if (*it != i && y >= lo.y() && y <= hi.y()) in_box.push_back(*it);
    }
    if (in_box.empty()) continue;
    std::sort(in_box.begin(), in_box.end());
    const std::vector<Point> hole = to_cgal(loops[i].points);
    for (const std::size_t j : in_box) {
      const Vec2& p = loops[j].points.front();
      if (CGAL::bounded_side_2(hole.begin(), hole.end(), Point(p.x(), p.y()), Kernel()) ==
          CGAL::ON_BOUNDED_SIDE) {
        throw GeometryError(ErrorLocation{}, fmt::format("{} lies inside {} (near {}); holes may not nest",
                                                         loops[j].label, loops[i].label, at(p)));
      }
    }
  }
}

// No loop may come within `tolerance` of itself across a neck (its two
// sides nearly touching): as for two loops, the mesh could not tell them apart.
void require_no_neck(const std::vector<Loop>& loops, double tolerance) {
  for (const Loop& l : loops) {
    const std::optional<PolygonNeck> neck = find_neck(l.points, tolerance);
    if (!neck) continue;
    throw GeometryError(near(l.key, neck->b),
                        fmt::format("{} comes within {:.6g} of itself ({} near {}, {} near {}), closer than "
                                    "the {:.6g} the mesh is built within: its two sides nearly touch there",
                                    l.label, neck->distance, edge_name(l, neck->first), at(neck->a),
                                    edge_name(l, neck->second), at(neck->b), tolerance));
  }
}

// The exact curves of different loops must stay `tolerance` apart.
void require_clearance(const std::vector<Loop>& loops, double tolerance, Region2& region) {
  if (loops.size() < 2) return;
  std::vector<std::unique_ptr<ExactArc>> arcs;
  std::vector<ArcPiece> pieces;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const std::size_t first = arcs.size();
    for (const Segment& seg : loops[l].curve->segments()) arcs.push_back(std::make_unique<SegmentArc>(seg));
    const auto& params = loops[l].params;
    for (std::size_t i = 0; i < params.size(); ++i) {
      const auto [s0, s1] = edge_parameters(params, i);
      pieces.push_back({arcs[first + params[i].segment].get(), s0, s1, static_cast<int>(l)});
    }
  }
  ClearanceOptions co;
  co.accuracy = 1e-3 * tolerance;
  const Clearance c = exact_clearance(pieces, co);
  const Loop& a = loops[static_cast<std::size_t>(std::min(c.group_a, c.group_b))];
  const Loop& b = loops[static_cast<std::size_t>(std::max(c.group_a, c.group_b))];
  const Vec2 pa = c.group_a < c.group_b ? c.a : c.b, pb = c.group_a < c.group_b ? c.b : c.a;
  region.min_clearance = c.lower;
  region.clearance_where = fmt::format("{} near {} and {} near {}", a.label, at(pa), b.label, at(pb));
  if (c.upper < tolerance) {
    throw GeometryError(near(b.key, pb),
                        fmt::format("{} comes within {:.6g} of {} ({} near {}, {} near {}), closer than "
                                    "the {:.6g} the mesh is built within{}",
                                    b.label, c.upper, a.label, b.label, at(pb), a.label, at(pa), tolerance,
                                    c.lower == 0.0 ? " (the exact curves meet)" : ""));
  }
}

}  // namespace

Region2 build_region(const CompositeCurve& outline, const std::vector<RegionHole>& holes,
                     const RegionOptions& options) {
  require_positive("tolerance", options.tolerance);
  std::vector<Loop> loops;
  loops.push_back({"outline", options.outline_key, &outline, {}, {}});
  for (const RegionHole& h : holes) loops.push_back({h.label, h.key, &h.curve, {}, {}});

  Region2 region;
  std::size_t budget = options.max_points;
  for (Loop& l : loops) {
    require_closed(*l.curve, l.label);
    SampleOptions so;
    so.tolerance = options.tolerance;
    so.max_points = budget;
    Polyline2 line = sample_curve(*l.curve, so, &l.params);
    budget -= std::min(budget, line.points.size());
    region.max_deviation = std::max(region.max_deviation, line.max_deviation);
    l.points = std::move(line.points);
    if (l.points.size() < 3) {
      throw GeometryError(
          ErrorLocation{},
          fmt::format("{} samples to {} points; a closed loop needs at least 3", l.label, l.points.size()));
    }
  }
  require_disjoint(loops);
  require_no_neck(loops, options.tolerance);
  require_nesting(loops);
  require_clearance(loops, options.tolerance, region);

  for (std::size_t i = 0; i < loops.size(); ++i) {
    std::vector<Vec2>& pts = loops[i].points;
    const double a2 = signed_area2(pts);
    region.reversed.push_back((i == 0) != (a2 > 0.0));
    if (region.reversed.back()) std::reverse(pts.begin(), pts.end());
    region.area += (i == 0 ? 0.5 : -0.5) * std::abs(a2);
    if (i == 0) {
      for (const CurveParam& p : loops[i].params)
        region.outer_along.push_back(static_cast<double>(p.segment) + p.s);
      if (region.reversed.back()) std::reverse(region.outer_along.begin(), region.outer_along.end());
      region.outer = std::move(pts);
    } else {
      region.holes.push_back(std::move(pts));
    }
  }
  region.proof = fmt::format(
      "outline and {} hole(s) sampled into simple, pairwise disjoint polygons with every hole "
      "strictly inside the outline and outside the others (exact predicates)",
      holes.size());
  return region;
}

std::vector<std::vector<Vec2>> region_loops(const Region2& region) {
  std::vector<std::vector<Vec2>> loops;
  loops.reserve(region.holes.size() + 1);
  loops.push_back(region.outer);
  loops.insert(loops.end(), region.holes.begin(), region.holes.end());
  return loops;
}

}  // namespace fabmesh
