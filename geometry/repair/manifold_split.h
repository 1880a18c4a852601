#pragma once
// Non-manifold edges and vertices split: faces around an edge of more than
// two are paired around it (each pair encloses solid between its faces), and
// a vertex whose faces form several fans becomes one vertex per fan. Copies
// of one point are moved apart, each into its own fan, so that the solids
// which touched there (two cubes sharing an edge) no longer touch.

#include "geometry/repair/repair_log.h"
#include "geometry/repair/tracked_soup.h"

namespace fabmesh {

/// Splits the non-manifold edges and vertices of `mesh` (its faces free of
/// degenerate ones). The faces of an edge are sorted by angle around it and
/// each face paired with its neighbour on the side its back faces (where a
/// consistently oriented solid is); an edge whose faces do not alternate in
/// direction is paired in angular order. Then each vertex gets one copy per
/// fan of faces connected across paired edges. Each copy (the original
/// included) moves by `separation` (model units, >= 0) toward the centroid
/// of its fan's far corners. Logs RepairStep::NonManifoldEdge per edge and
/// RepairStep::NonManifoldVertex per vertex split.
void split_non_manifold(TrackedSoup& mesh, double separation, RepairLog& log);

}  // namespace fabmesh
