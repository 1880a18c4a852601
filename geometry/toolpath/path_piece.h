#pragma once
// The pieces a tool-centre path is made of: straight lines and circular arcs
// in the plane, each knowing where it comes from.

#include <cstddef>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "geometry/core/types.h"

namespace fabmesh {

enum class PieceKind { Line, Arc };

/// Where a piece of a loop's path comes from.
enum class PieceRole {
  Offset,   ///< the offset of a curve segment (exact line or arc, or a chord of a chain)
  Corner,   ///< the arc of the tool radius around a convex corner
  Dogbone,  ///< the run into a concave corner and back (relief: dogbone)
  Link,     ///< a joining piece (lead-in and lead-out arcs)
};

const char* to_string(PieceRole role);

/// A line or a circular arc from `from` to `to`. An arc turns about `center`
/// by `sweep` radians (positive: counter-clockwise); |sweep| <= 2 pi.
struct PathPiece {
  PieceKind kind = PieceKind::Line;
  Vec2 from{0.0, 0.0};
  Vec2 to{0.0, 0.0};
  Vec2 center{0.0, 0.0};  ///< arcs only
  double sweep = 0.0;     ///< arcs only, radians
  PieceRole role = PieceRole::Offset;
  std::size_t segment = 0;  ///< the curve segment (Offset) or the segment after the joint (Corner, Dogbone)
  /// Smallest radius of curvature of the path along this piece (an estimate
  /// from its end points for chords of a chain; infinity for exact lines).
  double radius_of_curvature = std::numeric_limits<double>::infinity();
};

/// A straight piece.
PathPiece line_piece(const Vec2& from, const Vec2& to, PieceRole role, std::size_t segment);
/// An arc about `center` from `from` turning by `sweep` radians; `to` is computed.
PathPiece arc_piece(const Vec2& center, const Vec2& from, double sweep, PieceRole role, std::size_t segment);

/// Radius of an arc (distance of its start from the centre).
double piece_radius(const PathPiece& p);
/// Length of a piece.
double piece_length(const PathPiece& p);
/// Point at distance `u` in [0, piece_length] from the start.
Vec2 piece_point(const PathPiece& p, double u);
/// Unit direction of travel at distance `u`.
Vec2 piece_tangent(const PathPiece& p, double u);
/// The piece split at distance `u` in (0, length): {before, after}.
std::pair<PathPiece, PathPiece> split_piece(const PathPiece& p, double u);
/// The same piece run backwards.
PathPiece reversed(const PathPiece& p);
/// The piece as a polyline (points, first = from, last = to) whose chords stay
/// within `sagitta` of the arc (lines: their two ends). \pre sagitta > 0
std::vector<Vec2> piece_polyline(const PathPiece& p, double sagitta);

/// Where two pieces cross: distances along each from its start.
struct PieceCrossing {
  double u_first = 0.0;
  double u_second = 0.0;
  Vec2 where{0.0, 0.0};
};

/// All crossings of two pieces (lines and arcs, up to two), in no particular order.
std::vector<PieceCrossing> piece_crossings(const PathPiece& a, const PathPiece& b);

/// Total length of a chain of pieces.
double path_length(const std::vector<PathPiece>& pieces);

}  // namespace fabmesh
