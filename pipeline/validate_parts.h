#pragma once
// Validate before write: the one place where the pipeline validates the
// meshes it writes (every part of a job's Result: the design's mesh, every
// mould part), each with the proofs its builder gives, before anything is
// encoded, and where it decides whether they are fit to be written.

#include <string>

#include "geometry/core/soup.h"
#include "geometry/core/stage_timer.h"
#include "geometry/validation/validate.h"
#include "io/design/design.h"
#include "pipeline/result.h"

namespace fabmesh {

/// Validates `soup`, a mesh a builder made, with the builder's proofs in
/// `checks` (validate(soup, checks)), its example locations in the order of
/// its faces. Every mesh the pipeline writes is validated here.
/// \throw InputError when an index is out of range
ValidationReport validate_built(const TriangleSoup& soup, const ValidationOptions& checks);

/// Validates `part` (its mesh with its proofs) into its `validation`.
void validate_part(Part& part);

/// Validates every part of `result` not validated yet, timed as "validate".
void validate_parts(Result& result, StageTimer& watch);

/// Throws ValidationFailed unless every part of `result` is fit for what it
/// is for (require_valid's message: "vessel 'cup'" or "mould part 'base'",
/// then every defect), and unless an open mesh, fit for viewing only, is
/// what the design asks for (`purpose: view`).
void require_fit(const Result& result, Purpose asked);

/// Throws ValidationFailed unless every part of `result` but its product
/// (the mould's parts) is fit for fabrication.
void require_parts_fit(const Result& result);

/// Throws ValidationFailed unless `report` is fit_for `purpose`; the message
/// starts with `what` and lists every defect.
void require_fit(const ValidationReport& report, MeshPurpose purpose, const std::string& what);

}  // namespace fabmesh
