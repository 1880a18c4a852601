#pragma once
// Curvature against arc length along a composite curve: the data of a
// curvature plot, with the joints where it may jump.

#include <vector>

#include "geometry/curves/composite.h"

namespace fabmesh {

/// One sample: arc length from the curve's start (model units) and signed
/// curvature (1 / model units, positive turning left) at segment parameter s.
struct CurvatureSample {
  double s = 0.0;
  double arc_length = 0.0;
  double curvature = 0.0;
};

struct CurvatureProfile {
  /// Per segment, samples at s = 0, 1/m, ..., 1 (m = samples_per_segment).
  /// A sample where the curve stops (zero speed, curvature undefined) is left out.
  std::vector<std::vector<CurvatureSample>> segments;
  /// Arc length at the end of each segment (the last one is the curve's length);
  /// joint i of CompositeCurve::joints() sits at segment_ends[i] (the closing joint at the length).
  std::vector<double> segment_ends;
  double length = 0.0;
};

/// The curvature a picture draws at segment parameter s: Segment::curvature,
/// or 0 where |k| times the size of the segment's control polygon is below
/// 1e-9 (a radius a billion times the segment's size), which is what rounding
/// leaves on a straight or flat curve (a flat H-Bézier patch's border gives
/// curvatures near 1e-16 of alternating sign). NaN where the curve stops.
double drawn_curvature(const Segment& seg, double s);

/// Samples analytic curvature (drawn_curvature) on a uniform grid of each
/// segment; arc length is integrated between grid points with 8-point
/// Gauss-Legendre quadrature of |r'(s)|. \throw RangeError unless
/// samples_per_segment is in [1, 100000].
CurvatureProfile curvature_profile(const CompositeCurve& curve, int samples_per_segment);

}  // namespace fabmesh
