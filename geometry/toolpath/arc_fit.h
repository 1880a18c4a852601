#pragma once
// Arcs fitted to the G1 stretches of a tool-centre path: a digitised
// outline's points (offset lines joined by the tool's small arcs round its
// convex points or crossing at its slight concave turns) and the chords of
// non-circular offsets, replaced by tangent-continuous biarcs (two circular
// arcs meeting with one tangent) within a proven distance of the path they
// replace.
//
// The bound (checked exactly, per fitted arc F of centre c, radius R and
// sweep S, against the stretch P it replaces, whose ends are F's ends):
// every piece of P must move monotonically round c in F's sense (a line
// always does, unless it runs the other way; an arc of the path unless it
// holds one of the two points where a line from c touches its circle), and
// the turns of P's pieces about c must add up to S. Then each ray from c at
// an angle of F's span meets P (a connected chain) in one point or one
// radial piece, and matching each point of F with the points of P on its
// ray is a monotone correspondence between the two: the Frechet distance,
// and so the distance either way, is at most
//   max over p in P of | |p - c| - R |,
// and on each piece that maximum is exact: |p - c| is convex along a line
// (its largest value at an end, its smallest at the foot of c, clamped),
// and along an arc of centre q it is extreme at its ends or where the ray
// from c through q meets it. A fitted line works the same way with
// projections on its direction in place of angles about c, and the
// distance to the line in place of | |p - c| - R |. A biarc is split where
// P crosses the common normal at its joint (the line through both centres),
// each half checked against its arc.
//
// Where the path runs on smoothly (its pieces' tangents agree) the fitted
// arcs keep its tangent; where it has a slight kink (a digitised point, a
// chord's end) the arcs meet with the tangent of the circle through that
// point and its neighbours. A stretch's first and last tangents are the
// path's own, so the fit joins the rest of the path as the path did.

#include <cstddef>
#include <vector>

#include "geometry/toolpath/path_piece.h"

namespace fabmesh {

struct ArcFitOptions {
  /// Largest distance (Frechet, so either way) between the fitted path and
  /// the path it replaces, > 0.
  double tolerance = 0.0025;
  /// Arcs of a larger radius are not fitted (a stretch that straight is left
  /// as its lines): controllers lose precision on far-away centres, > 0.
  double max_radius = 1e5;
  /// The tool's arcs round convex corners that turn at most this (radians)
  /// belong to a stretch (a digitised point); larger ones are corners.
  double max_corner_turn = 10.0 * 3.14159265358979323846 / 180.0;
};

struct ArcFitResult {
  std::vector<PathPiece> pieces;  ///< same ends, the fitted stretches replaced
  std::size_t replaced = 0;       ///< pieces of the path the fitted arcs replaced
  std::size_t arcs = 0;           ///< arcs fitted in their place
  std::size_t lines = 0;          ///< straight pieces fitted in their place (exactly straight stretches)
  double deviation = 0.0;         ///< proven: the largest distance between a fit and what it replaced
};

/// Fits the stretches of `path` (a chain of pieces, each starting where the
/// previous ends; closed or not: the first piece's start and the last's end
/// stay) made of offset lines and the tool's slight corner arcs. Exact arcs
/// (offsets of circle arcs, corner arcs of real corners), dog-bones and
/// links are kept as they are. A stretch is replaced only where that takes
/// fewer pieces.
ArcFitResult fit_arcs(const std::vector<PathPiece>& path, const ArcFitOptions& options);

/// The proven Frechet bound between one fitted piece (a line or an arc no
/// larger than a half turn) and a chain of pieces with the same ends, or
/// infinity when the chain does not move monotonically along it (above).
double fit_deviation(const PathPiece& fitted, const std::vector<PathPiece>& chain);

}  // namespace fabmesh
