#pragma once
// A patch network made into a mesh: tessellated, and thickened into a solid
// shell when a thickness is given.

#include <cstddef>

#include "geometry/core/types.h"
#include "geometry/mesh/tessellate.h"
#include "geometry/surfaces/patch_network.h"

namespace fabmesh {

struct SurfaceMeshOptions {
  double tolerance = 0.01;               ///< model units: mesh to exact surface (both sheets)
  double thickness = 0.0;                ///< > 0: a solid shell along the normals; 0: the open surface
  std::size_t max_triangles = 20000000;  ///< budget for the final mesh; more is a BudgetError
};

/// Returned by value (NRVO: built in place); OpenMesh meshes cannot be moved.
struct SurfaceMesh {
  SurfaceTessellation sheet;   ///< the tessellated surface (open)
  Mesh solid;                  ///< the thickened shell (empty without thickness)
  std::size_t rim_edges = 0;   ///< boundary edges of the sheet
  double max_deviation = 0.0;  ///< the tessellation's achieved bound (tessellate.h)
  bool thickened = false;
  /// The result: the solid when thickened, else the open sheet.
  const Mesh& mesh() const { return thickened ? solid : sheet.mesh; }
};

/// Tessellates `network` within `tolerance` (with thickness: the offset
/// sheet as well) and, with thickness > 0, thickens it along the normals
/// (S_s x S_t). The shell is not validated here: its self-intersection
/// (too thick for the curvature) must be tested with validate().
/// \throw RangeError, BudgetError, GeometryError
SurfaceMesh build_surface_mesh(const PatchNetwork& network, const SurfaceMeshOptions& options);

}  // namespace fabmesh
