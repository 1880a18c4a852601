#pragma once
// How close a tool-centre path comes to the part: the loops sampled from
// their exact curves into a BoundaryIndex, and the least distance from a
// path's pieces to them.

#include <cstddef>
#include <limits>
#include <vector>

#include "geometry/toolpath/boundary_index.h"
#include "geometry/toolpath/manufacturability.h"
#include "geometry/toolpath/path_piece.h"

namespace fabmesh {

/// The loops sampled within `tolerance` of their exact curves (sample_curve,
/// proven bound), as edges tagged with their loop and segment.
struct SampledBoundary {
  std::vector<BoundaryEdge> edges;
  double deviation = 0.0;  ///< proven: every edge point is this close to its exact curve and back
};

/// \throw RangeError (tolerance), BudgetError (max_points)
SampledBoundary sample_boundary(const std::vector<CutCurve>& loops, double tolerance, std::size_t max_points);

/// The closest approach of a path to the boundary.
struct Clearance {
  double distance = std::numeric_limits<double>::infinity();  ///< to the sampled boundary
  std::size_t piece = 0;                                      ///< the path piece
  std::size_t edge = 0;                                       ///< the boundary edge
  Vec2 at{0.0, 0.0};                                          ///< on the path
};

/// The least distance between the pieces of `path` (arcs as chords within
/// `sagitta`; pieces with role Dogbone skipped) and the boundary edges that
/// lie within `radius`; distance = infinity when none does. The exact path
/// is then at least distance - sagitta - boundary deviation from the exact part.
Clearance path_clearance(const std::vector<PathPiece>& path, const BoundaryIndex& boundary, double radius,
                         double sagitta);

}  // namespace fabmesh
