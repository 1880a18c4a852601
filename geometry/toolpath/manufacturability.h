#pragma once
// Can a router bit of the given diameter cut this region? Checked on the
// exact curves before any toolpath is built: concave corners and concave
// stretches tighter than the tool, holes narrower than the tool, webs
// between loops narrower than allowed.

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "geometry/curves/composite.h"
#include "geometry/toolpath/boundary_index.h"
#include "geometry/toolpath/cnc_options.h"

namespace fabmesh {

/// One closed loop of the part as the tool sees it. `reversed`: the loop runs
/// against its curve so that the part lies on its left (Region2::reversed):
/// the outline counter-clockwise, the holes clockwise. The tool cuts on the
/// right of that direction: outside the outline, inside the holes.
struct CutCurve {
  const CompositeCurve* curve = nullptr;
  std::string label;  ///< "outline", "holes[0] (rounded_rect)", ...
  bool outer = false;
  bool reversed = false;
};

/// A G0 joint of a loop (a corner).
struct LoopCorner {
  std::size_t before = 0, after = 0;  ///< curve segments meeting there (curve order)
  Vec2 at{0.0, 0.0};
  double turn = 0.0;  ///< signed turning angle in the cutting orientation, radians (> 0: convex for the tool)
};

/// What the checks found on one loop.
struct LoopCheck {
  std::string label;
  /// Proven lower bound of the radius of curvature over the loop's concave
  /// stretches (curving away from the tool), to 6 digits when below 1000
  /// tool radii (else a bound at least that); infinity when there are none.
  double min_concave_radius = std::numeric_limits<double>::infinity();
  std::size_t min_segment = 0;  ///< where the smallest radius was found
  Vec2 min_at{0.0, 0.0};
  std::vector<LoopCorner> convex_corners;   ///< the tool turns around them on an arc of its radius
  std::vector<LoopCorner> concave_corners;  ///< relieved by dog-bones (refused without relief)
  /// Concave corners so slight that the tool's round leaves at most
  /// shallow_corner_depth(options) of material at the corner point,
  /// r (1 / cos(turn / 2) - 1): cut through (the offsets trimmed to where
  /// they meet), neither refused nor relieved. A digitised outline's points
  /// on a smooth stretch are such corners.
  std::vector<LoopCorner> shallow_corners;
};

/// The material a tool of radius r keeps at a concave corner turning by
/// `turn` radians: its round's distance from the corner point, r (1 / cos(turn / 2) - 1).
double corner_round_depth(double r, double turn);

/// The most material a shallow concave corner may keep at its corner point:
/// a quarter of options.tolerance (plan_toolpath's share "shallow concave corners").
double shallow_corner_depth(const CncOptions& options);

struct ManufacturabilityReport {
  std::vector<LoopCheck> loops;  ///< in the order given
  /// Narrowest distance between two different loops (infinity for one loop),
  /// measured on the sampled loops: the exact gap is within 2 * boundary
  /// deviation of it.
  double min_web = std::numeric_limits<double>::infinity();
  Vec2 min_web_at{0.0, 0.0};
};

/// The checks, in this order, each throwing GeometryError whose `where` is the
/// loop's label (message: loop, segment or joint, point, the radius or gap found):
///  1. every hole is at least one tool diameter wide in every direction;
///  2. no concave G0 corner, unless options.relief is Dogbone or it is shallow
///     (LoopCheck::shallow_corners);
///  3. every concave stretch has a radius of curvature >= the tool radius
///     (least_curvature: proven, relative slack 1e-6); at a shallow corner
///     between two lines (a digitised outline's point), the circle through it
///     and its neighbouring points has a radius >= the tool radius;
///  4. no two loops come closer than min_web(options).
/// `boundary` holds the loops sampled within `boundary_deviation` of their
/// curves (loop indices as in `loops`).
/// \throw GeometryError, RangeError (options)
ManufacturabilityReport check_manufacturability(const std::vector<CutCurve>& loops,
                                                const BoundaryIndex& boundary, double boundary_deviation,
                                                const CncOptions& options);

/// The corners of one loop (G0 joints), in cutting orientation.
std::vector<LoopCorner> loop_corners(const CutCurve& loop);

/// "segment 3 (tbezier)".
std::string segment_name(const CompositeCurve& curve, std::size_t segment);

}  // namespace fabmesh
