#pragma once
// Where the holding tabs go on the outline's tool path.

#include <utility>
#include <vector>

#include "geometry/toolpath/cnc_options.h"
#include "geometry/toolpath/loop_path.h"

namespace fabmesh {

/// Intervals [begin, end] of distance along `path.pieces` over which the tool
/// rises for options.tabs.count tabs, each width + tool diameter long. Tab i
/// wants its centre at (i + 1/2) L / count (L the path length, measured from
/// the start point where the lead-in arrives) and goes to the nearest
/// position where its whole interval lies on offset pieces whose radius of
/// curvature is at least tab_min_radius(options) (straight or gently curved),
/// at least one tool diameter from the start point and from the other tabs.
/// Sorted; empty when count is 0.
/// \throw GeometryError (where: the loop's label) when a tab finds no room
std::vector<std::pair<double, double>> place_tabs(const LoopPath& path, const CncOptions& options);

}  // namespace fabmesh
