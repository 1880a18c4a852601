#pragma once
// A DXF SPLINE (a B-spline or NURBS of degree 1 to 3) as the exact cubic
// Bézier spans it is made of, and a polynomial cubic span as the uniform
// cubic B-spline span that is the same curve (docs/math/curves.md 5).

#include <array>
#include <vector>

#include "geometry/core/types.h"

namespace fabmesh {

/// One span of a spline as a cubic Bézier curve: polynomial, or rational with
/// the points' (positive) weights.
struct BezierSpan {
  std::array<Vec2, 4> points{};
  std::array<double, 4> weights{1.0, 1.0, 1.0, 1.0};
  bool rational = false;  ///< the weights differ: a rational cubic Bézier
};

/// The cubic Bézier spans of the B-spline of degree `degree` (1..3) with
/// `knots` (n + degree + 1, non-decreasing), control `points` (n) and their
/// `weights` (n, finite and > 0) over its domain [knots[degree], knots[n]],
/// one per span of positive length, in order, in linear time. A span whose
/// degree + 1 control points weigh the same is a polynomial (its Bézier from
/// the plane points, the degree raised exactly); a rational span's comes from
/// the homogeneous points by blossoming, exactly.
std::vector<BezierSpan> bezier_spans(const std::vector<double>& knots, const std::vector<Vec2>& points,
                                     const std::vector<double>& weights, int degree);

/// The control points of the uniform cubic B-spline span (a quasi-cubic span
/// with both local parameters 0) that is the cubic Bézier curve `z` exactly.
std::array<Vec2, 4> bspline_span_of(const std::array<Vec2, 4>& z);

}  // namespace fabmesh
