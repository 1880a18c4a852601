#pragma once
// The offset of one curve segment by the tool radius, as path pieces: exact
// where the offset is a line or a circle, chords within a proven bound of the
// exact offset curve elsewhere.
//
// Travelling along the segment (with the parameter s, or against it: sign
// = -1), let T be the unit tangent, N the unit normal to the right of the
// travel, and k the signed curvature in the travel direction (positive
// turning left). The exact offset by the radius r to the right is
//   o(s) = r(s) + r N(s).
// Since dN/ds = k |r'| T, its derivatives are
//   o'  = r' (1 + r k)
//   o'' = r'' (1 + r k) + r k' r'.
// With |k| <= |r''| / |r'|^2 and |k'| |r'| <= |r'''| / |r'| + 3 |r''|^2 / |r'|^2
// (curvature_bound.h), on an interval of half-width h with the bounds B2,
// B3, S of curvature_bound.h:
//   |o''| <= B2 (1 + r B2 / S^2) + r (B3 / S + 3 B2^2 / S^2) = O2.
// The chord between o(a) and o(b) (b - a = 2h) then stays within
//   (2h)^2 / 8 * O2 = h^2 / 2 * O2
// of the arc of o between them (and the arc within that of the chord: the
// error e(s) = o(s) - chord(s) vanishes at both ends, so |e| <= (s-a)(b-s)/2 O2).
// Chords are bisected until this bound is at most the tolerance. The offset
// is regular where 1 + r k > 0, which the manufacturability checks prove
// for every concave stretch before offsets are built.

#include <cstddef>
#include <vector>

#include "geometry/curves/segment.h"
#include "geometry/toolpath/path_piece.h"

namespace fabmesh {

struct SegmentOffsetOptions {
  double radius = 6.0;               ///< r > 0, model units
  double tolerance = 0.005;          ///< largest chord deviation from the exact offset, > 0
  std::size_t max_points = 5000000;  ///< budget of chord points; more is a BudgetError
};

/// The offset of `segment` to the right of the travel direction (`reversed`:
/// against the parameter). Lines give one line; circle arcs (ellipse arcs
/// with a == b) one arc of radius R + r (turning left) or R - r (turning
/// right; a zero-length line at the centre when that is 0); everything else a chain of chords whose
/// ends lie on the exact offset, with the proven bound above. The pieces'
/// role is Offset, their `segment` is `index`. `achieved` receives the largest
/// chord bound (0 for exact pieces).
/// \throw BudgetError when the tolerance needs more than max_points chords,
///        GeometryError when the segment has no tangent somewhere (zero speed)
std::vector<PathPiece> offset_segment(const Segment& segment, bool reversed, std::size_t index,
                                      const SegmentOffsetOptions& options, double* achieved = nullptr);

/// The exact offset point at parameter s (for tests and checks): r(s) + r N(s).
Vec2 exact_offset_point(const Segment& segment, bool reversed, double radius, double s);

}  // namespace fabmesh
