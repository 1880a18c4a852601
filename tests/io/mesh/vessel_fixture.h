#pragma once
// The golden vessel (configs/examples/vessel_golden_shell.yaml, in cm) built
// through the geometry API: a closed, outward shell mesh for the format tests.

#include "geometry/core/soup.h"
#include "geometry/curves/curve_spec.h"
#include "geometry/mesh/vessel.h"

namespace fabmesh::test {

/// The golden vessel shell: 3 mm wall, 4 mm base, the profile of docs/math/curves.md 2.
/// Model units: cm. \param tolerance cm
inline TriangleSoup golden_vessel_cm(double tolerance = 0.005) {
  CurveSpec spec;
  spec.family = CurveFamily::QuasiBSpline;
  spec.bspline_points = {{1.5, 6}, {1, 5}, {2, 4}, {3, 3}, {1.5, 2}};
  VesselOptions options;
  options.mode = BodyMode::Shell;
  options.wall = 0.3;
  options.base = 0.4;
  options.tolerance = tolerance;
  return build_vessel(construct_curve(spec), options).soup;
}

/// `soup` with every vertex multiplied by `factor`.
inline TriangleSoup scaled(TriangleSoup soup, double factor) {
  for (Vec3& p : soup.vertices) p *= factor;
  return soup;
}

/// Lowest and highest corner of the bounding box of `soup`'s vertices.
inline std::pair<Vec3, Vec3> bounds(const TriangleSoup& soup) {
  Vec3 lo = soup.vertices.front();
  Vec3 hi = lo;
  for (const Vec3& p : soup.vertices) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return {lo, hi};
}

}  // namespace fabmesh::test
