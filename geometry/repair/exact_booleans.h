#pragma once
// The repair's exact constructions (CGAL Epeck, in exact_booleans.cpp): the
// union of overlapping closed shells by corefinement, and a shell's own
// intersections removed by autorefinement. Points are computed exactly and
// rounded to double once, at the end.

#include <optional>
#include <string>
#include <vector>

#include "geometry/core/soup.h"

namespace fabmesh {

/// The union of `shells`, each a closed, oriented-outward, manifold surface
/// free of self-intersections (one solid each): CGAL's
/// corefine_and_compute_union over exact constructions, shell after shell.
/// Every face of the result lies in a face of a shell, and every point of a
/// shell is on the result or inside it (checked: every vertex of the
/// shells is tested exactly). Empty when CGAL cannot (a shell that does not
/// bound a volume, or an output that would be non-manifold); `why` then
/// says so.
std::optional<TriangleSoup> unite_shells(const std::vector<TriangleSoup>& shells, std::string* why = nullptr);

/// `shell` (closed, manifold, consistently oriented) with its own
/// intersections removed: CGAL's experimental
/// autorefine_and_remove_self_intersections over exact constructions. Empty
/// when CGAL reports that not all could be fixed, throws, or returns a
/// surface that is open, still self-intersecting, or leaves a vertex of
/// `shell` outside it (it removed a part instead of an inner patch; each
/// tested exactly).
std::optional<TriangleSoup> resolve_self_intersections(const TriangleSoup& shell, std::string* why = nullptr);

}  // namespace fabmesh
