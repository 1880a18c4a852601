#pragma once
// Whether a mould opens: which parts can be withdrawn from the cast piece.
//
// Side parts (split by half-planes through the axis, pulled horizontally).
// A pure horizontal translation moves every horizontal slice in its own
// plane, so a part releases iff each of its slices does. A part spanning the
// angles [a, b] (b - a <= pi) pulled along its bisector d: a slice of the
// cavity that is a disc of radius rho releases, since every point p of the
// part at that height has p.d >= 0, so |p + t d|^2 = |p|^2 + 2t p.d + t^2 >
// rho^2 for t > 0 (it never enters the disc). A slice that is not a disc
// (an annulus around a ring of plaster, where the profile folds back
// downward) traps that ring: the ring's point nearest the annulus on the
// pull's side enters the cast at once, for every direction. So the claim "a
// 2- or 3-part mould releases for any revolved cavity" is FALSE in general
// and true exactly when every horizontal slice of the cavity within the side
// parts is a disc: when the cavity's boundary, walked down from the opening,
// never rises (z non-increasing). Bellies and necks are fine; a rim curling
// down outside, a foot ring below the floor, a gallery are not.
//
// Base part (below a horizontal cut, pulled down; equivalently the cast is
// lifted off it). A vertical translation keeps r, so it releases iff every
// vertical line meets the cavity inside the base in one interval that
// reaches the cut plane: iff the cavity's boundary inside the base, walked
// from the cut toward the axis, never moves outward (r non-increasing):
// the cavity must not grow wider downward inside the base.
//
// Keys. A hemispherical bump of radius r in a socket of radius r_s pulled at
// an angle alpha from the socket's axis stays inside the socket sphere until
// it crosses the split plane, where its farthest point is r / cos(alpha)
// from the centre: it releases iff r_s cos(alpha) >= r. A side part is
// pulled along its bisector (the only direction giving both split planes the
// same angle; any release direction needs p.d >= 0 over its span), so
// alpha = pi/2 - pi/parts: 0 for 2 parts, 30 degrees for 3 parts (sockets at
// least 1.1547 r). The horizontal base cut carries no keys: a side part
// slides off it horizontally, alpha = 90 degrees, which no socket allows.

#include <string>
#include <vector>

#include "geometry/core/types.h"

namespace fabmesh {

enum class MouldPartKind { Side, Base };

/// A cavity boundary point where a part cannot be withdrawn.
struct Undercut {
  Vec2 point;  ///< (r, z), master size, model units
  MouldPartKind part = MouldPartKind::Side;
};

/// Points of `side_cavity` (walking down from the opening) lying in a fold:
/// a point below an earlier point or above a later one, where the slice is
/// not a disc. Then the points of `base_cavity` (walking from the cut toward
/// the axis) where the cavity widens downward: a point farther out than an
/// earlier one or nearer than a later one. Ties (horizontal or vertical runs)
/// release. O(n).
std::vector<Undercut> find_undercuts(const std::vector<Vec2>& side_cavity,
                                     const std::vector<Vec2>& base_cavity);

/// The angle between the pull of a side part of a `parts`-part mould and its
/// keys' axes: pi/2 - pi/parts (radians).
double key_pull_angle(int parts);

/// True when a bump of `key_radius` leaves its socket of `socket_radius`
/// pulled at key_pull_angle(parts): socket_radius cos(angle) >= key_radius.
bool keys_release(int parts, double key_radius, double socket_radius);

/// "the side parts cannot ... at (r 1, z 2), ...": one sentence per part kind
/// with up to `max_points` points each (and how many more), for messages.
std::string describe_undercuts(const std::vector<Undercut>& undercuts, std::size_t max_points = 6);

}  // namespace fabmesh
