#pragma once
// Segments as Bézier curves, for files that store curves as (rational)
// B-splines (STEP): exact where the family is polynomial, or rational in a
// substituted parameter, and approximated with a proven bound where it is
// neither (docs/math/curves.md 4).

#include <optional>
#include <vector>

#include "geometry/core/types.h"
#include "geometry/curves/segment.h"

namespace fabmesh {

/// A Bézier curve of degree poles.size() - 1 over w in [0, 1]; rational when
/// it has weights (one positive weight per pole).
struct BezierPiece {
  std::vector<Vec2> poles;
  std::vector<double> weights;  ///< empty: polynomial
};

/// The point at w in [0, 1] (de Casteljau, in homogeneous coordinates when rational).
Vec2 evaluate(const BezierPiece& piece, double w);

/// The exact Bézier form of a segment, where its family has one: a line
/// (degree 1), a quasi-cubic B-spline span (a quartic polynomial: degree 4),
/// a rational cubic Bézier segment (itself: degree 3 with its weights) and a
/// T-Bézier segment (rational of degree 6 in w = tan(pi t / 4)).
/// nullopt for ellipse arcs (conics: files write them as such) and H-Bézier
/// segments (not rational: hermite_approximation).
std::optional<BezierPiece> exact_bezier(const Segment& segment);

/// The parameter w of exact_bezier(segment) at the segment's parameter s:
/// tan(pi s / 4) for a T-Bézier segment, s for the polynomial and rational Bézier families.
double bezier_parameter(const Segment& segment, double s);

/// The cubic over a parameter step h from point a with derivative da to
/// point b with derivative db (derivatives per unit of that parameter).
BezierPiece hermite_cubic(const Vec2& a, const Vec2& da, const Vec2& b, const Vec2& db, double h);

/// Cubic pieces that interpolate a segment's points and first derivatives at
/// equal steps h of s, and a proven bound of their distance from it.
struct BezierApproximation {
  std::vector<BezierPiece> pieces;  ///< in order of s, each of degree 3
  /// |r(s) - p(s)| <= bound: per coordinate the Hermite remainder is
  /// r''''(xi) (s - a)^2 (s - b)^2 / 24 <= M4 h^4 / 384, so the distance is at
  /// most sqrt(2) M4 h^4 / 384, M4 = Segment::fourth_derivative_bound().
  double bound = 0.0;
};

/// The fewest equal cubic Hermite pieces (at most max_pieces) whose proven
/// bound is at most `tolerance` (> 0).
/// \throw RangeError for a tolerance <= 0; GeometryError when max_pieces do not reach it
BezierApproximation hermite_approximation(const Segment& segment, double tolerance, int max_pieces = 4096);

}  // namespace fabmesh
