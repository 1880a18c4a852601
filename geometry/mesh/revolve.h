#pragma once
// Surfaces of revolution: a section in the (radius, height) half-plane
// revolved about the height (z) axis into a closed triangle mesh.

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/core/proofs.h"
#include "geometry/core/soup.h"
#include "geometry/core/types.h"

namespace fabmesh {

struct RevolveOptions {
  int segments = 64;  ///< angular segments over 360 degrees (>= 3)
};

/// The fewest angular segments whose chord sagitta at radius `max_radius`
/// is at most `tolerance`: R (1 - cos(pi / n)) <= tolerance, n >= 3.
/// \throw RangeError for tolerance <= 0.
int angular_segments(double max_radius, double tolerance);

/// The angle of one of `segments` uniform angular steps: 2 pi / segments.
inline double angular_step(int segments) { return 2.0 * M_PI / segments; }

/// The sagitta of a chord over angle `step` of a circle of radius `radius`:
/// radius (1 - cos(step / 2)), how far the chord is from its arc at most.
inline double chord_sagitta(double radius, double step) { return radius * (1.0 - std::cos(0.5 * step)); }

/// Triangles one angular step of the revolution of `loop` has: two per loop
/// edge, one when an end is on the axis, none along the axis.
std::size_t revolved_triangles_per_step(const std::vector<Vec2>& loop);

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

/// Where revolve puts one loop's vertices: loop vertex by loop vertex, a
/// vertex on the axis (x == 0) as one pole, any other as a ring of `ring`
/// vertices, one per angular sample (sample 0 first).
struct LoopGrid {
  std::vector<std::uint32_t> first;  ///< per loop vertex: its pole or its sample-0 vertex
  std::vector<char> on_axis;         ///< per loop vertex: nonzero when x == 0
  std::size_t ring = 0;              ///< vertices of a ring

  /// The vertex of loop vertex `i` at angular sample `j` (mod ring; a pole at every j).
  std::uint32_t at(std::size_t i, std::size_t j) const {
    return on_axis[i] ? first[i] : first[i] + static_cast<std::uint32_t>(j % ring);
  }
};

/// Appends the vertices of `loop` to `vertices` in revolve's layout: a pole
/// at (0, 0, y), ring vertex (i, j) at position(i, j) (a Vec3).
template <class Position>
LoopGrid append_loop_grid(const std::vector<Vec2>& loop, std::size_t ring, std::vector<Vec3>& vertices,
                          Position&& position) {
  LoopGrid grid;
  grid.ring = ring;
  grid.first.resize(loop.size());
  grid.on_axis.resize(loop.size());
  for (std::size_t i = 0; i < loop.size(); ++i) {
    grid.on_axis[i] = static_cast<char>(loop[i].x() == 0.0 ? 1 : 0);
    grid.first[i] = static_cast<std::uint32_t>(vertices.size());
    if (grid.on_axis[i]) {
      vertices.emplace_back(0.0, 0.0, loop[i].y());
      continue;
    }
    for (std::size_t j = 0; j < ring; ++j) vertices.push_back(position(i, j));
  }
  return grid;
}

/// revolve's triangles of `grid`: loop edge by loop edge (an edge along the
/// axis has none), angular steps j = 0 .. steps - 1 from sample j to j + 1
/// (mod ring), face(c0, c1, c2) as for_each_edge_face calls it; the edge
/// from loop vertex `skipped` (if any) to the next gets none.
template <class Face>
void for_each_grid_face(const LoopGrid& grid, std::size_t steps, Face&& face,
                        std::size_t skipped = static_cast<std::size_t>(-1)) {
  const std::size_t n = grid.first.size();
  for (std::size_t a = 0; a < n; ++a) {
    const std::size_t b = (a + 1) % n;
    if ((grid.on_axis[a] && grid.on_axis[b]) || a == skipped) continue;
    for (std::size_t j = 0; j < steps; ++j) {
      for_each_edge_face(
          grid.on_axis[a] != 0, grid.on_axis[b] != 0, j,
          [&](bool is_b, std::size_t step) { return grid.at(is_b ? b : a, step); }, face);
    }
  }
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
