#pragma once
// Profiles and options shared by the mould tests.

#include <string>
#include <vector>

#include "geometry/curves/composite.h"
#include "geometry/fairing/build_curve.h"
#include "geometry/mould/mould.h"
#include "io/design/read_design.h"
#include "tests/geometry/mesh/point_triangle.h"

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

}  // namespace fabmesh::test
