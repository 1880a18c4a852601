#pragma once
// Whether solids placed together (the objects of one file: mould parts, a
// slicer's plate) overlap, as opposed to touch.

#include <cstddef>
#include <utility>
#include <vector>

#include "geometry/mesh/soup.h"

namespace fabmesh {

/// The pairs (i, j), i < j, of `solids` whose interiors surely overlap, in
/// increasing order. Every non-null solid must be valid (closed, manifold,
/// consistently and outward oriented, without self-intersection: it has an
/// inside); null entries are not judged. Sound and conservative, with exact
/// predicates: only pairs whose bounding boxes overlap with positive volume
/// are tested, and a pair is reported when
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
/// edge or a vertex. A pair whose surfaces meet only where one's vertices,
/// edges and faces lie on the other's surface without any of the three
/// (a tetrahedron inscribed in a cube, its corners at the cube's corners)
/// is not reported.
std::vector<std::pair<std::size_t, std::size_t>> interpenetrating_pairs(
    const std::vector<const TriangleSoup*>& solids);

}  // namespace fabmesh
