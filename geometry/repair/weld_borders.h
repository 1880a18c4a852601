#pragma once
// The weld of a repair: coincident vertices merged exactly, then border
// vertices closer than a distance chosen from the data (the gaps an exporter's
// rounding leaves between copies of one corner) merged too.

#include <cstddef>
#include <string>

#include "geometry/repair/repair_log.h"
#include "geometry/repair/tracked_soup.h"

namespace fabmesh {

/// The border weld's distance, and how it was chosen.
struct WeldChoice {
  double distance = 0.0;  ///< border vertices this close merge (0: none)
  double cap = 0.0;       ///< the largest distance considered (see choose_weld_distance)
  std::size_t gaps = 0;   ///< border vertices with another border vertex within the cap
  std::string why;        ///< one sentence for the report
};

/// Chooses the border weld distance of `mesh` (exactly welded): each border
/// vertex's gap to its nearest other border vertex that shares no face with
/// it, among gaps at most the cap = min(1e-3 x the bounding box diagonal,
/// half the median edge length). The distance is 3 times the largest gap
/// before the first ten-fold jump above their median (jitter, most of the
/// gaps, sits below it, features above; copies of one corner chain beyond
/// their nearest neighbours), at most a third of the first gap above the
/// jump and the cap, at least 1e-12 of the largest coordinate; 0 when no
/// border vertex has such a gap.
/// `requested` >= 0 overrides the choice (0: no border weld).
WeldChoice choose_weld_distance(const TriangleSoup& mesh, double requested = -1.0);

/// Merges exactly coincident vertices of `mesh` (not a repair: every STL
/// repeats its corners); returns how many merged.
std::size_t weld_exact(TrackedSoup& mesh);

/// Merges border vertices of `mesh` within `distance` (transitively; each
/// group keeps its lowest index's position) and logs each merged vertex as a
/// RepairStep::Weld place. Faces whose corners merge are left for the
/// degenerate-face step.
void weld_borders(TrackedSoup& mesh, double distance, RepairLog& log);

}  // namespace fabmesh
