#pragma once
// Edges far shorter than anything a printer or a file's float32 coordinates
// keep: exact booleans leave them where a cut passes almost through a vertex
// of the solid it cuts (two of its edges crossed a hair apart). Rounded to
// float32, their ends become one point and their faces fold. Collapsing them
// first moves the surface no further than the edge's length.

#include <cstddef>

#include "geometry/core/soup.h"

namespace fabmesh {

/// Collapses every edge of `soup` shorter than `length` whose collapse keeps
/// the surface a closed 2-manifold: the edge's two faces go and one end takes
/// the other's place. An edge is kept when its ends share a neighbour other
/// than the two opposite its faces (the collapse would pinch the surface),
/// or when every choice of the end that stays turns a remaining face over or
/// makes it degenerate. The end that stays is the one that lies least off
/// the planes of the other's faces; collapses where it lies on them all (the
/// surface keeps its shape) come first, shortest first. No vertex moves:
/// each that goes, with each whose place it had taken, is within `length`
/// of the vertex that takes its place. Vertices no face uses any more are
/// dropped and the others keep their order. Returns the number of edges
/// collapsed. A heuristic in double precision: validate the result (it can
/// touch faces that were near).
/// \pre `soup` is closed and manifold (each edge in exactly two faces) with
/// indices in range.
std::size_t collapse_short_edges(TriangleSoup& soup, double length);

}  // namespace fabmesh
