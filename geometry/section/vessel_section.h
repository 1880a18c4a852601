#pragma once
// The closed 2D section of a vessel in the (radius, height) half-plane:
// the profile closed to the axis (solid) or thickened into a wall with a rim
// and a base (shell). Revolving a simple section gives an embedded surface.

#include <string>
#include <vector>

#include "geometry/core/limits.h"
#include "geometry/core/types.h"
#include "geometry/curves/composite.h"

namespace fabmesh {

enum class BodyMode { Solid, Shell };

struct VesselSectionOptions {
  BodyMode mode = BodyMode::Solid;
  double wall = 0.0;         ///< shell: wall thickness along the profile normal, model units (> 0)
  double base = 0.0;         ///< shell: base thickness, model units (> 0; 0 = wall)
  double tolerance = 0.005;  ///< profile sampling tolerance, model units (> 0)
  std::size_t max_points = kDefaultMaxPoints;
};

/// Closed, simple, counter-clockwise, pairwise disjoint loops in the
/// half-plane r >= 0 (x = radius, y = height), one per body: a solid profile
/// that runs along the axis between two parts makes two bodies. Vertices with
/// x == 0 exactly lie on the axis; a loop meets the axis only along axis
/// edges (both ends on it), never at an isolated vertex, so revolving it
/// gives a closed 2-manifold.
struct VesselSection {
  std::vector<std::vector<Vec2>> loops;
  double max_deviation = 0.0;  ///< bound on the distance between the loop and the exact section boundary
  double max_radius = 0.0;
  std::string proof;  ///< why the section is simple (for reports)
};

/// Builds and checks the section. The profile runs either way; its higher
/// end is the rim. A closed profile is revolved as it is (solid only).
/// \throw GeometryError when the profile crosses the axis or itself, touches
///        the axis at a single point (the body would pinch), or the wall is too thick for its
///        curvature or its radius; RangeError for bad wall/base/tolerance.
VesselSection build_vessel_section(const CompositeCurve& profile, const VesselSectionOptions& options);

}  // namespace fabmesh
