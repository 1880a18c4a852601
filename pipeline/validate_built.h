#pragma once
// Validate before write: the one place where the pipeline validates the
// meshes it writes (every design kind's mesh and every mould part), with the
// proofs their builders give, before anything is encoded, and where it
// decides whether a mesh is fit to be written.

#include <string>

#include "geometry/mesh/soup.h"
#include "geometry/validation/validate.h"
#include "pipeline/built_mesh.h"

namespace fabmesh {

/// Validates `soup`, a mesh a builder made, with the builder's proofs in
/// `checks` (validate(soup, checks)), its example locations in the order of
/// its faces. Every mesh the pipeline writes is validated here.
/// \throw InputError when an index is out of range
ValidationReport validate_built(const TriangleSoup& soup, const ValidationOptions& checks);

/// Validates the mesh of `out` (out.soup with out.checks) into
/// out.validation and times the stage as "validate". A mesh builder calls it
/// as soon as its mesh is made, before its other products (template, mould,
/// toolpath); the job then requires the report fit for out.purpose.
void validate_built(BuiltMesh& out, const BuildContext& context);

/// Throws ValidationFailed unless `report` is fit_for `purpose`; the message
/// is require_valid's: it starts with `what` (e.g. "vessel 'cup'", "mould
/// part 'base'") and lists every defect.
void require_fit(const ValidationReport& report, MeshPurpose purpose, const std::string& what);

}  // namespace fabmesh
