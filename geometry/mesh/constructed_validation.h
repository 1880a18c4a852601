#pragma once
// Validation of meshes whose embedding is proven by their construction.

#include "geometry/mesh/embedding_proof.h"
#include "geometry/mesh/topology_proof.h"
#include "geometry/mesh/validate.h"

namespace fabmesh {

/// Validates `mesh` fully (closedness, manifoldness, orientation, degenerate
/// and duplicate faces, volume, genus) except for the 3D self-intersection
/// test, which `proof` replaces: the report says
/// IntersectionCheck::ProvenByConstruction and carries the statement.
/// `soup` must be to_soup(mesh). A mesh with a non-finite vertex keeps
/// IntersectionCheck::NotRun (a proof about the exact construction says
/// nothing about NaNs), so it is never called valid.
ValidationReport validate_constructed(const Mesh& mesh, const TriangleSoup& soup,
                                      const EmbeddingProof& proof);

/// Validates a soup whose connectivity and embedding its construction both
/// prove (a revolution): the connectivity analysis is replaced by `topology`
/// and the 3D test by `embedding`; finiteness, exact degeneracy, area and
/// signed volume (hence outward orientation) are still checked on `soup`.
/// The report carries both statements.
ValidationReport validate_constructed(const TriangleSoup& soup, const TopologyProof& topology,
                                      const EmbeddingProof& embedding);

}  // namespace fabmesh
