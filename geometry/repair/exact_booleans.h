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

/// Pieces carved from one solid: `block` less `part` (each closed, outward,
/// manifold and free of self-intersections), cut by `regions` in order
/// (each the union of its solids): piece i + 1 is what lies in region i and
/// in none before it,
/// united with the solids `added[i]`; the solids `holes[i]` are then taken
/// from what is left (from the pieces after it and from piece 0, what lies
/// in no region). All by CGAL's corefinement over exact
/// constructions, each piece rounded to double once, at the end. Empty when
/// CGAL cannot, or a piece is empty or not closed; `why` then says so.
std::optional<std::vector<TriangleSoup>> carve_pieces(const TriangleSoup& block, const TriangleSoup& part,
                                                      const std::vector<std::vector<TriangleSoup>>& regions,
                                                      const std::vector<std::vector<TriangleSoup>>& added,
                                                      const std::vector<std::vector<TriangleSoup>>& holes,
                                                      std::string* why = nullptr);

/// The cells of one solid `solid` (closed, outward, manifold and free of
/// self-intersections): cell i is what of it lies in `cells[i]` (a closed
/// solid), united with the solids `added[i]` and less the solids
/// `removed[i]`. All by CGAL's corefinement over exact constructions, each
/// cell rounded to double once, at the end; a cell the solid does not reach
/// is empty. None when CGAL cannot or a cell is not closed; `why` then says so.
std::optional<std::vector<TriangleSoup>> cut_cells(const TriangleSoup& solid,
                                                   const std::vector<TriangleSoup>& cells,
                                                   const std::vector<std::vector<TriangleSoup>>& added,
                                                   const std::vector<std::vector<TriangleSoup>>& removed,
                                                   std::string* why = nullptr);

/// The exact sign (-1, 0, +1) of ((b - a) x (c - a)) . d: which way the
/// triangle (a, b, c) faces along d.
int exact_facing(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// The exact sign of (p - o) . d: the side of the plane through o across d
/// that p lies on.
int exact_side(const Vec3& p, const Vec3& o, const Vec3& d);

}  // namespace fabmesh
