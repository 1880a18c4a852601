#pragma once
// The reference self-intersection test: CGAL's box_intersection_d for the
// candidates and CGAL Epick for every pair. Slow but simple; kept so that
// the fast find_self_intersections can be tested against it pair for pair
// (tests/geometry/validation/self_intersect_test.cpp) and timed against it (bench/).
//
// Internal to geometry/validation (validate.h is the public entry); the
// tests and the benchmarks include it to check and time this part alone.

#include <cstdint>
#include <vector>

#include "geometry/core/soup.h"
#include "geometry/validation/detail/self_intersect.h"

namespace fabmesh {

/// Whether faces f and g of `soup` meet anywhere other than at the vertex
/// indices they share, decided with exact predicates (CGAL Epick): faces
/// sharing 3 indices never (duplicates are reported elsewhere); sharing 2
/// (p, q) iff all four points are coplanar and the third vertices lie on the
/// same side of pq; sharing 1 iff the edge opposite the shared vertex in one
/// face touches the other face; sharing none iff the triangles intersect.
/// This is the one narrow-phase definition both implementations use.
/// \pre f and g index soup.triangles, whose indices are in range and whose
/// vertices are finite (not checked here).
bool faces_intersect_exact(const TriangleSoup& soup, std::uint32_t f, std::uint32_t g);

/// The reference implementation of find_self_intersections (same contract,
/// same options): every candidate pair of CGAL's box_intersection_d is tested
/// with faces_intersect_exact. Its pairs are the smallest max_pairs of the
/// first max(max_pairs, 100000) pairs found, so they are deterministic only
/// while count <= max(max_pairs, 100000); when capped, which pairs were
/// counted depends on the thread schedule.
/// \throw InputError when an index is out of range or a coordinate is not finite.
SelfIntersections find_self_intersections_reference(const TriangleSoup& soup,
                                                    const std::vector<char>& skip = {},
                                                    const SelfIntersectOptions& options = {});

}  // namespace fabmesh
