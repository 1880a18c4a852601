#pragma once
// Reads the body of a `kind: surface` design (docs/design-files.md "Surfaces").

#include <yaml-cpp/yaml.h>

#include "io/design/design.h"
#include "io/design/yaml/fields.h"

namespace fabmesh {

/// Reads `patches` (each with name, u/v parameters {alpha, lambda, mu} and
/// either 4 x 4 `points` or a `join: {to, side, continuity, gamma | k, m}`
/// with the free rows), `thickness` (optional, > 0) and `max_triangles`
/// (optional) from the design's root map, and builds the patch network once
/// so that joins that cannot be made are reported at the patch.
/// \throw FileError naming file, line, column and field
SurfaceDesign read_surface(const yaml::Fields& fields, const YAML::Node& root);

}  // namespace fabmesh
