#pragma once
// A proven bound on the distance between two triangle surfaces: how far a
// repair moved the surface (docs/repair.md, "How the distance is bounded").
//
// For a triangle T of one surface and the other surface B, sup over p in T
// of d(p, B) is bounded two ways, and the smaller bound kept:
// - convexity: p -> d(p, t) is convex for one triangle t of B, so on T it
//   is largest at a corner: sup_T d(., B) <= max_i d(c_i, t), for t the
//   triangle nearest to any corner c_i;
// - covering: every p in T is within 2/3 of T's longest edge L of a corner
//   (the corner of largest barycentric weight w: |p - c| <= (1 - w) L), and
//   d(., B) is 1-Lipschitz: sup_T d(., B) <= max_i d(c_i, B) + 2L/3.
// T is split in four until the bound is within `resolution` of the largest
// corner distance (which the surface attains: a lower bound) or the work is
// spent. Distances to B are computed to points constructed on B's
// triangles, so each is an upper bound up to the rounding of that
// construction, which is added (1e-13 x (coordinate magnitude + distance)).

#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/core/soup.h"

namespace fabmesh {

/// What bounds the distance measured.
struct DistanceOptions {
  double resolution = 0.0;  ///< refine until upper - lower <= this (model units; 0: 1e-6 of the size)
  std::size_t max_evaluations = 20000000;  ///< corner-to-surface distances, in all (a work bound)
};

/// A one- or two-sided distance: proven upper bound, attained lower bound.
struct DistanceBound {
  double upper = 0.0;      ///< no point is farther than this (model units)
  double lower = 0.0;      ///< a point this far was found (its corner distance)
  Vec3 at = Vec3::Zero();  ///< that point
  std::size_t faces = 0;   ///< faces measured (faces present in both surfaces are at distance 0)
};

/// No partner face (see one_sided_distance).
inline constexpr std::uint32_t kNoPartner = static_cast<std::uint32_t>(-1);

/// sup over the points of `from`'s faces (those with measure[f] set, or all
/// when `measure` is empty) of the distance to the surface of `to`. A face
/// whose three corners are exactly those of a face of `to` is at distance
/// 0 and not measured. `to` must have a face unless nothing is measured.
/// `partners` (empty, or one per face of `from`: a face of `to`, or
/// kNoPartner) names the face of `to` each face of `from` was made from by
/// moving its corners (a weld, a split vertex moved apart): then the most a
/// corner moved, under the best matching of corners, bounds the face too
/// (the affine map between the two triangles moves no point farther), and
/// the smaller bound is kept.
DistanceBound one_sided_distance(const TriangleSoup& from, const std::vector<bool>& measure,
                                 const TriangleSoup& to, const DistanceOptions& options = {},
                                 const std::vector<std::uint32_t>& partners = {});

/// The two-sided (Hausdorff) bound: the larger of both one-sided ones.
DistanceBound hausdorff_distance(const TriangleSoup& a, const TriangleSoup& b,
                                 const DistanceOptions& options = {});

}  // namespace fabmesh
