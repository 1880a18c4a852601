#pragma once
// Simplicity of 2D polylines and polygons, decided with exact predicates.

#include <cstddef>
#include <optional>
#include <vector>

#include "geometry/core/types.h"

namespace fabmesh {

/// Two edges of a polyline that meet where they should not: edge i runs
/// from point i to point i+1 (the closing edge of a loop is the last one).
struct EdgeCrossing {
  std::size_t first = 0;
  std::size_t second = 0;
  Vec2 where{0.0, 0.0};  ///< a point near the crossing (for messages)
};

/// The first pair of edges (in a deterministic order) that intersect other
/// than adjacent edges at their shared end point, or nullopt when the
/// polyline (closed: polygon) is simple. Repeated consecutive points and
/// edges folding back on their neighbour count as crossings. Exact
/// predicates (CGAL Epick), O(n log n) expected via box intersection.
std::optional<EdgeCrossing> find_crossing(const std::vector<Vec2>& points, bool closed);

/// The same for several closed loops at once: an edge may not meet any edge
/// of another loop either. Edge indices count through the loops in order.
std::optional<EdgeCrossing> find_crossing(const std::vector<std::vector<Vec2>>& loops);

/// Twice the signed area of a closed polygon (positive: counter-clockwise).
double signed_area2(const std::vector<Vec2>& points);

}  // namespace fabmesh
