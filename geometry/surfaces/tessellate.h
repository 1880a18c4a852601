#pragma once
// Tessellation of a patch network into one conforming triangle mesh.

#include <cstddef>
#include <vector>

#include "geometry/core/limits.h"
#include "geometry/core/types.h"
#include "geometry/surfaces/patch_network.h"

namespace fabmesh {

struct TessellateOptions {
  /// Largest distance between the mesh and the exact surface, model units (> 0).
  double tolerance = 0.01;
  /// When not 0, the offset sheet S + offset n (thicken) is kept within
  /// `tolerance` of the exact offset surface as well, model units.
  double offset = 0.0;
  int initial_segments = 4;  ///< segments per patch direction before refinement (>= 1)
  std::size_t max_triangles = kDefaultMaxTriangles;  ///< budget; more is a BudgetError
};

/// A network tessellated: one mesh, vertices shared by index across borders.
struct SurfaceTessellation {
  Mesh mesh;
  /// Unit normal of the exact surface at each mesh vertex (mean of the
  /// patches meeting there), indexed like the mesh's vertices.
  std::vector<Vec3> normals;
  /// The achieved bound on the distance to the exact surface: per cell a
  /// second-order Taylor bound of the linear interpolation in (s, t) with the
  /// second derivatives sampled on the cell (3 x 3, plus a 25% margin); with
  /// an offset, also the sampled offset deviation with a 50% margin. Model units.
  double max_deviation = 0.0;
  /// Grid breakpoints in s and t of each patch (shared borders share them).
  std::vector<std::vector<double>> s_breaks, t_breaks;
};

/// Tessellates `network` adaptively: the grid lines of each parameter
/// direction are refined (in classes of directions tied together by shared
/// borders, so both sides of a border use the same samples and the same
/// vertices) until every cell is within `tolerance`. Each grid cell becomes two
/// triangles counter-clockwise about S_s x S_t; collapsed sides become one
/// vertex. The only boundary edges are on the network's outer border.
/// \throw RangeError (tolerance), BudgetError (max_triangles), GeometryError
///        (a network whose patches cannot form a manifold mesh)
SurfaceTessellation tessellate(const PatchNetwork& network, const TessellateOptions& options);

}  // namespace fabmesh
