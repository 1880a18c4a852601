#pragma once
// Adaptive sampling of curves into polylines with a proven deviation bound.

#include <cstddef>
#include <vector>

#include "geometry/core/limits.h"
#include "geometry/core/types.h"
#include "geometry/curves/composite.h"

namespace fabmesh {

struct SampleOptions {
  double tolerance = 0.01;                     ///< max distance between polyline and curve, model units (> 0)
  std::size_t max_points = kDefaultMaxPoints;  ///< budget; exceeding it is a BudgetError
  int min_pieces_per_segment = 2;              ///< never fewer chords than this per segment
};

/// Samples one segment: parameters s_0 = 0 < ... < s_m = 1 such that on every
/// piece the chord stays within `tolerance` of the arc. The bound used is
/// |r(s) - chord(s)| <= h^2/8 max|r''| on a piece of length h, with max|r''|
/// bounded from the endpoint values and a bound on |r'''| (itself bounded from
/// a grid and the basis' fourth-derivative bound), so it is guaranteed.
/// Returns the parameters; `achieved` receives the largest piece bound.
std::vector<double> sample_segment_parameters(const Segment& segment, const SampleOptions& options,
                                              double* achieved = nullptr);

/// Where on the curve a polyline point lies: segment index and parameter s.
struct CurveParam {
  std::size_t segment = 0;
  double s = 0.0;
};

/// Samples a composite curve. Joint points appear once; a closed curve's
/// polyline does not repeat its first point. max_deviation is the proven
/// bound actually achieved (<= tolerance, plus any joint gap). When `params`
/// is given it receives the curve parameter of every polyline point.
/// \throw RangeError for a bad tolerance, BudgetError over the point budget.
Polyline2 sample_curve(const CompositeCurve& curve, const SampleOptions& options,
                       std::vector<CurveParam>* params = nullptr);

}  // namespace fabmesh
