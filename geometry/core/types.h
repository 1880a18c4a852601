#pragma once
// Plain value types shared by every geometry stage.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace fabmesh {

using Vec2 = Eigen::Vector2d;  ///< a point or vector in the plane, model units
using Vec3 = Eigen::Vector3d;  ///< a point or vector in space, model units

/// 2D cross product (z component of the 3D cross product).
inline double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// A sampled curve: points in order; `closed` means the last point connects
/// back to the first (the first point is not repeated).
struct Polyline2 {
  std::vector<Vec2> points;
  bool closed = false;
  /// Proven upper bound on the distance between this polyline and the exact
  /// curve it samples (both ways), model units.
  double max_deviation = 0.0;
};

}  // namespace fabmesh
