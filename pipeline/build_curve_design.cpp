// kind: curve: a curve alone has no mesh.

#include "geometry/core/errors.h"
#include "pipeline/build_design.h"

namespace fabmesh {

BuiltMesh build(const CurveDesign& /*design*/, const BuildContext& /*context*/) {
  throw InputError("a curve design has no mesh to run; use `fabmesh sample` or `fabmesh optimize`");
}

}  // namespace fabmesh
