#pragma once
// The offset of an exact segment by a constant distance along its normal (a
// vessel's inner wall), with a proven chord bound for adaptive sampling and a
// proven check that the offset does not fold.

#include <string>

#include "geometry/curves/segment.h"
#include "geometry/sampling/sample_curve.h"

namespace fabmesh {

/// The offset o(s) = r(s) + distance * side * N(s) of a segment, N the unit
/// left normal (r' turned by +90 degrees), side = +1 or -1.
struct OffsetSpec {
  double distance = 0.0;      ///< model units (> 0)
  double side = 1.0;          ///< +1: to the left of the direction of travel, -1: to the right
  std::string what = "wall";  ///< names the offset in messages ("wall 0.3")
  std::string where;          ///< names the segment in messages ("segment 2 of profile")
};

/// Point and derivatives of the offset at s, with what its chord bound needs.
struct OffsetJet {
  Vec2 point, d1, d2;  ///< o, o', o'' (d/ds)
  double speed = 0.0;  ///< |r'|
  /// Curvature of r toward the offset side (positive: the offset side is
  /// concave, the offset folds where distance * k >= 1), 1 / model units.
  double k = 0.0;
};

/// o, o' = |r'| (1 - distance k) T and o'' from the segment's jet, analytically.
OffsetJet offset_jet(const Segment& segment, const OffsetSpec& offset, double s);

/// Chord bound of the offset curve, proven on each piece [s0, s1]:
/// |o - chord| <= h^2/8 sup|o''|, with sup|o''| the smaller of
///   A = M2 + d (M3 / sigma + 3 M2^2 / sigma^2)
///   B = max(|o''(s0)|, |o''(s1)|) + h/2 (M3 + d (M4 / sigma + 10 M2 M3 / sigma^2 + 15 M2^3 / sigma^3))
/// where, on the piece, sigma <= |r'|, M2 >= |r''|, M3 >= |r'''| (from the end
/// values and the next derivative's bound) and M4 >= |r''''| (the basis'
/// bound). The piece is accepted only when the offset provably does not fold
/// on it: max(k(s0), k(s1)) + h/2 (M3 / sigma^2 + 3 M2^2 / sigma^3) < 1 / d
/// (a bound of |k'|); otherwise its bound is +infinity and it is split.
/// `at` throws GeometryError where distance * k >= 1 at a point; `bound`
/// throws it when a piece too short to split still cannot be proven.
class OffsetChordBound : public ChordBound {
 public:
  OffsetChordBound(const Segment& segment, const OffsetSpec& offset);
  Ends at(double s) const override;
  double bound(double s0, double s1, const Ends& a, const Ends& b) const override;

 private:
  const Segment* segment_;
  OffsetSpec offset_;
  double m3_ = 0.0, m4_ = 0.0;
};

}  // namespace fabmesh
