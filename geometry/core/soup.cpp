#include "geometry/core/soup.h"

#include <fmt/format.h>

#include "geometry/core/errors.h"

namespace fabmesh {

void require_indices_in_range(const TriangleSoup& soup) {
  const std::size_t n = soup.vertices.size();
  for (std::size_t f = 0; f < soup.triangles.size(); ++f) {
    for (const std::uint32_t i : soup.triangles[f]) {
      if (i >= n) {
        throw InputError(
            fmt::format("triangle {} refers to vertex {} but the soup has {} vertices", f, i, n));
      }
    }
  }
}

}  // namespace fabmesh
