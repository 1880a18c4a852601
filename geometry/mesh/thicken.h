#pragma once
// Thickening an open surface mesh into a closed solid shell for fabrication.

#include <cstddef>
#include <vector>

#include "geometry/core/limits.h"
#include "geometry/core/types.h"

namespace fabmesh {

struct ThickenOptions {
  /// Distance of the second sheet along the vertex normals, model units (> 0).
  double thickness = 1.0;
  std::size_t max_triangles = kDefaultMaxTriangles;  ///< budget for the shell; more is a BudgetError
};

/// Triangles of the shell over `sheet`: both sheets and two per boundary edge.
std::size_t thickened_triangle_count(const Mesh& sheet);

/// The shell between `sheet` and its offset p + thickness n(p): the offset
/// sheet keeps the sheet's orientation, the sheet itself is reversed, and
/// each boundary edge gets a side-wall quad (two triangles) sharing the
/// vertices of both sheets. With `vertex_normals` the unit normals the
/// sheet's faces turn counter-clockwise about (one per sheet vertex), the
/// solid is closed and oriented outward. Whether the offset sheet folds or
/// meets the rest (thickness beyond a radius of curvature) is not decided
/// here: validate the result with the self-intersection test.
/// \throw RangeError (thickness <= 0 or not finite, a normal count that does
///        not match), BudgetError (over max_triangles), GeometryError (a sheet
///        that is not manifold at its border)
Mesh thicken(const Mesh& sheet, const std::vector<Vec3>& vertex_normals, const ThickenOptions& options);

}  // namespace fabmesh
