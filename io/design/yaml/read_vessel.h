#pragma once
// Reads the body of a `kind: vessel` design (docs/design-files.md "Vessels").

#include <yaml-cpp/yaml.h>

#include "io/design/design.h"
#include "io/design/yaml/fields.h"

namespace fabmesh {

/// Reads profile (a curve in the (radius, height) plane), body {mode, wall,
/// base} and max_triangles from the design's root map (its keys already
/// checked against key_group("vessel")). \throw FileError naming file, line, column and field
/// `shrinkage` (in [0, 1)) and `mould:` (MouldOptions; defaults in mm,
/// converted to the design's units) as well; `common` gives the units and
/// the tolerance. \throw FileError
VesselDesign read_vessel(const yaml::Fields& fields, const YAML::Node& root, const DesignCommon& common);

}  // namespace fabmesh
