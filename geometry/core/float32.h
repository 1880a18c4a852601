#pragma once
// Rounding to float32, as the files that store float32 coordinates (STL,
// PLY, GLB, Draco's decoded positions) hold a vertex.

#include "geometry/core/types.h"

namespace fabmesh {

/// x rounded to the nearest float32 (ties to even), as a double. The float
/// passes through a volatile: GCC 12 at -O2 vectorizes two adjacent
/// double -> float -> double round trips into the identity (found on the
/// coordinates of a point), so the rounding must stay scalar.
inline double rounded_to_float32(double x) {
  volatile float f = static_cast<float>(x);
  return f;
}

/// Each coordinate of `p` rounded to the nearest float32.
inline Vec3 rounded_to_float32(const Vec3& p) {
  return {rounded_to_float32(p.x()), rounded_to_float32(p.y()), rounded_to_float32(p.z())};
}

}  // namespace fabmesh
