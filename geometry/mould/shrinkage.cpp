#include "geometry/mould/shrinkage.h"

#include <fmt/format.h>

#include <cmath>

#include "geometry/core/error_checks.h"

namespace fabmesh {

double shrinkage_factor(double shrinkage) {
  if (!std::isfinite(shrinkage) || shrinkage < 0.0 || shrinkage >= 1.0) {
    throw RangeError("shrinkage", shrinkage,
                     fmt::format("shrinkage = {} is outside [0, 1): it is the fraction of its wet size a "
                                 "piece loses in firing (e.g. 0.12)",
                                 shrinkage));
  }
  return 1.0 / (1.0 - shrinkage);
}

CompositeCurve scale_curve(const CompositeCurve& curve, double factor) {
  require_positive("factor", factor);
  std::vector<Segment> segments;
  segments.reserve(curve.size());
  for (const Segment& s : curve.segments()) {
    if (s.kind() == SegmentKind::EllipseArc) {
      EllipseArcParams e = *s.ellipse();
      e.center *= factor;
      e.a *= factor;
      e.b *= factor;
      segments.push_back(Segment::ellipse_arc(e));
      continue;
    }
    std::array<Vec2, 4> points = s.control_points();
    for (Vec2& p : points) p *= factor;
    segments.push_back(s.with_points(points));
  }
  return CompositeCurve(std::move(segments), curve.closed());
}

}  // namespace fabmesh
