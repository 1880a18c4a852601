#pragma once
// A shell's inner wall for files that store curves as B-splines (STEP): the
// offset of a segment is not a polynomial nor a rational curve, so it gets
// cubic Hermite pieces whose distance from it is proven on each piece.

#include <vector>

#include "geometry/curves/bezier_form.h"
#include "geometry/curves/composite.h"
#include "geometry/curves/segment.h"
#include "geometry/sampling/offset_curve.h"

namespace fabmesh {

/// One piece of an exact closed section: a segment over s in [0, 1], or,
/// when `offset.distance` > 0, the arc of its offset from s0 to s1 (either
/// way round).
struct ExactPiece {
  Segment segment;
  OffsetSpec offset;  ///< distance 0: the segment itself
  double s0 = 0.0, s1 = 1.0;
};

/// The pieces of a composite curve, each segment whole.
std::vector<ExactPiece> exact_pieces(const CompositeCurve& curve);

/// Cubic Hermite pieces through the offset's points and tangents at equal
/// steps of s from s0 to s1, the fewest (doubling, at most max_pieces) whose
/// proven bound is within `tolerance`. The bound, on each piece, from a grid
/// of cells: |e| <= max |e| at the cells' ends + the offset's chord bound of
/// the cell (OffsetChordBound: h^2/8 sup|o''|) + h^2/8 sup|p''| (the cubic's
/// second derivative, from its control points), e = o - p.
/// \throw GeometryError when the offset folds (OffsetChordBound) or
///        max_pieces do not reach the tolerance
BezierApproximation offset_approximation(const ExactPiece& piece, double tolerance, int max_pieces = 4096);

}  // namespace fabmesh
