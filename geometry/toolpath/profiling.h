#pragma once
// The router's profiling pass of an edge profile: the profile bit along each
// run of a part's exposed edges, after the part is cut out.

#include <string>
#include <vector>

#include "geometry/core/types.h"

namespace fabmesh {

/// One run of exposed edges: the profile bit's centre path (closed when the
/// run is the whole loop: its last point is then its first).
struct ProfileRun {
  std::vector<Vec2> path;
  bool closed = false;
  std::string label;  ///< "piece-1 exposed edges 1": for comments
};

/// The passes of a program: the profile bit (its number, its diameter at the
/// tip), the depth of its tip below the top, and the runs, in order.
struct ProfilePasses {
  int tool = 0;
  double diameter = 0.0;
  double depth = 0.0;
  std::string profile;  ///< "half_bullnose, radius 12": for comments
  std::vector<ProfileRun> runs;
};

/// The runs of consecutive exposed edges of `outer` (counter-clockwise; edge
/// i from outer[i] to outer[i + 1], `exposed` one flag per edge), each
/// offset outward by `radius`: the tool rolls round a convex corner on an
/// arc (chords within `tolerance` of it) and meets a reflex one at the
/// mitre; a run starts and ends at the offset of its end points. Runs are
/// named `label` exposed edges 1, 2, ... from the first exposed edge after
/// an unexposed one.
std::vector<ProfileRun> profile_runs(const std::vector<Vec2>& outer, const std::vector<bool>& exposed,
                                     double radius, double tolerance, const std::string& label);

}  // namespace fabmesh
