#pragma once
// Welding: merge coincident vertices of a triangle soup (STL files repeat
// every vertex once per triangle).

#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/core/soup.h"

namespace fabmesh {

/// How close two vertices must be to merge.
struct WeldOptions {
  /// 0 (default): only exactly equal coordinates merge (+0.0 equals -0.0).
  /// > 0: vertices within this Euclidean distance (model units) merge, and
  /// merging is transitive (chains of close vertices become one vertex).
  double tolerance = 0.0;
};

/// A welded soup and what welding did.
struct WeldResult {
  TriangleSoup soup;                ///< same triangles, indices into the merged vertices
  std::size_t merged_vertices = 0;  ///< input vertex count minus output vertex count
  /// For each output vertex, the input vertex whose position it keeps (the
  /// lowest index of those merged into it): how a report names a welded
  /// vertex by the file's numbering.
  std::vector<std::uint32_t> representatives;
};

/// Merges coincident vertices of `soup`. Each merged vertex keeps the
/// position of its lowest-index member; vertex order follows first
/// occurrence. Triangles are kept as they are (a triangle whose corners merge
/// becomes degenerate, for validation to report). Non-finite vertices never
/// merge. Time: linear for the exact weld (a hash partition, parallel); with
/// a tolerance, O(n log n) on a grid whose cells are merged without
/// pairwise tests (the bound and its one super-linear case are in
/// weld_grid.cpp). \throw RangeError when tolerance is negative, not finite,
/// or too small for the coordinates' magnitude; InputError when an index is
/// out of range.
WeldResult weld(const TriangleSoup& soup, const WeldOptions& options = {});

}  // namespace fabmesh
