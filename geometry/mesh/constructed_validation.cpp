#include "geometry/mesh/constructed_validation.h"

namespace fabmesh {

ValidationReport validate_constructed(const Mesh& mesh, const TriangleSoup& soup,
                                      const EmbeddingProof& proof) {
  ValidateOptions options;
  options.check_self_intersections = false;
  ValidationReport report = validate(mesh, soup, options);
  if (report.non_finite_vertices == 0) {
    report.self_intersection = IntersectionCheck::ProvenByConstruction;
    report.embedding_proof = proof.statement;
    report.self_intersecting = false;
  }
  return report;
}

}  // namespace fabmesh
