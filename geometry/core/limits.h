#pragma once
// Work budgets shared by every builder and reader.

#include <cstddef>

namespace fabmesh {

/// Default budget of triangles one design may produce (design key `max_triangles`).
inline constexpr std::size_t kDefaultMaxTriangles = 20'000'000;

/// Largest `max_triangles` a design may ask for.
inline constexpr double kMaxTrianglesLimit = 2e9;

/// Default budget of sampled curve points (a curve alone: `fabmesh sample`).
inline constexpr std::size_t kDefaultMaxPoints = 5'000'000;

}  // namespace fabmesh
