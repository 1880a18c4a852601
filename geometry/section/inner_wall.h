#pragma once
// A shell vessel's inner wall: the exact offset of the profile by the wall
// thickness, sampled with a proven chord bound, cut exactly where it meets
// the base plane, the axis or a level rim.

#include <cstddef>
#include <memory>
#include <vector>

#include "geometry/curves/composite.h"
#include "geometry/sampling/offset_bezier.h"
#include "geometry/sampling/sample_curve.h"
#include "geometry/section/curve_clearance.h"

namespace fabmesh {

/// A point of the inner wall and where it lies: on the offset of profile
/// segment `segment` at parameter s, or on a straight piece.
struct WallPoint {
  Vec2 point{0.0, 0.0};
  std::size_t segment = 0;
  double s = 0.0;
};

/// The inner wall from the rim down. Piece k runs from points[k] to
/// points[k + 1]: a straight line when straight[k] (a bevel across a profile
/// corner, where the offsets of the two segments do not meet, or a level
/// rim's extension), else an arc of one segment's offset.
struct InnerWall {
  std::vector<WallPoint> points;
  std::vector<bool> straight;
  /// Proven bound between the polyline and the exact wall (offset arcs,
  /// straight pieces), model units.
  double max_deviation = 0.0;
  double wall = 0.0;
  double side = 1.0;  ///< offset side of the profile's direction (OffsetSpec::side)
};

/// Samples the offset of every segment of `profile` by `wall` on side
/// `side` (+1: left of the profile's direction) within options.tolerance,
/// proving on each piece that the offset does not fold (OffsetChordBound),
/// and orders the result from the rim down (`rim_at_end`: the profile's
/// end is its rim). Messages name segment i "segment i of `profile_name`"
/// (nothing when it is empty). \throw GeometryError (a wall too thick for
/// the curvature), BudgetError (options.max_points)
InnerWall sample_inner_wall(const CompositeCurve& profile, double wall, double side, bool rim_at_end,
                            const SampleOptions& options, const std::string& profile_name);

/// Cuts the wall where it first (from the rim down) reaches height z_cut or
/// the axis (radius 0), at the exact crossing of the offset curve (bisection
/// on the arc whose chord crosses). Returns true for a cut at z_cut (then the
/// last point is at exactly z_cut), false for the axis or no crossing.
bool cut_inner_wall(InnerWall& wall, const CompositeCurve& profile, double z_cut);

/// A level rim at height z_top: the wall above is cut away at its exact
/// crossing, or, when the wall ends below, it is extended along its end
/// tangent (a straight piece) up to z_top. \throw GeometryError when the wall
/// does not rise at the rim.
void level_inner_wall(InnerWall& wall, const CompositeCurve& profile, double z_top, bool rim_at_end);

/// The exact curves of the wall's pieces for the clearance check, in `group`;
/// `arcs` keeps the curve objects the pieces point to.
void inner_wall_pieces(const InnerWall& wall, const CompositeCurve& profile, int group,
                       std::vector<std::unique_ptr<ExactArc>>& arcs, std::vector<ArcPiece>& pieces);

}  // namespace fabmesh

namespace fabmesh {

/// The wall's exact pieces from the rim down: its straight pieces as lines,
/// and each run of offset arcs of one profile segment as one arc (for exact
/// outputs: STEP). Zero-length pieces are left out.
std::vector<ExactPiece> inner_wall_exact_pieces(const InnerWall& wall, const CompositeCurve& profile);

}  // namespace fabmesh
