#include "pipeline/validate_built.h"

namespace fabmesh {

ValidationReport validate_built(const TriangleSoup& soup, const ValidationOptions& checks) {
  ValidationOptions options = checks;
  options.examples_in_face_order = true;  // as a built mesh's report has always listed them
  return validate(soup, options);
}

void validate_built(BuiltMesh& out, const BuildContext& context) {
  out.validation = validate_built(out.soup, out.checks);
  context.watch.lap("validate");
}

void require_fit(const ValidationReport& report, MeshPurpose purpose, const std::string& what) {
  if (!fit_for(report, purpose)) require_valid(report, what);
}

}  // namespace fabmesh
