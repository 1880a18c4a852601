#pragma once
// Triangulation of a region with holes: a constrained Delaunay triangulation
// of its loops (CGAL), optionally refined to a maximum edge length.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/core/limits.h"
#include "geometry/core/types.h"
#include "geometry/section/region.h"

namespace fabmesh {

struct TriangulateOptions {
  /// Longest edge allowed, model units; 0 keeps the loops' points only (no
  /// refinement). When > 0 the triangulation is refined (Delaunay refinement,
  /// minimum angle about 20.7 degrees), which also splits boundary edges.
  double max_edge = 0.0;
  std::size_t max_triangles = kDefaultMaxTriangles;  ///< budget; more is a BudgetError
};

/// Triangles covering a region exactly (the union of the triangles is the
/// region's polygon with holes), counter-clockwise, sharing vertices.
struct PlanarTriangulation {
  std::vector<Vec2> vertices;                           ///< model units
  std::vector<std::array<std::uint32_t, 3>> triangles;  ///< counter-clockwise
  /// The region's boundary as vertex cycles with the region on their left
  /// (outer loop counter-clockwise, holes clockwise), following every
  /// boundary edge of `triangles`: refinement may have split the input loops.
  std::vector<std::vector<std::uint32_t>> boundary;
  std::size_t steiner_points = 0;  ///< vertices added by refinement
};

/// Triangulates `region` (Region2 guarantees simple disjoint loops, holes
/// inside). In-domain faces are found by nesting depth from the unbounded
/// face across constrained edges (odd depth: inside).
/// \throw RangeError (max_edge < 0 or not finite), BudgetError (max_edge too
///        small for max_triangles).
PlanarTriangulation triangulate(const Region2& region, const TriangulateOptions& options = {});

}  // namespace fabmesh
