#pragma once
// The tolerance weld's grouping (part of weld.cpp's implementation): the
// transitive closure of "within tolerance" over a soup's vertices.

#include <cstdint>
#include <vector>

#include "geometry/core/types.h"

namespace fabmesh {

/// rep[i] = the lowest index of the group of vertex i, where two finite
/// vertices are in one group when a chain of vertices links them with each
/// step's computed distance (vertices[j] - vertices[i]).norm() <= tol.
/// Non-finite vertices are alone (rep[i] = i).
/// \param exact  for each vertex, the lowest index at exactly its position
///        (the exact weld), which the grid starts from
/// \throw RangeError when tol is too small for a coordinate (|x| / tol > 1e15).
std::vector<std::uint32_t> tolerance_groups(const std::vector<Vec3>& vertices,
                                            const std::vector<std::uint32_t>& exact, double tol);

}  // namespace fabmesh
