#pragma once
// A piecewise curve of segments of any family, open or closed, with a report
// of the measured continuity at every joint.

#include <limits>
#include <string>
#include <vector>

#include "geometry/curves/segment.h"

namespace fabmesh {

enum class Continuity { None = -1, G0 = 0, G1 = 1, G2 = 2 };

const char* to_string(Continuity c);

/// Thresholds that turn measured joint numbers into a continuity class.
struct JointTolerances {
  double gap_relative = 1e-9;        ///< position gap / curve extent
  double angle = 1e-7;               ///< tangent angle, radians
  double curvature_relative = 1e-6;  ///< |k1 - k2| / max(|k1|, |k2|, 1 / extent)
};

/// Measured continuity where segment `before` ends and segment `after` starts.
struct JointReport {
  std::size_t before = 0;
  std::size_t after = 0;
  bool closing = false;           ///< the joint that closes a closed curve
  double gap = 0.0;               ///< |r_before(1) - r_after(0)|, model units
  double tangent_angle = 0.0;     ///< angle between the end tangents, radians
  double curvature_before = 0.0;  ///< signed curvature, 1 / model units
  double curvature_after = 0.0;
  double curvature_jump = 0.0;  ///< relative, see JointTolerances
  Continuity achieved = Continuity::None;
};

class CompositeCurve {
 public:
  CompositeCurve() = default;
  /// \throw GeometryError when `segments` is empty.
  CompositeCurve(std::vector<Segment> segments, bool closed);

  const std::vector<Segment>& segments() const { return segments_; }
  std::size_t size() const { return segments_.size(); }
  bool closed() const { return closed_; }
  /// Diagonal of the bounding box of 9 points on each segment (the scale for
  /// relative tolerances), computed once when the curve is made.
  double extent() const { return extent_; }

  /// Point at global parameter g in [0, size()]: segment floor(g) at s = g - floor(g).
  Vec2 point(double g) const;

  /// One report per joint: size()-1 for an open curve, size() for a closed one
  /// (the closing joint last).
  std::vector<JointReport> joints(const JointTolerances& tol = {}) const;

 private:
  std::vector<Segment> segments_;
  bool closed_ = false;
  double extent_ = std::numeric_limits<double>::infinity();  ///< of no segments: as if measured
};

/// Measures one joint between two segments.
JointReport measure_joint(const Segment& before, const Segment& after, double extent,
                          const JointTolerances& tol);

}  // namespace fabmesh
