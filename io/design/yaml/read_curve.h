#pragma once
// Reads one curve (docs/design-files.md "Curves") from a YAML node.

#include <yaml-cpp/yaml.h>

#include <string>

#include "geometry/curves/curve_spec.h"
#include "io/design/yaml/fields.h"

namespace fabmesh {

/// Reads the curve at `node` (field name `field` for messages): family,
/// points or segments, joins, fair. Checks every shape parameter's range and
/// every count of points against the family, with the location of the value.
/// \throw FileError
CurveSpec read_curve(const yaml::Fields& fields, const YAML::Node& node, const std::string& field);

}  // namespace fabmesh
