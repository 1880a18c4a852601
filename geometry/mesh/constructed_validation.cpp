#include "geometry/mesh/constructed_validation.h"

#include "geometry/core/errors.h"

namespace fabmesh {

ValidationReport validate_constructed(const Mesh& mesh, const std::string& embedding_proof) {
  return validate_constructed(mesh, to_soup(mesh), embedding_proof);
}

ValidationReport validate_constructed(const Mesh& mesh, const TriangleSoup& soup,
                                      const std::string& embedding_proof) {
  if (embedding_proof.empty())
    throw std::logic_error("validate_constructed needs the builder's embedding proof");
  ValidateOptions options;
  options.check_self_intersections = false;
  ValidationReport report = validate(mesh, soup, options);
  if (report.non_finite_vertices == 0) {
    report.self_intersection_checked = true;
    report.self_intersecting = false;
    report.timings_ms.emplace_back("self_intersection_by_construction", 0.0);
  }
  return report;
}

}  // namespace fabmesh
