#include "geometry/curves/shapes.h"

#include <Eigen/Geometry>
#include <array>
#include <cmath>

#include "geometry/core/error_checks.h"

namespace fabmesh {
namespace {

SegmentSpec arc_spec(const Vec2& center, double a, double b, double rotation_deg, double from, double to) {
  SegmentSpec s;
  s.kind = SegmentKind::EllipseArc;
  s.ellipse.center = center;
  s.ellipse.a = a;
  s.ellipse.b = b;
  s.ellipse.rotation_deg = rotation_deg;
  s.ellipse.from_deg = from;
  s.ellipse.to_deg = to;
  Segment::ellipse_arc(s.ellipse);  // range checks
  return s;
}

}  // namespace

CurveSpec ellipse_curve(const Vec2& center, double a, double b, double rotation_deg) {
  require_positive("a", a);
  require_positive("b", b);
  require_in_range("rotation_deg", rotation_deg, -1e6, 1e6);
  CurveSpec spec;
  spec.closed = true;
  spec.closing_declared = Continuity::G1;
  spec.segments.push_back(arc_spec(center, a, b, rotation_deg, 0.0, 360.0));
  return spec;
}

CurveSpec rounded_rect_curve(const Vec2& center, double w, double h, double r, double rotation_deg) {
  require_positive("size[0]", w);
  require_positive("size[1]", h);
  require_in_range("radius", r, 0.0, 0.5 * std::min(w, h));
  require_in_range("rotation_deg", rotation_deg, -1e6, 1e6);
  const double t = rotation_deg * M_PI / 180.0;
  const Eigen::Rotation2Dd rot(t);
  auto place = [&](double x, double y) -> Vec2 { return center + rot * Vec2(x, y); };
  const double hw = 0.5 * w, hh = 0.5 * h;
  const Continuity joint = r > 0.0 ? Continuity::G1 : Continuity::G0;
  CurveSpec spec;
  spec.closed = true;
  spec.closing_declared = joint;
  // Counter-clockwise: each straight side (skipped when the corners use it all up), then the corner after it.
  const std::array<Vec2, 4> side_from{Vec2(-hw + r, -hh), Vec2(hw, -hh + r), Vec2(hw - r, hh),
                                      Vec2(-hw, hh - r)};
  const std::array<Vec2, 4> side_to{Vec2(hw - r, -hh), Vec2(hw, hh - r), Vec2(-hw + r, hh),
                                    Vec2(-hw, -hh + r)};
  const std::array<Vec2, 4> corner{Vec2(hw - r, -hh + r), Vec2(hw - r, hh - r), Vec2(-hw + r, hh - r),
                                   Vec2(-hw + r, -hh + r)};
  for (int i = 0; i < 4; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (side_from[k] != side_to[k]) {
      SegmentSpec line;
      line.kind = SegmentKind::Line;
      if (spec.segments.empty()) line.points.push_back(place(side_from[k].x(), side_from[k].y()));
      line.points.push_back(place(side_to[k].x(), side_to[k].y()));
      line.declared = joint;
      spec.segments.push_back(line);
    }
    if (r > 0.0) {
      SegmentSpec arc =
          arc_spec(place(corner[k].x(), corner[k].y()), r, r, rotation_deg, -90.0 + 90.0 * i, 90.0 * i);
      arc.declared = joint;
      spec.segments.push_back(arc);
    }
  }
  return spec;
}

}  // namespace fabmesh
