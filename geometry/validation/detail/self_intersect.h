#pragma once
// Self-intersection of a triangle soup: pairs of faces that meet anywhere
// other than at the vertices and edges they share by index.
//
// Internal to geometry/validation (validate.h is the public entry); the
// tests and the benchmarks include it to check and time this part alone.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "geometry/core/soup.h"

namespace fabmesh {

/// Options of find_self_intersections.
struct SelfIntersectOptions {
  bool parallel = true;         ///< test candidate pairs on all cores (TBB)
  std::size_t max_pairs = 100;  ///< how many intersecting pairs to return
  /// Stop once this many intersecting pairs are found (bounds the time spent
  /// on a soup that is a pile of overlapping faces).
  std::size_t count_limit = 10'000'000;
  /// Give up when the search is still running at this time: the result is
  /// then `incomplete` (checked between units of work of at most a few
  /// thousand candidate pairs). None: no limit.
  std::optional<std::chrono::steady_clock::time_point> deadline;
};

/// The deadline `seconds` from now; none when seconds is not positive, not
/// finite or beyond a year (no limit in practice).
inline std::optional<std::chrono::steady_clock::time_point> deadline_after(double seconds) {
  if (!(seconds > 0.0) || !(seconds < 3.2e7)) return std::nullopt;
  return std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                std::chrono::duration<double>(seconds));
}

/// The outcome of a self-intersection test.
struct SelfIntersections {
  std::size_t count = 0;  ///< number of intersecting face pairs (exact unless capped)
  bool capped = false;    ///< the search stopped at count_limit; count is a lower bound
  /// The search stopped at the deadline: pairs were left untested; count
  /// and pairs are what was found until then (a lower bound).
  bool incomplete = false;
  std::size_t candidates_tested = 0;  ///< candidate pairs decided (by filter or exact test)
  /// Up to max_pairs intersecting pairs of face indices (first < second),
  /// in ascending order.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
};

/// Finds the pairs of faces of `soup` that intersect, exactly: faces sharing
/// two vertex indices intersect only if they are coplanar and overlap across
/// the shared edge; faces sharing one vertex only if the edge opposite it in
/// one face touches the other; faces sharing none if the triangles meet
/// (faces_intersect_exact in self_intersect_reference.h is the definition).
/// Candidates come from a bounding-volume hierarchy over the triangle boxes,
/// except the pairs sharing a vertex of high degree, which come from that
/// vertex's star (vertex_star.h: d faces around a vertex in O(d log d));
/// a floating-point filter with proven error bounds dismisses the pairs that
/// certainly do not intersect and the others are decided with exact
/// predicates (CGAL Epick). The result equals find_self_intersections_reference
/// and does not depend on the number of threads: `pairs` are the smallest
/// max_pairs pairs counted; when capped, the pairs counted are the first
/// count_limit in the search order (a fixed order over a Morton sort).
/// Faces with skip[f] != 0 take no part (validation skips degenerate faces
/// and extra copies of duplicate faces, which it reports on their own).
/// \param skip  empty, or one flag per triangle
/// \pre every vertex coordinate is finite and every index in range
/// \throw InputError when an index is out of range, a coordinate is not
///        finite, or `skip` is neither empty nor one flag per triangle.
SelfIntersections find_self_intersections(const TriangleSoup& soup, const std::vector<char>& skip = {},
                                          const SelfIntersectOptions& options = {});

}  // namespace fabmesh
