#include "geometry/toolpath/offset_segment.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geometry/core/error_checks.h"
#include "geometry/toolpath/curvature_bound.h"

namespace fabmesh {
namespace {

Vec2 right_normal(const Vec2& t) { return Vec2(t.y(), -t.x()); }

// Radius of curvature of the offset at s (travel direction given by sign).
double offset_radius_of_curvature(const Segment& seg, double sign, double r, double s) {
  const CurveJet j = seg.jet(s);
  const double speed = j[1].norm();
  const double k = sign * cross2(j[1], j[2]) / (speed * speed * speed);
  const double ko = k / (1.0 + r * k);  // curvature of the offset curve
  return ko == 0.0 ? INFINITY : 1.0 / std::abs(ko);
}

std::vector<PathPiece> circle_offset(const Segment& seg, bool reversed, std::size_t index, double r) {
  const EllipseArcParams& e = *seg.ellipse();
  const double sign = reversed ? -1.0 : 1.0;
  const double span = (e.to_deg - e.from_deg) * M_PI / 180.0;
  const double sweep = sign * span;
  const double radius = sweep > 0.0 ? e.a + r : e.a - r;
  if (radius < -1e-12 * e.a) {
    throw GeometryError(fmt::format("segment {}", index),
                        fmt::format("segment {} (circle arc of radius {}) is tighter than the tool radius {}",
                                    index, e.a, r));
  }
  if (radius <= 1e-12 * e.a) {  // the tool fits the arc exactly: its centre stands still
    return {line_piece(e.center, e.center, PieceRole::Offset, index)};
  }
  const Vec2 start = seg.point(reversed ? 1.0 : 0.0);
  const Vec2 u = (start - e.center).normalized();
  return {arc_piece(e.center, e.center + radius * u, sweep, PieceRole::Offset, index)};
}

struct Chord {
  double a, b;
};

// Parameters of a chain of chords within the tolerance of the exact offset (header derivation).
std::vector<double> chain_parameters(const Segment& seg, std::size_t index, const SegmentOffsetOptions& o,
                                     double* achieved) {
  const double m4 = seg.fourth_derivative_bound();
  const double r = o.radius;
  auto bound = [&](const Chord& c) -> double {
    const JetBounds jb = jet_bounds(seg, c.a, c.b, m4);
    if (!(jb.min_speed > 0.0)) return INFINITY;
    const double s = jb.min_speed, b2 = jb.d2, b3 = jb.d3;
    const double o2 = b2 * (1.0 + r * b2 / (s * s)) + r * (b3 / s + 3.0 * b2 * b2 / (s * s));
    return 0.5 * jb.half * jb.half * o2;
  };
  std::vector<double> params{0.0};
  std::vector<Chord> stack;
  constexpr int kInitial = 4;
  for (int i = kInitial - 1; i >= 0; --i) {
    stack.push_back({static_cast<double>(i) / kInitial, static_cast<double>(i + 1) / kInitial});
  }
  double worst = 0.0;
  while (!stack.empty()) {
    const Chord c = stack.back();
    stack.pop_back();
    const double b = bound(c);
    if (b <= o.tolerance) {
      params.push_back(c.b);
      worst = std::max(worst, b);
      if (params.size() > o.max_points) {
        throw BudgetError(static_cast<double>(params.size()), static_cast<double>(o.max_points),
                          fmt::format("the offset of segment {} within {} needs more than {} points (the "
                                      "point budget)",
                                      index, o.tolerance, o.max_points));
      }
      continue;
    }
    const double mid = 0.5 * (c.a + c.b);
    if (!(mid > c.a && mid < c.b)) {
      throw GeometryError(fmt::format("segment {}", index),
                          fmt::format("segment {} ({}) has no tangent near s = {:.9g} (zero speed): its "
                                      "offset is undefined",
                                      index, to_string(seg.kind()), c.a));
    }
    stack.push_back({mid, c.b});
    stack.push_back({c.a, mid});
  }
  params.back() = 1.0;
  if (achieved) *achieved = worst;
  return params;
}

}  // namespace

Vec2 exact_offset_point(const Segment& seg, bool reversed, double radius, double s) {
  const CurveJet j = seg.jet(s);
  const Vec2 t = (reversed ? -j[1] : j[1]).normalized();
  return j[0] + radius * right_normal(t);
}

std::vector<PathPiece> offset_segment(const Segment& seg, bool reversed, std::size_t index,
                                      const SegmentOffsetOptions& o, double* achieved) {
  require_positive("radius", o.radius);
  require_positive("tolerance", o.tolerance);
  if (achieved) *achieved = 0.0;
  if (seg.kind() == SegmentKind::Line) {
    const Vec2 a = seg.point(reversed ? 1.0 : 0.0), b = seg.point(reversed ? 0.0 : 1.0);
    const Vec2 n = o.radius * right_normal((b - a).normalized());
    return {line_piece(a + n, b + n, PieceRole::Offset, index)};
  }
  if (seg.kind() == SegmentKind::EllipseArc && seg.ellipse()->a == seg.ellipse()->b) {
    return circle_offset(seg, reversed, index, o.radius);
  }
  std::vector<double> params = chain_parameters(seg, index, o, achieved);
  if (reversed) {
    std::reverse(params.begin(), params.end());
  }
  const double sign = reversed ? -1.0 : 1.0;
  std::vector<PathPiece> out;
  out.reserve(params.size() - 1);
  Vec2 prev = exact_offset_point(seg, reversed, o.radius, params[0]);
  double prev_radius = offset_radius_of_curvature(seg, sign, o.radius, params[0]);
  for (std::size_t i = 1; i < params.size(); ++i) {
    const Vec2 next = exact_offset_point(seg, reversed, o.radius, params[i]);
    const double next_radius = offset_radius_of_curvature(seg, sign, o.radius, params[i]);
    PathPiece p = line_piece(prev, next, PieceRole::Offset, index);
    p.radius_of_curvature = std::min(prev_radius, next_radius);
    out.push_back(p);
    prev = next;
    prev_radius = next_radius;
  }
  return out;
}

}  // namespace fabmesh
