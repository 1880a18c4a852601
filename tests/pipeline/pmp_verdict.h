#pragma once
// CGAL Polygon Mesh Processing's own verdict on a triangle soup, the
// independent judge the tests compare `fabmesh check` with (the same checks
// as bench/pmp_check, in-process). CGAL stays inside pmp_verdict.cpp.

#include <optional>

#include "geometry/core/soup.h"

namespace fabmesh::testing {

struct PmpVerdict {
  bool polygon_mesh = false;       ///< the soup (welded) is a polygon mesh without reorienting
  bool closed = false;             ///< CGAL::is_closed
  bool self_intersecting = false;  ///< PMP::does_self_intersect
  /// PMP::is_outward_oriented, for a closed mesh of one connected component
  /// (CGAL decides it from one extreme vertex: its notion is the whole
  /// mesh's only then); unset otherwise.
  std::optional<bool> outward;
};

/// PMP's verdict on `soup`, whose equal positions are already one vertex.
PmpVerdict pmp_verdict(const TriangleSoup& soup);

}  // namespace fabmesh::testing
