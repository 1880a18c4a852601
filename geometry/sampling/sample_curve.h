#pragma once
// Adaptive sampling of curves into polylines with a proven deviation bound.

#include <array>
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

/// A proven bound on how far the chords of one curve (parameter s in [0, 1])
/// stray from its arcs. The adaptive sampler asks it about every piece it
/// considers; the values a piece needs from its two ends are computed once
/// per sample (`at`) and handed back to `bound`.
class ChordBound {
 public:
  using Ends = std::array<double, 6>;
  virtual ~ChordBound() = default;
  /// What a piece's bound needs from its end at s (may throw GeometryError
  /// when the curve is unusable there, e.g. a wall that folds).
  virtual Ends at(double s) const = 0;
  /// Upper bound on the distance between the arc over [s0, s1] and its chord,
  /// model units; +infinity when nothing can be proven on so long a piece.
  virtual double bound(double s0, double s1, const Ends& a, const Ends& b) const = 0;
};

/// The chord bound of an exact segment: on a piece of length h,
/// |r(s) - chord(s)| <= h^2/8 max|r''|, with max|r''| <= max(|r''(s0)|,
/// |r''(s1)|) + h/2 M3 and M3 >= |r'''| on [0, 1] (a grid of |r'''| plus half
/// its step times the basis' fourth-derivative bound).
class SegmentChordBound : public ChordBound {
 public:
  explicit SegmentChordBound(const Segment& segment);
  Ends at(double s) const override;
  double bound(double s0, double s1, const Ends& a, const Ends& b) const override;
  /// M3: the bound of |r'''| over the whole segment.
  double third_derivative_bound() const { return m3_; }

 private:
  const Segment* segment_;
  double m3_ = 0.0;
};

/// Upper bound of |r'''| over [0, 1] of a segment (see SegmentChordBound).
double third_derivative_bound(const Segment& segment);

/// Bisects [0, 1] until every piece's bound is at most options.tolerance.
/// Returns the parameters 0 = s_0 < ... < s_m = 1; `achieved` receives the
/// largest piece bound. \throw BudgetError over options.max_points or below
/// double precision; what `bound.at` throws.
std::vector<double> sample_parameters(const ChordBound& bound, const SampleOptions& options,
                                      double* achieved = nullptr);

/// Samples one segment: parameters s_0 = 0 < ... < s_m = 1 such that on every
/// piece the chord stays within `tolerance` of the arc, by SegmentChordBound,
/// so it is guaranteed. Returns the parameters; `achieved` receives the
/// largest piece bound.
std::vector<double> sample_segment_parameters(const Segment& segment, const SampleOptions& options,
                                              double* achieved = nullptr);

/// A lower bound on the number of chords sample_segment_parameters makes for
/// `tolerance`, computed before any refinement: every accepted piece of
/// length h has h^2/8 |r''(s)| <= tolerance at each of its points, so the
/// count is at least the integral of sqrt(|r''| / (8 tolerance)) ds, summed
/// here from below on a grid with the bound of |r'''|.
double min_chord_count(const Segment& segment, double tolerance, int min_pieces = 1);

/// Where on the curve a polyline point lies: segment index and parameter s.
struct CurveParam {
  std::size_t segment = 0;
  double s = 0.0;
};

/// Samples a composite curve. Joint points appear once; a closed curve's
/// polyline does not repeat its first point. max_deviation is the proven
/// bound actually achieved (<= tolerance, plus any joint gap). When `params`
/// is given it receives the curve parameter of every polyline point.
/// \throw RangeError for a bad tolerance, BudgetError over the point budget
///        (refused before refining when min_chord_count already exceeds it).
Polyline2 sample_curve(const CompositeCurve& curve, const SampleOptions& options,
                       std::vector<CurveParam>* params = nullptr);

/// The parameter range [s0, s1] of segment params[i].segment that polyline
/// edge i -> i+1 samples (the last edge of a closed curve runs to the end of
/// its segment).
std::array<double, 2> edge_parameters(const std::vector<CurveParam>& params, std::size_t i);

}  // namespace fabmesh
