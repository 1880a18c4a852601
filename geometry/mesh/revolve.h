#pragma once
// Surfaces of revolution: a section in the (radius, height) half-plane
// revolved about the height (z) axis into a closed triangle mesh.

#include <cstddef>
#include <vector>

#include "geometry/core/types.h"
#include "geometry/mesh/soup.h"
#include "geometry/mesh/topology_proof.h"

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
