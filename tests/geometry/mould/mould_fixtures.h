#pragma once
// Profiles and options shared by the mould tests.

#include <string>
#include <vector>

#include "geometry/curves/build_curve.h"
#include "geometry/curves/composite.h"
#include "geometry/mould/mould.h"
#include "io/design/read_design.h"

namespace fabmesh::test {

inline std::string example_path(const std::string& name) {
  return std::string(FABMESH_SOURCE_DIR) + "/configs/examples/" + name;
}

/// The profile of a vessel example (read with read_design, built with build_curve).
inline CompositeCurve example_profile(const std::string& name) {
  const Design d = read_design(example_path(name));
  return build_curve(std::get<VesselDesign>(d.body).profile).curve;
}

/// Mould options for the cm-unit examples: 30 mm wall, 25 mm spare, 6 mm keys with 0.2 mm clearance.
inline MouldOptions cm_options() {
  MouldOptions o;
  o.wall = 3.0;
  o.spare = 2.5;
  o.keys = 4;
  o.key_radius = 0.6;
  o.key_clearance = 0.02;
  o.shrinkage = 0.12;
  o.tolerance = 0.005;
  return o;
}

/// An open polyline profile of straight segments (base end first or last).
inline CompositeCurve polyline_profile(const std::vector<Vec2>& pts) {
  std::vector<Segment> segs;
  for (std::size_t i = 0; i + 1 < pts.size(); ++i) segs.push_back(Segment::line(pts[i], pts[i + 1]));
  return CompositeCurve(segs, false);
}

/// Distance from p to triangle abc (Ericson, Real-Time Collision Detection 5.1.5).
inline double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return (p - a).norm();
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return (p - b).norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return (p - c).norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  const double denom = 1 / (va + vb + vc);
  return (p - (a + ab * vb * denom + ac * vc * denom)).norm();
}

}  // namespace fabmesh::test
