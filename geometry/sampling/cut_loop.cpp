#include "geometry/sampling/cut_loop.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/core/errors.h"
#include "geometry/sampling/sample_curve.h"

namespace fabmesh {
namespace {

void reverse_loop(CutLoop& loop) {
  std::reverse(loop.entities.begin(), loop.entities.end());
  for (CutEntity& e : loop.entities) {
    std::reverse(e.points.begin(), e.points.end());
    std::swap(e.arc.from_deg, e.arc.to_deg);
  }
}

// The arc's end points and its extreme points in x and y that lie on the arc.
void arc_extremes(const EllipseArcParams& a, std::vector<Vec2>& out) {
  const double phi = a.rotation_deg * M_PI / 180.0;
  const double lo = std::min(a.from_deg, a.to_deg), hi = std::max(a.from_deg, a.to_deg);
  out.push_back(arc_point(a, a.from_deg));
  out.push_back(arc_point(a, a.to_deg));
  // dx/dt = 0 and dy/dt = 0 of center + R(phi) (a cos t, b sin t).
  for (double t0 : {std::atan2(-a.b * std::sin(phi), a.a * std::cos(phi)),
                    std::atan2(a.b * std::cos(phi), a.a * std::sin(phi))}) {
    for (int k = -3; k <= 3; ++k) {
      const double deg = t0 * 180.0 / M_PI + 180.0 * k;
      if (deg >= lo && deg <= hi) out.push_back(arc_point(a, deg));
    }
  }
}

}  // namespace

Vec2 arc_point(const EllipseArcParams& a, double deg) {
  const double t = deg * M_PI / 180.0;
  return a.center +
         Eigen::Rotation2Dd(a.rotation_deg * M_PI / 180.0) * Vec2(a.a * std::cos(t), a.b * std::sin(t));
}

CutLoop cut_loop(const CompositeCurve& curve, const std::string& label, bool outer,
                 const CutLoopOptions& options) {
  require_positive("tolerance", options.tolerance);
  SampleOptions so;
  so.tolerance = options.tolerance;
  CutLoop loop;
  loop.label = label;
  loop.outer = outer;
  loop.closed = curve.closed();
  for (const Segment& seg : curve.segments()) {
    if (seg.kind() == SegmentKind::Line) {
      loop.entities.push_back({CutKind::Line, {seg.point(0.0), seg.point(1.0)}, {}});
    } else if (seg.kind() == SegmentKind::EllipseArc) {
      loop.entities.push_back({CutKind::Arc, {seg.point(0.0), seg.point(1.0)}, *seg.ellipse()});
    } else {
      if (loop.entities.empty() || loop.entities.back().kind != CutKind::Polyline) {
        loop.entities.push_back({CutKind::Polyline, {seg.point(0.0)}, {}});
      }
      std::vector<Vec2>& pts = loop.entities.back().points;
      const std::vector<double> s = sample_segment_parameters(seg, so);
      for (std::size_t i = 1; i < s.size(); ++i) pts.push_back(seg.point(s[i]));
    }
  }
  // A loop that starts and ends inside one run of polyline segments is one polyline.
  if (loop.closed && loop.entities.size() > 1 && loop.entities.front().kind == CutKind::Polyline &&
      loop.entities.back().kind == CutKind::Polyline) {
    std::vector<Vec2>& tail = loop.entities.back().points;
    tail.insert(tail.end(), loop.entities.front().points.begin() + 1, loop.entities.front().points.end());
    loop.entities.erase(loop.entities.begin());
  }
  if (options.reverse) reverse_loop(loop);
  return loop;
}

std::pair<Vec2, Vec2> cut_bounds(const std::vector<CutLoop>& loops) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Vec2 lo = Vec2::Constant(kInf), hi = Vec2::Constant(-kInf);
  std::vector<Vec2> pts;
  for (const CutLoop& l : loops) {
    for (const CutEntity& e : l.entities) {
      pts = e.points;
      if (e.kind == CutKind::Arc) arc_extremes(e.arc, pts);
      for (const Vec2& p : pts) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    }
  }
  return {lo, hi};
}

}  // namespace fabmesh
