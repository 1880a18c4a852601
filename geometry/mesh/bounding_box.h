#pragma once
// The axis-aligned bounding box of a point set (builder facts, size checks).

#include <limits>
#include <vector>

#include "geometry/core/types.h"

namespace fabmesh {

/// Smallest and largest coordinates of a point set, model units. Empty: lo =
/// +inf, hi = -inf.
struct BoundingBox {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = Vec3::Constant(-std::numeric_limits<double>::infinity());
  Vec3 size() const { return hi - lo; }
};

/// The bounding box of `points`.
inline BoundingBox bounding_box(const std::vector<Vec3>& points) {
  BoundingBox box;
  for (const Vec3& p : points) {
    box.lo = box.lo.cwiseMin(p);
    box.hi = box.hi.cwiseMax(p);
  }
  return box;
}

}  // namespace fabmesh
