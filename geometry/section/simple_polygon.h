#pragma once
// Simplicity of 2D polylines and polygons, decided with exact predicates.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
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

/// Whether a planar triangulation with vertices `points` is embedded: every
/// triangle counter-clockwise, and its boundary `cycles` (vertex indices;
/// the outer one counter-clockwise, the holes clockwise, in any order)
/// simple and pairwise disjoint, with every hole strictly inside the outer
/// cycle and outside the other holes. Exact predicates (CGAL Epick). Then
/// each point of the plane is covered by as many triangles as the cycles wind
/// round it, 0 or 1: the triangles meet only at shared edges and vertices.
/// `why`, when given, receives the first condition that fails.
bool is_planar_embedding(const std::vector<Vec2>& points,
                         const std::vector<std::array<std::uint32_t, 3>>& triangles,
                         const std::vector<std::vector<std::uint32_t>>& cycles, std::string* why = nullptr);

/// Where a closed polygon comes near itself across a neck: two points, on
/// edges `first` and `second`, `distance` apart.
struct PolygonNeck {
  std::size_t first = 0;
  std::size_t second = 0;
  double distance = 0.0;
  Vec2 a{0.0, 0.0};  ///< on edge `first`
  Vec2 b{0.0, 0.0};  ///< on edge `second`
};

/// The narrowest neck of a simple closed polygon narrower than `width`: a
/// vertex and a point of an edge not incident to it closer than `width`
/// while the polygon's shorter way between them is longer than
/// `detour` x `width` (so a fine run of points, whose neighbours are close
/// along the polygon too, is no neck; nor is a bend whose sides come within
/// `width` of each other over a way shorter than that). nullopt when there is
/// none. O(n log n + k) with box intersection, k the pairs of edges whose
/// boxes come within `width`.
std::optional<PolygonNeck> find_neck(const std::vector<Vec2>& points, double width, double detour = 2.0);

/// The side of the line through `a` and `b` that `p` lies on, exactly:
/// 1 left, -1 right, 0 on it (CGAL's exact orientation predicate).
int side_of_line(const Vec2& a, const Vec2& b, const Vec2& p);

/// Whether `p` lies strictly inside, on the boundary of (0) or outside a
/// simple closed polygon: 1, 0, -1, decided exactly.
int point_in_polygon(const std::vector<Vec2>& polygon, const Vec2& p);

/// Twice the signed area of a closed polygon (positive: counter-clockwise).
double signed_area2(const std::vector<Vec2>& points);

}  // namespace fabmesh
