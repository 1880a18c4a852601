#pragma once
// The reports of `fabmesh repair`: its `--json` item per file and its human
// summary (docs/reports.md, docs/repair.md).

#include <nlohmann/json.hpp>
#include <string>

#include "geometry/repair/repair.h"
#include "pipeline/repair_mesh.h"

namespace fabmesh {

/// The facts of one repair (an object of a file, or a soup): before and
/// after, the steps with their places, components dropped, the distance and
/// what is left unmended.
nlohmann::ordered_json repair_result_json(const RepairResult& result);

/// The `repair --json` item of a file: file, format, units, output, status,
/// exit code, message, then the repair's facts (per object when it has several).
nlohmann::ordered_json repair_json(const FileRepair& repair);

/// The human summary of a file's repair: verdict, steps with counts and the
/// first places (more with verbosity 2), components, volume, area, distance.
std::string repair_text(const FileRepair& repair, int verbosity);

}  // namespace fabmesh
