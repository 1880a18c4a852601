#pragma once
// The self-intersection test against its CGAL-based reference: the same
// count, cap and pairs, in parallel and sequentially.

#include <catch2/catch.hpp>
#include <cstddef>
#include <vector>

#include "geometry/core/soup.h"
#include "geometry/validation/detail/self_intersect.h"
#include "geometry/validation/detail/self_intersect_reference.h"

namespace fabmesh::test {

/// Requires find_self_intersections, parallel and sequential, to give the
/// reference's answer (faces flagged in `skip` left out); returns it.
inline SelfIntersections require_same(const TriangleSoup& s, const std::vector<char>& skip = {},
                                      std::size_t max_pairs = 100, std::size_t count_limit = 10'000'000) {
  SelfIntersectOptions options;
  options.max_pairs = max_pairs;
  options.count_limit = count_limit;
  const SelfIntersections expected = find_self_intersections_reference(s, skip, options);
  const SelfIntersections parallel = find_self_intersections(s, skip, options);
  options.parallel = false;
  const SelfIntersections sequential = find_self_intersections(s, skip, options);
  REQUIRE(parallel.count == expected.count);
  REQUIRE(parallel.capped == expected.capped);
  REQUIRE(parallel.pairs == expected.pairs);
  REQUIRE_FALSE(parallel.incomplete);
  REQUIRE(sequential.count == parallel.count);
  REQUIRE(sequential.pairs == parallel.pairs);
  return parallel;
}

}  // namespace fabmesh::test
