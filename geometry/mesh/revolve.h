#pragma once
// Surfaces of revolution: a section in the (radius, height) half-plane
// revolved about the height (z) axis into a closed triangle mesh.

#include <array>
#include <cstddef>
#include <vector>

#include "geometry/core/types.h"
#include "geometry/mesh/soup.h"
#include "geometry/validation/proofs.h"

namespace fabmesh {

struct RevolveOptions {
  int segments = 64;  ///< angular segments over 360 degrees (>= 3)
};

/// The fewest angular segments whose chord sagitta at radius `max_radius`
/// is at most `tolerance`: R (1 - cos(pi / n)) <= tolerance, n >= 3.
/// \throw RangeError for tolerance <= 0.
int angular_segments(double max_radius, double tolerance);

/// Triangles the revolution of `loops` has with `segments` angular segments.
std::size_t revolved_triangle_count(const std::vector<std::vector<Vec2>>& loops, int segments);

/// The unit direction (cos, sin) of revolve's angular step j of `segments`
/// (angle 2 pi j / segments). revolve computes its vertices with it, so what
/// reasons about them (revolution_margin) sees them bit for bit.
std::array<double, 2> revolve_direction(std::size_t j, int segments);

/// revolve's vertex of section point `p` (radius, height) in `direction`.
inline Vec3 revolved_point(const Vec2& p, const std::array<double, 2>& direction) {
  return {p.x() * direction[0], p.x() * direction[1], p.y()};
}

/// revolve's triangles of the loop edge from vertex a to vertex b at angular
/// step j: calls face(c0, c1, c2) for each, its corners made by
/// corner(is_b, step) with step j or j + 1 (a pole's step does not matter):
///   (a_{j+1}, b_{j+1}, a_j) when a is off the axis,
///   (b_{j+1}, b_j, a_j)     when b is off the axis,
/// counter-clockwise seen from outside for a counter-clockwise loop.
template <class Step, class Corner, class Face>
void for_each_edge_face(bool a_on_axis, bool b_on_axis, Step j, Corner&& corner, Face&& face) {
  if (!a_on_axis) face(corner(false, j + 1), corner(true, j + 1), corner(false, j));
  if (!b_on_axis) face(corner(true, j + 1), corner(true, j), corner(false, j));
}

/// Vertices the revolution of `loops` has with `segments` angular segments.
std::size_t revolved_vertex_count(const std::vector<std::vector<Vec2>>& loops, int segments);

/// A revolution: its triangles, and what their construction proves.
struct RevolvedSoup {
  TriangleSoup soup;
  /// The revolution grid's connectivity: every edge has exactly two faces
  /// traversing it in opposite directions, every vertex one fan. A loop that
  /// does not touch the axis gives a torus (Euler characteristic 0); a loop
  /// with k axis edges gives k spheres (2 each), one per arc between them.
  TopologyProof topology;
};

/// Revolves closed counter-clockwise loops (x = radius >= 0, y = height)
/// about the z axis. Each vertex with x == 0 becomes one pole vertex; edges
/// along the axis produce no faces. The result is closed, manifold and
/// consistently oriented by construction (`topology` states it), with
/// outward normals for counter-clockwise loops; every angular slice of it is
/// a uniformly scaled copy of the loop. Vertices come loop by loop, each
/// loop vertex as its pole or its ring of `segments` vertices (angle 0
/// first); triangles loop edge by loop edge, angular step by step.
/// \throw RangeError for segments < 3 or a negative radius; GeometryError
///        for an axis vertex that is not the end of exactly one axis edge;
///        BudgetError for more than 2^32 - 1 vertices.
RevolvedSoup revolve(const std::vector<std::vector<Vec2>>& loops, const RevolveOptions& options);

}  // namespace fabmesh
