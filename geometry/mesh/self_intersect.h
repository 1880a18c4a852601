#pragma once
// Self-intersection of a triangle soup: pairs of faces that meet anywhere
// other than at the vertices and edges they share by index.

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "geometry/mesh/soup.h"

namespace fabmesh {

/// Options of find_self_intersections.
struct SelfIntersectOptions {
  bool parallel = true;         ///< test candidate pairs on all cores (TBB)
  std::size_t max_pairs = 100;  ///< how many intersecting pairs to return
  /// Stop once this many intersecting pairs are found (bounds the time spent
  /// on a soup that is a pile of overlapping faces).
  std::size_t count_limit = 10'000'000;
};

/// The outcome of a self-intersection test.
struct SelfIntersections {
  std::size_t count = 0;  ///< number of intersecting face pairs (exact unless capped)
  bool capped = false;    ///< the search stopped at count_limit; count is a lower bound
  /// Up to max_pairs intersecting pairs of face indices (first < second),
  /// in ascending order.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
};

/// Finds the pairs of faces of `soup` that intersect, using exact predicates
/// (CGAL Epick) on axis-aligned-box candidates. Faces sharing two vertex
/// indices intersect only if they are coplanar and overlap across the shared
/// edge; faces sharing one vertex only if they meet elsewhere too.
/// Faces with skip[f] != 0 take no part (validation skips degenerate faces
/// and extra copies of duplicate faces, which it reports on their own).
/// \param skip  empty, or one flag per triangle
/// \pre every vertex coordinate is finite and every index in range
/// \throw InputError when an index is out of range or a coordinate is not finite.
SelfIntersections find_self_intersections(const TriangleSoup& soup, const std::vector<char>& skip = {},
                                          const SelfIntersectOptions& options = {});

}  // namespace fabmesh
