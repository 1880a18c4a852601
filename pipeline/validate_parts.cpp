#include "pipeline/validate_parts.h"

#include <fmt/format.h>

#include "geometry/core/errors.h"

namespace fabmesh {

ValidationReport validate_built(const TriangleSoup& soup, const ValidationOptions& checks) {
  ValidationOptions options = checks;
  options.examples_in_face_order = true;  // as a built mesh's report has always listed them
  return validate(soup, options);
}

void validate_part(Part& part) {
  part.validation = validate_built(part.mesh, part.proofs);
  part.validated = true;
}

void validate_parts(Result& result, StageTimer& watch) {
  bool any = false;
  for (Part& part : result.parts) {
    if (part.validated) continue;
    validate_part(part);
    any = true;
  }
  if (any) watch.lap("validate");
}

void require_fit(const ValidationReport& report, MeshPurpose purpose, const std::string& what) {
  if (!fit_for(report, purpose)) require_valid(report, what);
}

void require_fit(const Result& result, Purpose asked) {
  if (const Part* part = product(result)) {
    const std::string what = fmt::format("{} '{}'", result.kind, result.name);
    require_fit(part->validation, result.purpose, what);
    if (result.purpose == MeshPurpose::Viewing && asked != Purpose::View) {
      throw ValidationFailed(fmt::format(
          "{}: the mesh is open ({} boundary edges): not fit for fabrication, so nothing is written; give "
          "the surface a `thickness` for a solid shell, or set `purpose: view` to write it for viewing",
          what, part->validation.boundary_edges));
    }
  }
  require_parts_fit(result);
}

void require_parts_fit(const Result& result) {
  for (const Part& part : result.parts) {
    if (part.role != PartRole::Product)
      require_fit(part.validation, MeshPurpose::Fabrication, "mould part '" + part.name + "'");
  }
}

}  // namespace fabmesh
