#include "geometry/surfaces/surface_mesh.h"

#include <fmt/format.h>

#include "geometry/core/errors.h"
#include "geometry/mesh/tessellate.h"
#include "geometry/mesh/thicken.h"

namespace fabmesh {

SurfaceMesh build_surface_mesh(const PatchNetwork& network, const SurfaceMeshOptions& options) {
  require_positive("tolerance", options.tolerance);
  if (options.thickness != 0.0) require_positive("thickness", options.thickness);
  TessellateOptions to;
  to.tolerance = options.tolerance;
  to.offset = options.thickness;
  // Two sheets and the rim: the sheet may use a little under half the budget.
  to.max_triangles = options.thickness > 0.0 ? options.max_triangles / 2 : options.max_triangles;
  SurfaceMesh out;
  tessellate(network, to, out.sheet);
  const Mesh& sheet = out.sheet.mesh;
  for (const auto h : sheet.halfedges()) out.rim_edges += sheet.is_boundary(h) ? 1 : 0;
  out.max_deviation = out.sheet.max_deviation;
  if (options.thickness > 0.0) {
    const std::size_t total = 2 * sheet.n_faces() + 2 * out.rim_edges;
    if (total > options.max_triangles) {
      throw BudgetError(static_cast<double>(total), static_cast<double>(options.max_triangles),
                        fmt::format("tolerance {} needs {} triangles, over the budget of {}",
                                    options.tolerance, total, options.max_triangles));
    }
    ThickenOptions th;
    th.thickness = options.thickness;
    thicken(sheet, out.sheet.normals, th, out.solid);
    out.thickened = true;
  }
  return out;
}

}  // namespace fabmesh
