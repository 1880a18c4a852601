#pragma once
// The signed volume a triangle soup encloses (validation, a mould's plaster).

#include "geometry/core/soup.h"
#include "geometry/mesh/bounding_box.h"

namespace fabmesh {

/// The signed volume `soup` encloses, model units^3: exact for a closed
/// soup, positive when it is oriented outward. Taken about the centre of its
/// bounding box (less cancellation than about the origin). The volume
/// validate reports. \pre every index in range
inline double signed_volume(const TriangleSoup& soup) {
  const BoundingBox box = bounding_box(soup.vertices);
  const Vec3 centre = soup.vertices.empty() ? Vec3::Zero() : Vec3(0.5 * (box.lo + box.hi));
  double volume6 = 0.0;
  for (const auto& t : soup.triangles) {
    const Vec3& a = soup.vertices[t[0]];
    const Vec3& b = soup.vertices[t[1]];
    const Vec3& c = soup.vertices[t[2]];
    volume6 += (a - centre).dot((b - centre).cross(c - centre));
  }
  return volume6 / 6.0;
}

}  // namespace fabmesh
