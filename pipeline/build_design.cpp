#include "pipeline/build_design.h"

#include <algorithm>

#include "geometry/mesh/constructed_validation.h"

namespace fabmesh {

bool fit_for(const ValidationReport& report, MeshPurpose purpose) {
  if (purpose == MeshPurpose::Drawing || report.valid()) return true;
  return purpose == MeshPurpose::Viewing && report.self_intersection != IntersectionCheck::NotRun &&
         std::all_of(report.defects.begin(), report.defects.end(),
                     [](const DefectReport& d) { return d.kind == Defect::BoundaryEdge; });
}

BuiltMesh build_design(const Design& design, const BuildContext& context) {
  return std::visit([&](const auto& body) { return build(body, context); }, design.body);
}

BuiltMesh validated(const Mesh& mesh, const std::optional<EmbeddingProof>& proof,
                    const BuildContext& context) {
  BuiltMesh out;
  out.soup = to_soup(mesh);
  out.validation = proof ? validate_constructed(mesh, out.soup, *proof) : validate(mesh, out.soup);
  context.watch.lap("validate");
  return out;
}

}  // namespace fabmesh
