#pragma once
// Faces lying in one axis plane (x, y or z = c exactly: the top and bottom
// of a slab), proven pairwise apart as a whole rather than pair by pair.
// A countertop triangulated from a finely sampled outline has long slivers
// across its top at every angle; their boxes overlap quadratically many
// others', so the box search cannot be near-linear there. For such a plane
// group, a degree argument settles all its pairs at once: if the faces, as
// a surface glued along their shared vertex indices, map to the plane as an
// orientation-preserving local homeomorphism, then each point off the image
// of their boundary is covered sum-of-winding-numbers times; if that sum is
// 0 or 1 on both sides of every boundary loop (and the loops are simple and
// disjoint), no point is covered twice: the map is injective, so two faces
// meet exactly in the vertices and edges they share (faces_intersect_exact
// is false for every pair of the group).
//
// Internal to geometry/validation (validate.h is the public entry).

#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/core/soup.h"

namespace fabmesh::detail {

/// The patch of a face in no certified plane group.
constexpr std::uint32_t kNoPatch = 0xffffffffu;

/// Plane groups proven free of intersections among their own faces.
struct PlanarPatches {
  std::vector<std::uint32_t> patch;  ///< per face: its certified group, or kNoPatch
  std::vector<int> axis;             ///< per group: the axis (0, 1, 2) normal to its plane
  std::vector<double> level;         ///< per group: the plane's coordinate on that axis
};

/// Groups the faces f with skip[f] == 0 whose three corners have one
/// coordinate exactly equal, by that plane, and certifies the groups of at
/// least `min_faces` faces where every test holds, all with exact
/// predicates: every face is non-degenerate with one orientation in the
/// plane; every edge has one or two faces of the group, two running in
/// opposite directions; around a vertex without a border edge the far
/// edges wind once; a vertex on the border has one border edge out and one
/// in, and no face but the first covers the outgoing edge's direction; no
/// two border edges meet but consecutive ones at their shared vertex; and
/// the winding numbers of the border loops sum to 0 just outside each loop.
/// A group failing any test is simply not certified (its pairs are then
/// tested one by one).
/// \pre indices in range, coordinates finite, skip empty or one flag per face.
PlanarPatches certify_planar_patches(const TriangleSoup& soup, const std::vector<char>& skip,
                                     std::size_t min_faces = 64);

}  // namespace fabmesh::detail
