#pragma once
// Tap holes drilled with a drill cycle: round through holes the router does
// not cut round, drilled in one canned cycle each before any routing (the
// part is still held by all its surroundings). Coordinates as the toolpath's.

#include <cstddef>
#include <string>
#include <vector>

#include "geometry/core/types.h"
#include "geometry/toolpath/cnc_options.h"

namespace fabmesh {

/// A hole the program drills (a design hole `drill: {center, diameter}`).
struct DrillHole {
  Vec2 center{0.0, 0.0};  ///< in the program's coordinates (slab coordinates for a kitchen)
  double diameter = 0.0;  ///< > 0, the drill's
  int tool = 0;           ///< the drill's number in the tool table
  std::string label;      ///< "holes[2] (drill)", "piece-2 holes[2]": for messages and comments
};

/// `holes` in the order drilled: by tool number (one tool change each), then
/// as given. Each is checked: diameter > 0, a tool number in [1, 999] that
/// is not the router bit's (end_mill_number), and with a tool table
/// (options.tools) a drill of the table of the hole's diameter.
/// \throw GeometryError at the hole's label
std::vector<DrillHole> drilling_order(std::vector<DrillHole> holes, const CncOptions& options);

/// Checks the web of material round each drill hole, as
/// check_manufacturability does between routed loops: `loops` are the
/// part's loops sampled within `deviation` of their exact curves (the
/// outline, then the holes), `labels` their names, `own[k]` the index in
/// `loops` of drill k's own loop (skipped). A drill's exact gap to another
/// loop is at most d + deviation - radius (d: the distance from its exact
/// centre to the samples); when that is below min_web(options) the hole is
/// refused.
/// \throw GeometryError at the drill's label, naming the other loop, the gap and the place
void check_drill_webs(const std::vector<DrillHole>& drills, const std::vector<std::size_t>& own,
                      const std::vector<const std::vector<Vec2>*>& loops,
                      const std::vector<std::string>& labels, double deviation, const CncOptions& options);

/// What the drill cycles of `drills` run, model units: the feeds down (from
/// the retract plane R = drill_retract to -(depth + breakthrough), each
/// peck's re-approach clearance left out, so a lower bound) and the rapids
/// (down from safe height to R, up after each feed or peck, and across at
/// safe height from hole to hole).
struct DrillingTotals {
  double feeding = 0.0;
  double rapid = 0.0;
};
DrillingTotals drilling_totals(const std::vector<DrillHole>& drills, const CncOptions& options);

}  // namespace fabmesh
