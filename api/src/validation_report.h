#pragma once
// The pipeline's validation report as the library's.

#include <nlohmann/json.hpp>

#include "fabmesh/mesh.h"
#include "geometry/validation/validate.h"
#include "pipeline/check_mesh.h"

namespace fabmesh::api::detail {

/// The public kind of a defect, and back.
DefectKind public_kind(fabmesh::Defect kind);
fabmesh::Defect internal_kind(DefectKind kind);

/// The public verdict of `report`, with `json` (the command line's facts) as its text.
ValidationReport public_report(const fabmesh::ValidationReport& report, const nlohmann::ordered_json& json);

/// The public verdict of a checked file: its one object's, or the sums over
/// its objects with the assembly's verdict, or why it could not be read.
ValidationReport file_report(const fabmesh::FileCheck& check, const nlohmann::ordered_json& json);

}  // namespace fabmesh::api::detail
