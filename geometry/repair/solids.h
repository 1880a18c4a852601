#pragma once
// A repaired mesh as solids: each outer shell with the cavities inside it,
// what a slicer takes as one object.

#include <vector>

#include "geometry/core/soup.h"
#include "geometry/validation/validate.h"

namespace fabmesh {

/// The solids of `soup` validated as `report` (its component shells with
/// their nesting determined): each component at even depth with the
/// components directly inside it (its cavities), in component order; each
/// solid's vertices in order of first use. Without a determined nesting,
/// the whole soup as one solid.
std::vector<TriangleSoup> solids_of(const TriangleSoup& soup, const ValidationReport& report);

}  // namespace fabmesh
