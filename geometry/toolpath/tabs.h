#pragma once
// Where the holding tabs go on the outline's tool path.

#include <utility>
#include <vector>

#include "geometry/toolpath/cnc_options.h"
#include "geometry/toolpath/loop_path.h"

namespace fabmesh {

/// Where the tabs of one loop go.
struct TabPlacement {
  std::vector<std::pair<double, double>> tabs;  ///< sorted intervals of distance along the path
  /// Empty when every tab asked for was placed; else which were left out and why.
  std::string warning;
};

/// Intervals [begin, end] of distance along `path.pieces` over which the tool
/// rises for tabs.count tabs, each width + tool diameter long. Tab i wants
/// its centre at (i + 1/2) L / count (L the path length, measured from the
/// start point where the lead-in arrives) and goes to the nearest position
/// where its whole interval lies on offset pieces whose radius of curvature
/// is at least tabs.min_radius (straight or gently curved; unset: 20 tool
/// diameters, or the loop's largest radius of curvature where no stretch is
/// that flat, so a round cut-out gets tabs; the arcs round convex corners
/// that turn less than such a curve turns over one tool diameter count as
/// gentle too), at least one tool diameter from the other tabs, from
/// the end of the path and from `clear_start` (one tool diameter, or the end of a ramp entry's stretch plus
/// one). A tab that finds no such place is left out, and the warning says so (no tab is better than one that
/// breaks the program; the operator holds the part or adds a clamp).
TabPlacement place_tabs(const LoopPath& path, const TabOptions& tabs, const CncOptions& options,
                        double clear_start);

}  // namespace fabmesh
