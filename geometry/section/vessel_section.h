#pragma once
// The closed 2D section of a vessel in the (radius, height) half-plane:
// the profile closed to the axis (solid) or thickened into a wall with a rim
// and a base (shell). Revolving a simple section gives an embedded surface.

#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "geometry/core/limits.h"
#include "geometry/core/types.h"
#include "geometry/curves/composite.h"
#include "geometry/section/inner_wall.h"

namespace fabmesh {

enum class BodyMode { Solid, Shell };

/// How a shell's rim is cut. Square: across the wall, perpendicular to the
/// profile at its end, so the inner edge lies `wall` from the outer one along
/// the normal (a profile that flares outward at the rim makes the inner edge
/// higher than the profile's end: the golden cup ending at z = 6 with a 0.3
/// wall stands 6.134 high). Level: a horizontal rim at the profile's end
/// height (the inner wall cut there, or continued along its end tangent up to
/// it when it ends lower).
enum class RimCut { Square, Level };

/// How a message names a key it mentions besides the one it is at (the
/// profile whose segment a wall is too thick for): the caller's name for the
/// key, e.g. with its place in the design ("file:line:column: profile").
using KeyNamer = std::function<std::string(const std::string& key)>;

struct VesselSectionOptions {
  BodyMode mode = BodyMode::Solid;
  double wall = 0.0;            ///< shell: wall thickness along the profile normal, model units (> 0)
  double base = 0.0;            ///< shell: base thickness, model units (> 0; 0 = wall)
  RimCut rim = RimCut::Square;  ///< shell: how the rim is cut
  double tolerance = 0.005;     ///< profile sampling tolerance, model units (> 0)
  /// Shell: the exact inner and outer walls (with the base and the bottom)
  /// must stay at least this far apart, model units; 0: `tolerance`.
  double min_clearance = 0.0;
  /// Off-axis loop vertices closer to the axis than this are moved out to
  /// it (radially; when the loops stay simple), and max_deviation grows by
  /// the largest move: rings of tiny radius would crowd the pole of the
  /// revolution and leave it no margin for rounding (revolution_margin).
  /// Model units, >= 0; 0: none moved.
  double axis_clearance = 0.0;
  std::size_t max_points = kDefaultMaxPoints;
  /// Names the profile where a message points at one of its segments
  /// ("segment 3 of NAME"); null: "segment 3 of profile". Errors are at the
  /// keys "profile", "wall", "base" and "rim" (GeometryError::location).
  KeyNamer name_key;
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
  /// Shell: the smallest distance between the exact outer surface (profile and
  /// bottom) and the exact inner surface (inner wall and base), a proven lower
  /// bound; NaN for a solid.
  double min_clearance = std::numeric_limits<double>::quiet_NaN();
  std::string clearance_where;  ///< where min_clearance is attained (for reports)
  /// Shell: the inner wall as cut (from the rim down), with the profile
  /// segment and parameter of each point: the exact section is the profile,
  /// the rim, this wall, the base or the axis and the bottom.
  std::optional<InnerWall> inner_wall;
};

/// Builds and checks the section. The profile runs either way; its higher
/// end is the rim. A closed profile is revolved as it is (solid only).
/// A shell's inner wall is the exact offset of the profile, sampled with its
/// own proven chord bound (max_deviation covers both walls) and cut exactly
/// where it meets the base plane or the axis.
/// \throw GeometryError when the profile crosses the axis or itself, touches
///        the axis at a single point (the body would pinch), the wall is too
///        thick for its curvature (proven over each whole chord) or its radius,
///        the base leaves no cavity (a base at least as tall as the wall's
///        height), or the exact walls come closer than min_clearance;
///        RangeError for bad wall/base/tolerance; BudgetError (max_points).
VesselSection build_vessel_section(const CompositeCurve& profile, const VesselSectionOptions& options);

}  // namespace fabmesh
