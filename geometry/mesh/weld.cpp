#include "geometry/mesh/weld.h"

#include <fmt/format.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <unordered_map>

#include "geometry/core/errors.h"

namespace fabmesh {
namespace {

bool finite(const Vec3& p) { return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()); }

/// representative[i] = the lowest index of the group vertex i merges into.
std::vector<std::uint32_t> exact_groups(const std::vector<Vec3>& vertices) {
  const auto n = static_cast<std::uint32_t>(vertices.size());
  std::vector<std::uint32_t> order;
  order.reserve(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    if (finite(vertices[i])) order.push_back(i);  // NaN would break the strict weak order
  }
  // Adding 0.0 turns -0.0 into +0.0 so that equal coordinates compare equal.
  auto key = [&](std::uint32_t i) {
    const Vec3& p = vertices[i];
    return std::array<double, 3>{p.x() + 0.0, p.y() + 0.0, p.z() + 0.0};
  };
  tbb::parallel_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    const auto ka = key(a);
    const auto kb = key(b);
    return ka != kb ? ka < kb : a < b;
  });
  std::vector<std::uint32_t> rep(n);
  std::iota(rep.begin(), rep.end(), 0u);
  for (std::size_t k = 1; k < order.size(); ++k) {
    if (key(order[k]) == key(order[k - 1])) rep[order[k]] = rep[order[k - 1]];
  }
  return rep;
}

std::uint32_t find_root(std::vector<std::uint32_t>& parent, std::uint32_t i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

/// Union-find over a uniform grid of cell size `tol`: each vertex is compared
/// with the vertices already placed in its 27 neighbouring cells.
std::vector<std::uint32_t> tolerance_groups(const std::vector<Vec3>& vertices, double tol) {
  const auto n = static_cast<std::uint32_t>(vertices.size());
  std::vector<std::uint32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0u);
  struct CellHash {
    std::size_t operator()(const std::array<std::int64_t, 3>& c) const {
      return static_cast<std::size_t>(c[0] * 73856093LL ^ c[1] * 19349663LL ^ c[2] * 83492791LL);
    }
  };
  std::unordered_map<std::array<std::int64_t, 3>, std::vector<std::uint32_t>, CellHash> grid;
  grid.reserve(n);
  const double limit = 1e15;  // cell coordinates must stay exact in int64 and double
  for (std::uint32_t i = 0; i < n; ++i) {
    const Vec3& p = vertices[i];
    if (!finite(p)) continue;
    std::array<std::int64_t, 3> cell{};
    for (int a = 0; a < 3; ++a) {
      const double c = std::floor(p[a] / tol);
      if (std::abs(c) > limit) {
        throw RangeError("weld tolerance", tol,
                         fmt::format("weld tolerance = {} is too small for coordinate {}", tol, p[a]));
      }
      cell[a] = static_cast<std::int64_t>(c);
    }
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const auto it = grid.find({cell[0] + dx, cell[1] + dy, cell[2] + dz});
          if (it == grid.end()) continue;
          for (const std::uint32_t j : it->second) {
            if ((vertices[j] - p).norm() > tol) continue;
            const std::uint32_t ri = find_root(parent, i);
            const std::uint32_t rj = find_root(parent, j);
            if (ri != rj) parent[std::max(ri, rj)] = std::min(ri, rj);
          }
        }
      }
    }
    grid[cell].push_back(i);
  }
  for (std::uint32_t i = 0; i < n; ++i) parent[i] = find_root(parent, i);
  return parent;
}

}  // namespace

WeldResult weld(const TriangleSoup& soup, const WeldOptions& options) {
  if (options.tolerance != 0.0) require_positive("weld tolerance", options.tolerance);
  require_indices_in_range(soup);
  const std::vector<std::uint32_t> rep = options.tolerance > 0.0
                                             ? tolerance_groups(soup.vertices, options.tolerance)
                                             : exact_groups(soup.vertices);
  WeldResult result;
  const std::size_t n = soup.vertices.size();
  constexpr std::uint32_t kUnset = UINT32_MAX;
  std::vector<std::uint32_t> new_index(n, kUnset);
  // rep[i] <= i, so every representative is numbered before its members.
  for (std::size_t i = 0; i < n; ++i) {
    if (rep[i] == i) {
      new_index[i] = static_cast<std::uint32_t>(result.soup.vertices.size());
      result.soup.vertices.push_back(soup.vertices[i]);
    } else {
      new_index[i] = new_index[rep[i]];
    }
  }
  result.soup.triangles.reserve(soup.triangles.size());
  for (const auto& t : soup.triangles) {
    result.soup.triangles.push_back({new_index[t[0]], new_index[t[1]], new_index[t[2]]});
  }
  result.merged_vertices = n - result.soup.vertices.size();
  return result;
}

}  // namespace fabmesh
