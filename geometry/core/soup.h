#pragma once
// A triangle soup: the indexed, unchecked triangles of a file from elsewhere,
// and of every mesh a builder makes (what validation judges and writers write).

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/core/types.h"

namespace fabmesh {

/// Indexed triangles with no topological guarantee: edges may be shared by
/// any number of faces, vertices may repeat, faces may be degenerate.
/// Invariant expected by consumers (readers guarantee it): every index is
/// < vertices.size().
struct TriangleSoup {
  std::vector<Vec3> vertices;                           ///< model units
  std::vector<std::array<std::uint32_t, 3>> triangles;  ///< counter-clockwise seen from outside
};

/// Throws InputError unless every triangle index of `soup` is < vertices.size().
void require_indices_in_range(const TriangleSoup& soup);

}  // namespace fabmesh
