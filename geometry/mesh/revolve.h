#pragma once
// Surfaces of revolution: a section in the (radius, height) half-plane
// revolved about the height (z) axis into a closed triangle mesh.

#include <cstddef>
#include <vector>

#include "geometry/core/types.h"

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

/// Revolves closed counter-clockwise loops (x = radius >= 0, y = height)
/// about the z axis, one closed component per loop. Each vertex with x == 0 becomes one pole vertex; edges
/// along the axis produce no faces. The result is watertight with outward
/// normals when the loop meets the axis only along axis edges; every
/// angular slice of it is a uniformly scaled copy of the loop.
/// \throw RangeError for segments < 3 or a negative radius; GeometryError
///        for an axis vertex that is not the end of exactly one axis edge.
Mesh revolve(const std::vector<std::vector<Vec2>>& loops, const RevolveOptions& options);

}  // namespace fabmesh
