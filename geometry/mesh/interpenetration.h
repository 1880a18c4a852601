#pragma once
// Whether solids placed together (the objects of one file: mould parts, a
// slicer's plate) overlap, as opposed to touch.

#include <cstddef>
#include <utility>
#include <vector>

#include "geometry/core/soup.h"

namespace fabmesh {

/// What interpenetrating_pairs found.
struct Interpenetration {
  std::vector<std::pair<std::size_t, std::size_t>> pairs;  ///< (i, j), i < j, in increasing order
  /// False when the work bound stopped the search: the pairs it had not
  /// reached were not tested (none of them is in `pairs`).
  bool complete = true;
};

/// Work units interpenetrating_pairs may spend on `triangles` triangles in
/// all: 16 per triangle and 100000 more. A candidate pair (bounding boxes
/// compared) costs 1, a pair tested the triangles of both.
std::size_t interpenetration_work_bound(std::size_t triangles);

/// The pairs (i, j), i < j, of `solids` whose interiors surely overlap.
/// Every non-null solid must be valid (closed, manifold, consistently and
/// outward oriented, without self-intersection: it has an inside); null
/// entries are not judged. Sound and conservative, with exact predicates:
/// only pairs whose bounding boxes overlap with positive volume are tested,
/// and a pair is reported when
/// 1. a vertex (of a triangle) of one lies strictly inside the other
///    (ray parity), or
/// 2. an edge of one crosses a face of the other transversally, through the
///    face's interior, its ends strictly on either side of the face's
///    plane, or
/// 3. a face of one and a face of the other lie in one plane, facing the
///    same way, and overlap with positive area (the solids are on the same
///    side of it: two copies of one body).
/// Each is a point where both insides meet. Touching is never reported:
/// faces meeting back to back (mould halves on their split plane), at an
/// edge or a vertex. A pair whose surfaces meet only where each one's
/// vertices and edges lie on the other's surface, without coincident faces
/// facing alike (a tetrahedron inscribed in a cube), is not reported.
/// Stops when the next pair would exceed `max_work` (see
/// interpenetration_work_bound; 0: that bound for all the solids' triangles),
/// so that many bodies piled together cost a bounded time.
///
/// `contact` (model units, default 0: exact) is how far surfaces may cross and
/// still count as touching: the precision of the coordinates as stored. Two
/// mould parts touching on a split plane at 120 degrees, written as float32
/// (3MF, STL), cross by a fraction of a float's unit in the last place (the
/// plane holds no float points); their exact solids do not overlap. With it,
/// criterion 1 needs the vertex farther than `contact` from the other's
/// surface, criterion 2 both ends of the edge farther than `contact` from the
/// face's plane and the crossing point farther than `contact` from the
/// face's edges (a cap's edge passing over a socket's rim, rounded, crosses
/// the socket's wall next to the rim; distances computed in floating point;
/// the predicates stay exact).
Interpenetration interpenetrating_pairs(const std::vector<const TriangleSoup*>& solids,
                                        std::size_t max_work = 0, double contact = 0.0);

/// The contact distance of solids whose coordinates are all float32 values
/// (as 3MF, STL, GLB and float PLY store them): 4 float32 units in the last
/// place at their largest coordinate (each vertex was moved by at most
/// sqrt(3) / 2 of one by rounding, two surfaces by twice that); 0 when some
/// coordinate is not a float32 value (the file's numbers are taken as exact).
double float32_contact(const std::vector<const TriangleSoup*>& solids);

}  // namespace fabmesh
