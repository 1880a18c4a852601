#pragma once
// Segment specs built in code, as a design file would give them.

#include <utility>
#include <vector>

#include "geometry/curves/curve_spec.h"

namespace fabmesh::test {

/// A T-Bézier segment with explicit control points and shape parameters.
inline SegmentSpec explicit_tbezier(std::vector<Vec2> pts, double l, double m) {
  SegmentSpec s;
  s.points = std::move(pts);
  s.lambda = l;
  s.mu = m;
  return s;
}

/// A T-Bézier segment joined to the previous one with continuity `c` (its free points `pts`).
inline SegmentSpec joined(Continuity c, std::vector<Vec2> pts, double l, double m, double alpha,
                          double beta = 0.0) {
  SegmentSpec s = explicit_tbezier(std::move(pts), l, m);
  s.join = JoinSpec{c, alpha, beta, 1.0, 0.0};
  return s;
}

}  // namespace fabmesh::test
