#pragma once
// Standard closed shapes as curve specs of exact segments (countertop cut-outs).

#include "geometry/curves/curve_spec.h"

namespace fabmesh {

/// A rounded rectangle as a closed curve spec: centre, width w, height h
/// (> 0), corner radius r in [0, min(w, h) / 2], rotated by rotation_deg
/// about its centre; counter-clockwise from the middle of its lower edge's
/// start: 4 lines (skipped where the corners use a side up) and 4 exact
/// quarter circles, declared G1 (G0 when r = 0). Model units.
/// \throw RangeError for sizes out of range
CurveSpec rounded_rect_curve(const Vec2& center, double w, double h, double r, double rotation_deg);

/// A whole ellipse (one exact arc 0..360 degrees) as a closed curve spec,
/// semi-axes a, b > 0 along the axes rotated by rotation_deg. \throw RangeError
CurveSpec ellipse_curve(const Vec2& center, double a, double b, double rotation_deg);

}  // namespace fabmesh
