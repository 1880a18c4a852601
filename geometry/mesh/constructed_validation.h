#pragma once
// Validation of meshes whose embedding is proven by their construction.

#include <string>

#include "geometry/mesh/validate.h"

namespace fabmesh {

/// Validates `mesh` fully (closedness, manifoldness, orientation, degenerate
/// and duplicate faces, volume, genus) except for the 3D self-intersection
/// test, which `embedding_proof` replaces: a builder that proved its output
/// embedded (e.g. a simple section revolved) states why. The report then
/// counts the self-intersection stage as checked, by construction.
ValidationReport validate_constructed(const Mesh& mesh, const std::string& embedding_proof);

/// The same when the caller already has `soup` == to_soup(mesh).
ValidationReport validate_constructed(const Mesh& mesh, const TriangleSoup& soup,
                                      const std::string& embedding_proof);

}  // namespace fabmesh
