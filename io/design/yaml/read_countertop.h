#pragma once
// Reads the body of a `kind: countertop` design (docs/design-files.md "Countertops").

#include <yaml-cpp/yaml.h>

#include "io/design/design.h"
#include "io/design/yaml/fields.h"

namespace fabmesh {

/// Reads outline (a closed curve), holes (ellipse, rounded_rect or a closed
/// outline each), thickness (> 0), max_edge (> 0, optional) and
/// max_triangles (optional) from the design's root map (its keys already
/// checked against key_group("countertop")). Ellipse and
/// rounded_rect holes become closed curves of exact segments (one 0..360
/// ellipse arc; 4 lines and 4 quarter circles, declared G1).
/// \throw FileError naming file, line, column and field
/// `cnc:` (CncOptions; defaults in mm, converted to the design's units;
/// depth defaults to the thickness) as well; `common` gives the units and tolerance.
CountertopDesign read_countertop(const yaml::Fields& fields, const YAML::Node& root,
                                 const DesignCommon& common);

}  // namespace fabmesh
