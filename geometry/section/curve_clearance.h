#pragma once
// The clearance of exact planar curves: how close pieces of different loops
// (or of different parts of one loop) come, decided on the exact curves by
// subdivision with proven chord bounds, not on their sampled polylines.

#include <cstddef>
#include <limits>
#include <memory>
#include <vector>

#include "geometry/curves/segment.h"
#include "geometry/sampling/offset_curve.h"
#include "geometry/sampling/sample_curve.h"

namespace fabmesh {

/// An exact curve over s in [0, 1] with a proven bound on the distance
/// between any of its arcs and the arc's chord.
class ExactArc {
 public:
  virtual ~ExactArc() = default;
  virtual Vec2 point(double s) const = 0;
  virtual const ChordBound& chord_bound() const = 0;
};

/// A segment of a composite curve.
class SegmentArc : public ExactArc {
 public:
  explicit SegmentArc(const Segment& segment) : segment_(&segment), bound_(segment) {}
  Vec2 point(double s) const override { return segment_->point(s); }
  const ChordBound& chord_bound() const override { return bound_; }

 private:
  const Segment* segment_;
  SegmentChordBound bound_;
};

/// The offset of a segment (offset_curve.h).
class OffsetArc : public ExactArc {
 public:
  OffsetArc(const Segment& segment, const OffsetSpec& offset)
      : segment_(&segment), offset_(offset), bound_(segment, offset) {}
  Vec2 point(double s) const override { return offset_jet(*segment_, offset_, s).point; }
  const ChordBound& chord_bound() const override { return bound_; }

 private:
  const Segment* segment_;
  OffsetSpec offset_;
  OffsetChordBound bound_;
};

/// A straight piece from `from` (s = 0) to `to` (s = 1): its chord is itself.
class LineArc : public ExactArc {
 public:
  LineArc(const Vec2& from, const Vec2& to) : from_(from), to_(to) {}
  Vec2 point(double s) const override { return from_ + s * (to_ - from_); }
  const ChordBound& chord_bound() const override { return bound_; }

 private:
  class Zero : public ChordBound {
   public:
    Ends at(double) const override { return {}; }
    double bound(double, double, const Ends&, const Ends&) const override { return 0.0; }
  };
  Vec2 from_, to_;
  Zero bound_;
};

/// The arc of `arc` over [s0, s1], belonging to `group` (a loop, or a part of one).
struct ArcPiece {
  const ExactArc* arc = nullptr;
  double s0 = 0.0, s1 = 1.0;
  int group = 0;
};

struct ClearanceOptions {
  /// Stop once the bracket [lower, upper] is narrower than this, model units (> 0).
  double accuracy = 1e-6;
  /// Subdivisions allowed before the bracket is returned as it is.
  std::size_t max_refinements = 200000;
};

/// The smallest distance between pieces of different groups, as a proven
/// bracket, and where it is.
struct Clearance {
  double lower = std::numeric_limits<double>::infinity();  ///< the curves are at least this far apart
  double upper = std::numeric_limits<double>::infinity();  ///< and somewhere at most this far
  Vec2 a{0.0, 0.0}, b{0.0, 0.0};   ///< near the closest points (a on group_a, b on group_b)
  int group_a = -1, group_b = -1;  ///< -1 when there is no pair of groups
};

/// Branch and bound over pairs of pieces from different groups: a pair's
/// distance lies within chord distance -/+ both chord bounds, pairs that
/// cannot beat the best upper bound are dropped, the others are split where
/// the chord bound is larger until the bracket is within `accuracy` (or the
/// curves provably meet: upper below accuracy). Pieces of one group are never
/// compared. Deterministic.
Clearance exact_clearance(const std::vector<ArcPiece>& pieces, const ClearanceOptions& options = {});

}  // namespace fabmesh
