#pragma once
// The closed tool-centre path around one loop of the part: the offsets of its
// segments by the tool radius on the waste side, arcs of the tool radius
// around convex corners, dog-bones into concave corners, run in the cutting
// direction from a start point on a straight or gently curved stretch.

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "geometry/toolpath/cnc_options.h"
#include "geometry/toolpath/manufacturability.h"
#include "geometry/toolpath/path_piece.h"

namespace fabmesh {

struct LoopPath {
  std::string label;
  bool outer = false;
  /// Closed: each piece starts where the previous ends, the last ends where
  /// the first starts (the start point, where the lead-in arrives).
  std::vector<PathPiece> pieces;
  /// The lead-in arc from the waste side onto pieces.front().from, tangent
  /// there (role Link); none when cnc.lead_in is 0 or no lead fits.
  std::optional<PathPiece> lead;
  /// Helix entry: the circle (a whole turn, role Link) the tool descends
  /// round, from and back to the lead's start (the path's without a lead),
  /// tangent to it there, in the waste.
  std::optional<PathPiece> helix;
  /// Tabs: intervals [begin, end] of distance along `pieces` from the start
  /// over which the tool rises, sorted.
  std::vector<std::pair<double, double>> tabs;
  double tab_height = 0.0;  ///< the tabs' height above the bottom of the slab
  double length = 0.0;      ///< of `pieces`
  /// Proven bound: the path vs the exact offset curve (chords of chains
  /// plus the fitted arcs' distance from what they replaced).
  double deviation = 0.0;
  double chord_deviation = 0.0;  ///< the chords' part of it
  /// Arc fitting (LoopPathOptions::arc_fit_tolerance > 0): pieces of G1
  /// stretches replaced, and the arcs and lines fitted in their place.
  std::size_t fit_replaced = 0, fit_arcs = 0, fit_lines = 0;
  double fit_deviation = 0.0;  ///< proven: the fitted arcs vs the pieces they replaced
};

struct LoopPathOptions {
  double radius = 6.0;             ///< tool radius, > 0
  double chain_tolerance = 0.005;  ///< chords vs exact offset, > 0
  CutDirection direction = CutDirection::Climb;
  double gentle_radius = 240.0;      ///< the start point goes on the longest stretch at least this flat
  std::size_t max_points = 5000000;  ///< budget of chords
  /// > 0: the path's G1 stretches (a digitised outline's points, chords of
  /// chains) are replaced by biarcs (arc_fit.h) within what is left of this
  /// when the chords' proven deviation is taken off (so the path stays within
  /// this of the exact offset); 0: none.
  double arc_fit_tolerance = 0.0;
};

/// The path of one loop, after check_manufacturability has accepted it
/// (`check` is its LoopCheck: which corners are convex and concave). Concave
/// corners get dog-bones (the caller refuses them unless relief is Dogbone;
/// shallow ones, LoopCheck::shallow_corners, are cut through, the offsets
/// trimmed to where they cross):
/// both neighbouring offsets are cut back to where they cross, X, and the
/// tool runs from X towards the corner point P until its disc touches P
/// (centre at P + r (X - P) / |X - P|) and back.
/// \throw GeometryError when the offsets at a concave corner do not cross
///        (a segment too short for the tool), BudgetError over max_points
LoopPath build_loop_path(const CutCurve& loop, const LoopCheck& check, const LoopPathOptions& options);

/// A tangent arc lead of radius `radius` and sweep pi/2 from the waste side
/// onto the start of `path` (the waste is on the right of the travel for
/// conventional cutting, on its left for climb).
PathPiece lead_arc(const LoopPath& path, CutDirection direction, double radius);

/// The same closed chain starting at distance u from its start (a piece split there).
std::vector<PathPiece> rotate_path(const std::vector<PathPiece>& pieces, double u);

/// The distance along a chain of pieces of its point nearest to q.
double nearest_along(const std::vector<PathPiece>& pieces, const Vec2& q);

/// Point and unit tangent at distance u along a closed chain of pieces.
std::pair<Vec2, Vec2> path_point(const std::vector<PathPiece>& pieces, double u);

}  // namespace fabmesh
