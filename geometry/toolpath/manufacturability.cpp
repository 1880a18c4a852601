#include "geometry/toolpath/manufacturability.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geometry/core/errors.h"
#include "geometry/toolpath/curvature_bound.h"

namespace fabmesh {
namespace {

constexpr double kRelativeSlack = 1e-6;  // radii within this fraction of the tool radius count as equal

std::string at(const Vec2& p) { return fmt::format("({:.6g}, {:.6g})", p.x(), p.y()); }

// 1. A hole narrower than the tool in some direction cannot take it at all.
void check_hole_width(const CutCurve& loop, std::size_t index, const BoundaryIndex& boundary,
                      double deviation, double diameter) {
  std::vector<Vec2> pts;
  for (const BoundaryEdge& e : boundary.edges()) {
    if (e.loop == index) pts.push_back(e.a);
  }
  constexpr int kDirections = 360;  // every half degree
  double narrowest = INFINITY, across = 0.0;
  for (int k = 0; k < kDirections; ++k) {
    const double angle = M_PI * k / kDirections;
    const Vec2 u(std::cos(angle), std::sin(angle));
    double lo = INFINITY, hi = -std::numeric_limits<double>::infinity();
    for (const Vec2& p : pts) lo = std::min(lo, p.dot(u)), hi = std::max(hi, p.dot(u));
    // The exact curve lies within `deviation` of its samples: its width is at most this.
    const double width = hi - lo + 2.0 * deviation;
    if (width < narrowest) narrowest = width, across = angle;
  }
  if (narrowest < diameter) {
    throw GeometryError(loop.label,
                        fmt::format("{} is at most {:.6g} wide (across the direction {:.4g} degrees): "
                                    "smaller than the tool diameter {}",
                                    loop.label, narrowest, across * 180.0 / M_PI, diameter));
  }
}

// 2. Concave corners: refused unless relieved.
void check_concave_corners(const CutCurve& loop, const LoopCheck& check, const CncOptions& o) {
  if (check.concave_corners.empty() || o.relief == CornerRelief::Dogbone) return;
  const LoopCorner& c = check.concave_corners.front();
  const CompositeCurve& curve = *loop.curve;
  throw GeometryError(
      loop.label,
      fmt::format(
          "{}: the corner between {} and {} at {} is concave for the tool (it turns {:.4g} degrees "
          "away from it): a tool of diameter {} leaves it rounded to radius {}, {:.3g} from the corner "
          "point (more than a quarter of the tolerance, {:.3g}); round the corner to a radius >= {} or set "
          "relief: dogbone",
          loop.label, segment_name(curve, c.before), segment_name(curve, c.after), at(c.at),
          std::abs(c.turn) * 180.0 / M_PI, o.tool_diameter, 0.5 * o.tool_diameter,
          corner_round_depth(0.5 * o.tool_diameter, c.turn), shallow_corner_depth(o), 0.5 * o.tool_diameter));
}

// The ways out of a concave stretch of `radius` the tool of radius `r` cannot follow.
std::string tighter_than_the_tool(double radius, double r) {
  return fmt::format(
      "; the tool cannot follow it: cut it with a tool of diameter at most {:.6g} (cnc.tool_diameter), "
      "give the curve a radius of at least {:.6g} (the tool radius), or make the corner sharp and set "
      "cnc.relief: dogbone",
      2.0 * radius, r);
}

// 3. Concave stretches: radius of curvature >= the tool radius, proven per segment.
void check_concave_stretches(const CutCurve& loop, LoopCheck& check, double r) {
  const CompositeCurve& curve = *loop.curve;
  const double sign = loop.reversed ? -1.0 : 1.0;
  for (std::size_t i = 0; i < curve.size(); ++i) {
    const Segment& seg = curve.segments()[i];
    // Curvature < 0 in the cutting orientation turns away from the tool (which cuts on the right).
    // Concave radii beyond 1000 tool radii need no precise value: stop once they are proven.
    const CurvatureBound b = least_curvature(seg, sign, 0.1 * kRelativeSlack / r, -1e-3 / r);
    if (!(b.least < 0.0)) continue;
    const double radius = -1.0 / b.least;  // proven: every concave radius of this segment is >= this
    if (radius < check.min_concave_radius) {
      check.min_concave_radius = radius;
      check.min_segment = i;
      check.min_at = seg.point(b.s);
    }
    if (radius >= r * (1.0 - kRelativeSlack)) continue;
    const Vec2 p = seg.point(b.s);
    if (b.attained < 0.0 && -1.0 / b.attained < r * (1.0 - kRelativeSlack)) {
      throw GeometryError(loop.label,
                          fmt::format("{} {}: a concave stretch has a radius of curvature of {:.6g} at {} "
                                      "(s = {:.6g}), below the tool radius {} (tool diameter {}){}",
                                      loop.label, segment_name(curve, i), -1.0 / b.attained, at(p), b.s, r,
                                      2.0 * r, tighter_than_the_tool(-1.0 / b.attained, r)));
    }
    throw GeometryError(loop.label,
                        fmt::format("{} {}: its concave radius of curvature could not be proven >= the tool "
                                    "radius {} (bound {:.6g}; least found {:.6g} at {})",
                                    loop.label, segment_name(curve, i), r, radius,
                                    b.attained < 0.0 ? -1.0 / b.attained : INFINITY, at(p)));
  }
}

// 3b. Digitised concave stretches: at a shallow corner between two lines,
// the circle through the neighbouring points (the lines' far ends and the
// corner) measures the stretch the points were taken from; tighter than the
// tool, the tool cannot follow it however slight each turn is.
void check_digitised_stretches(const CutCurve& loop, const LoopCheck& check, double r) {
  const CompositeCurve& curve = *loop.curve;
  for (const LoopCorner& c : check.shallow_corners) {
    const Segment& a = curve.segments()[c.before];
    const Segment& b = curve.segments()[c.after];
    if (a.kind() != SegmentKind::Line || b.kind() != SegmentKind::Line) continue;
    const Vec2 p0 = a.point(0.0), p1 = c.at, p2 = b.point(1.0);
    const double twice_area = std::abs(cross2(p1 - p0, p2 - p0));
    if (!(twice_area > 0.0)) continue;
    const double radius = (p1 - p0).norm() * (p2 - p1).norm() * (p2 - p0).norm() / (2.0 * twice_area);
    if (radius >= r * (1.0 - kRelativeSlack)) continue;
    throw GeometryError(
        loop.label,
        fmt::format("{}: the concave stretch through {} and {} at {} has a radius of {:.6g} (the circle "
                    "through the corner and its neighbouring points), below the tool radius {} (tool "
                    "diameter {}): the points were taken along a curve tighter than the tool can cut{}",
                    loop.label, segment_name(curve, c.before), segment_name(curve, c.after), at(c.at), radius,
                    r, 2.0 * r, tighter_than_the_tool(radius, r)));
  }
}

// 4. The web between two loops.
void check_webs(const std::vector<CutCurve>& loops, const BoundaryIndex& boundary, double deviation,
                double web, double diameter, ManufacturabilityReport& report) {
  const double radius = 2.0 * std::max(web, diameter);
  BoundaryIndex::Nearest best;
  std::size_t from_loop = 0;
  for (const BoundaryEdge& e : boundary.edges()) {
    const BoundaryIndex::Nearest n = boundary.nearest(e.a, e.b, radius, e.loop);
    if (n.distance < best.distance) best = n, from_loop = e.loop;
  }
  if (best.distance == INFINITY) return;
  report.min_web = best.distance;
  report.min_web_at = 0.5 * (best.on_edge + best.on_query);
  const std::size_t other = boundary.edges()[best.edge].loop;
  // The exact loops lie within `deviation` of their samples: the true gap is at most this.
  const double gap = best.distance + 2.0 * deviation;
  if (gap >= web) return;
  const CutCurve& a = loops[std::max(from_loop, other)];
  const CutCurve& b = loops[std::min(from_loop, other)];
  throw GeometryError(
      a.label, fmt::format("{} and {} are at most {:.6g} apart near {}: the web between them is "
                           "narrower than {} (cnc.min_web; default one tool diameter)",
                           a.label, b.outer ? "the outline" : b.label, gap, at(report.min_web_at), web));
}

}  // namespace

std::string segment_name(const CompositeCurve& curve, std::size_t segment) {
  return fmt::format("segment {} ({})", segment, to_string(curve.segments()[segment].kind()));
}

std::vector<LoopCorner> loop_corners(const CutCurve& loop) {
  std::vector<LoopCorner> out;
  for (const JointReport& j : loop.curve->joints()) {
    if (j.achieved != Continuity::G0) continue;
    const Segment& before = loop.curve->segments()[j.before];
    const Segment& after = loop.curve->segments()[j.after];
    const Vec2 t_in = before.jet(1.0)[1], t_out = after.jet(0.0)[1];
    double turn = std::atan2(cross2(t_in, t_out), t_in.dot(t_out));
    if (loop.reversed) turn = -turn;  // travelling backwards mirrors the turn
    out.push_back({j.before, j.after, before.point(1.0), turn});
  }
  return out;
}

double corner_round_depth(double r, double turn) { return r * (1.0 / std::cos(0.5 * turn) - 1.0); }

double shallow_corner_depth(const CncOptions& options) { return 0.25 * options.tolerance; }

ManufacturabilityReport check_manufacturability(const std::vector<CutCurve>& loops,
                                                const BoundaryIndex& boundary, double deviation,
                                                const CncOptions& o) {
  validate_cnc_options(o);
  const double r = 0.5 * o.tool_diameter;
  ManufacturabilityReport report;
  for (std::size_t i = 0; i < loops.size(); ++i) {
    if (!loops[i].outer) check_hole_width(loops[i], i, boundary, deviation, o.tool_diameter);
  }
  for (const CutCurve& loop : loops) {
    LoopCheck check;
    check.label = loop.label;
    for (const LoopCorner& c : loop_corners(loop)) {
      // A turn of exactly +-pi (a cusp) has no convex side: treat it as concave.
      if (c.turn > 0.0 && c.turn < M_PI) {
        check.convex_corners.push_back(c);
      } else if (corner_round_depth(r, c.turn) <= shallow_corner_depth(o)) {
        check.shallow_corners.push_back(c);  // the tool's round stays within the tolerance
      } else {
        check.concave_corners.push_back(c);
      }
    }
    check_concave_corners(loop, check, o);
    check_concave_stretches(loop, check, r);
    check_digitised_stretches(loop, check, r);
    report.loops.push_back(std::move(check));
  }
  check_webs(loops, boundary, deviation, min_web(o), o.tool_diameter, report);
  return report;
}

}  // namespace fabmesh
