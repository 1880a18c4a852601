#include "geometry/curves/composite.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/core/errors.h"

namespace fabmesh {

const char* to_string(Continuity c) {
  switch (c) {
    case Continuity::None:
      return "none";
    case Continuity::G0:
      return "G0";
    case Continuity::G1:
      return "G1";
    case Continuity::G2:
      return "G2";
  }
  return "none";
}

CompositeCurve::CompositeCurve(std::vector<Segment> segments, bool closed)
    : segments_(std::move(segments)), closed_(closed) {
  if (segments_.empty()) throw GeometryError("curve", "a curve needs at least one segment");
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Vec2 lo = Vec2::Constant(kInf), hi = Vec2::Constant(-kInf);
  for (const Segment& seg : segments_) {
    // Sample the segment too: an ellipse arc's control points live in its own frame.
    for (int i = 0; i <= 8; ++i) {
      const Vec2 p = seg.point(i / 8.0);
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  extent_ = (hi - lo).norm();
}

Vec2 CompositeCurve::point(double g) const {
  const double n = static_cast<double>(segments_.size());
  g = std::clamp(g, 0.0, n);
  std::size_t i = std::min(static_cast<std::size_t>(g), segments_.size() - 1);
  return segments_[i].point(g - static_cast<double>(i));
}

namespace {

// Signed curvature cross(d1, d2) / |d1|^3. A straight stretch (the cross
// product exactly 0: a line, or a T-Bézier segment's straight end) is that
// 0 without the power: dividing by the positive, finite or infinite cube
// would give the same signed zero.
double curvature_of(const Vec2& d1, const Vec2& d2) {
  const double c = cross2(d1, d2);
  const double speed = d1.norm();
  if (c == 0.0 && speed >= 1e-100) return c;
  return c / std::pow(speed, 3);
}

}  // namespace

JointReport measure_joint(const Segment& before, const Segment& after, double extent,
                          const JointTolerances& tol) {
  const CurveJet a = before.jet(1.0);
  const CurveJet b = after.jet(0.0);
  JointReport r;
  r.gap = (a[0] - b[0]).norm();
  r.tangent_angle = std::atan2(std::abs(cross2(a[1], b[1])), a[1].dot(b[1]));
  r.curvature_before = curvature_of(a[1], a[2]);
  r.curvature_after = curvature_of(b[1], b[2]);
  const double scale = std::max(
      {std::abs(r.curvature_before), std::abs(r.curvature_after), extent > 0.0 ? 1.0 / extent : 1.0});
  r.curvature_jump = std::abs(r.curvature_before - r.curvature_after) / scale;
  const bool g0 = r.gap <= tol.gap_relative * std::max(extent, 1e-300);
  const bool g1 = g0 && r.tangent_angle <= tol.angle;
  const bool g2 = g1 && r.curvature_jump <= tol.curvature_relative;
  r.achieved = g2 ? Continuity::G2 : g1 ? Continuity::G1 : g0 ? Continuity::G0 : Continuity::None;
  return r;
}

std::vector<JointReport> CompositeCurve::joints(const JointTolerances& tol) const {
  std::vector<JointReport> out;
  const double size = extent();
  const std::size_t n = segments_.size();
  for (std::size_t i = 1; i < n; ++i) {
    JointReport r = measure_joint(segments_[i - 1], segments_[i], size, tol);
    r.before = i - 1;
    r.after = i;
    out.push_back(r);
  }
  if (closed_) {
    JointReport r = measure_joint(segments_[n - 1], segments_[0], size, tol);
    r.before = n - 1;
    r.after = 0;
    r.closing = true;
    out.push_back(r);
  }
  return out;
}

}  // namespace fabmesh
