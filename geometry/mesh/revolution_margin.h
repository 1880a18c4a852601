#pragma once
// How far the vertices of a revolution may move before it can stop being
// embedded: the margin that lets a moved copy (a quantized Draco mesh, float32
// coordinates) be proven free of self-intersections without a 3D test.

#include <vector>

#include "geometry/core/types.h"

namespace fabmesh {

/// A margin m > 0 such that moving every vertex of revolve(loops, {segments})
/// by less than m leaves it free of self-intersections (as find_self_intersections
/// defines them) and of degenerate faces, or 0 when none is proven. `loops` must revolve into an
/// embedded mesh (a simple section): the margin is about how far that mesh
/// is from meeting itself, not a test of it.
///
/// Why it holds. When every vertex moves by at most d, every point of a face
/// (a convex combination of its corners) moves by at most d, so two faces can
/// meet after the move only where their original point sets, or the features
/// whose contact decides their intersection, were within 2d:
/// - faces sharing no vertex meet only if they touch;
/// - faces sharing one vertex only if the edge opposite it in one touches the other;
/// - faces sharing an edge (u, v), apexes a and b, only if they become
///   coplanar and fold: then b touches face (u, v, a), or a face (v, u, b),
///   or segment ub touches segment va, or ua touches vb.
/// The pairs are bounded in three classes; the margin is half the least bound,
/// less what rounding the vertices' angles can move them:
/// - from section edges that share no section vertex: the map of a point to
///   (distance from the axis, height) is 1-Lipschitz and sends a face of loop
///   edge e within the sagitta r_max (1 - cos(pi / n)) of e, so such faces are
///   at least their edges' 2D distance less two sagittas apart;
/// - from the same or neighbouring section edges, two or more angular steps
///   apart: a face lies in its step's wedge, wedges are 2 pi / n apart, so
///   faces (or, sharing a pole, an opposite edge and a face) whose points stay
///   at least rho from the axis are rho sin(min(2 pi / n, pi / 2)) apart, with
///   rho = cos(pi / n) times the least off-axis section radius;
/// - from the same or neighbouring section edges, at most one step apart:
///   every such pair of angular step 0 is bounded directly (separating axes
///   of the deciding features, with rounding bounds); the revolution repeats
///   it at every step.
/// - every face keeps its corners apart from the opposite sides: the least
///   altitude of the faces of step 0 (the others are their rotations).
/// A section vertex between two poles (a double cone) gets 0: its two fans
/// approach the axis together and the wedge bound does not hold.
double revolution_margin(const std::vector<std::vector<Vec2>>& loops, int segments);

}  // namespace fabmesh
