#include "geometry/mesh/constructed_validation.h"

namespace fabmesh {

namespace {

ValidationReport with_embedding(ValidationReport report, const EmbeddingProof& proof) {
  if (report.non_finite_vertices == 0) {
    report.self_intersection = IntersectionCheck::ProvenByConstruction;
    report.embedding_proof = proof.statement;
    report.embedding_margin = proof.margin;
    report.self_intersecting = false;
  }
  return report;
}

ValidateOptions without_3d_test() {
  ValidateOptions options;
  options.check_self_intersections = false;
  return options;
}

}  // namespace

ValidationReport validate_constructed(const Mesh& mesh, const TriangleSoup& soup,
                                      const EmbeddingProof& proof) {
  return with_embedding(validate(mesh, soup, without_3d_test()), proof);
}

ValidationReport validate_constructed(const TriangleSoup& soup, const TopologyProof& topology,
                                      const EmbeddingProof& embedding) {
  Topology known;
  known.components = topology.components;
  known.euler_characteristics = topology.euler_characteristics;
  ValidationReport report = with_embedding(validate_geometry(soup, known, without_3d_test()), embedding);
  report.topology_proof = topology.statement;
  return report;
}

}  // namespace fabmesh
