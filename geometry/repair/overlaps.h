#pragma once
// Intersections resolved: a shell's own by CGAL's autorefinement, closed
// shells that overlap each other by their exact union (docs/repair.md).

#include <string>
#include <vector>

#include "geometry/repair/repair_log.h"
#include "geometry/repair/tracked_soup.h"

namespace fabmesh {

/// What resolve_intersections did not manage, and which faces read it
/// replaced by construction.
struct OverlapOutcome {
  std::vector<std::string> unresolved;  ///< one line each, with where
  /// The faces read (indices of the mesh as read) of the shells united or
  /// autorefined: every point of them is on the output or inside it (by
  /// construction), so they are not measured from the input side.
  std::vector<std::uint32_t> united_faces;
};

/// Finds the faces of `mesh` that intersect (CGAL's exact test). A
/// component intersecting itself is autorefined (RepairStep::SelfIntersection);
/// components intersecting each other are each turned outward and united
/// (RepairStep::Union), cluster by cluster. Faces made get no origin.
/// Every face of `mesh` must be non-degenerate and every component a closed,
/// consistently oriented manifold.
OverlapOutcome resolve_intersections(TrackedSoup& mesh, RepairLog& log);

}  // namespace fabmesh
