#pragma once
// Patch networks built in code for the surface, tessellation and thickening tests.

#include <array>
#include <vector>

#include "geometry/surfaces/patch_network.h"

namespace fabmesh::test {

/// A square dish of half-width w and depth d from a 7 x 7 control net (rim
/// at z = 0, normals pointing out of the bowl; `wall` places the second
/// control line, 2/3 for an even net, near 1 for steep walls), as four
/// patches: 'a' explicit, 'b' joined to a along u_max, 'c' to a along v_max
/// and 'd' to b along v_max, all G1 with gamma = 1; d meets c along an
/// undeclared border.
inline std::vector<PatchSpec> basin_specs(double w = 2.0, double d = 1.5, double wall = 0.95) {
  const std::array<double, 7> x{-w, -wall * w, -0.5 * w, 0.0, 0.5 * w, wall * w, w};
  const std::array<double, 7> c{0.0, 0.9, 1.0, 1.0, 1.0, 0.9, 0.0};
  auto net = [&](std::size_t i, std::size_t j) { return Vec3(x[j], x[i], -d * c[i] * c[j]); };
  auto row = [&](std::size_t i, std::size_t j0) {
    return std::array<Vec3, 4>{net(i, j0), net(i, j0 + 1), net(i, j0 + 2), net(i, j0 + 3)};
  };
  auto column = [&](std::size_t j, std::size_t i0) {
    return std::array<Vec3, 4>{net(i0, j), net(i0 + 1, j), net(i0 + 2, j), net(i0 + 3, j)};
  };
  PatchSpec a;
  a.name = "a";
  a.points = {row(0, 0), row(1, 0), row(2, 0), row(3, 0)};
  PatchSpec b;
  b.name = "b";
  b.join = PatchJoin{0, PatchSide::UMax, Continuity::G1, 1.0, 1.0, 0.0};
  b.points = {row(5, 0), row(6, 0)};
  PatchSpec pc;
  pc.name = "c";
  pc.join = PatchJoin{0, PatchSide::VMax, Continuity::G1, 1.0, 1.0, 0.0};
  pc.points = {column(5, 0), column(6, 0)};
  PatchSpec pd;
  pd.name = "d";
  pd.join = PatchJoin{1, PatchSide::VMax, Continuity::G1, 1.0, 1.0, 0.0};
  pd.points = {column(5, 3), column(6, 3)};
  return {a, b, pc, pd};
}

/// One patch close to a half cylinder of radius r about the y axis (x in
/// [-r, r], z >= 0, length l), normals pointing towards the axis.
inline std::vector<PatchSpec> half_cylinder_specs(double r = 1.0, double l = 2.0) {
  const double k = 4.0 / 3.0 * r;  // cubic Bézier-like handles; any bulge will do
  const std::array<Vec3, 4> profile{Vec3(r, 0, 0), Vec3(r, 0, k), Vec3(-r, 0, k), Vec3(-r, 0, 0)};
  PatchSpec p;
  p.name = "half_cylinder";
  for (std::size_t i = 0; i < 4; ++i) {
    std::array<Vec3, 4> line;
    for (std::size_t j = 0; j < 4; ++j) line[j] = profile[i] + Vec3(0, l * static_cast<double>(j) / 3.0, 0);
    p.points.push_back(line);
  }
  return {p};
}

}  // namespace fabmesh::test
