#pragma once
// Meshes for the benchmark kernels, built in code: a torus revolved by the
// vessel builder's revolve(), as an indexed soup, a halfedge mesh, and an
// STL-style soup (three float-rounded vertices per triangle).

#include <cmath>
#include <cstddef>
#include <vector>

#include "geometry/mesh/halfedge_mesh.h"
#include "geometry/mesh/revolve.h"
#include "io/mesh/stl.h"

namespace fabmesh::bench {

/// The section of a torus: a circle of `points` points, radius 1, centred 3
/// from the axis (revolved with `segments` steps: 2 * points * segments triangles).
inline std::vector<std::vector<Vec2>> torus_section(int points) {
  std::vector<Vec2> loop;
  const double pi = std::acos(-1.0);
  for (int i = 0; i < points; ++i) {
    const double t = 2 * pi * i / points;
    loop.emplace_back(3.0 + std::cos(t), std::sin(t));
  }
  return {loop};
}

/// Section points and angular segments for about `triangles` triangles (segments = 2 * points).
inline int torus_points(std::size_t triangles) {
  return static_cast<int>(std::lround(std::sqrt(static_cast<double>(triangles) / 4.0)));
}

/// A revolved torus of about `triangles` triangles as an indexed soup.
inline TriangleSoup torus_soup(std::size_t triangles) {
  const int k = torus_points(triangles);
  return revolve(torus_section(k), RevolveOptions{2 * k}).soup;
}

/// The same torus as a halfedge mesh.
inline Mesh torus_mesh(std::size_t triangles) { return to_mesh(torus_soup(triangles)).mesh; }

/// The same torus as an STL file holds it: three float-rounded vertices per triangle.
inline TriangleSoup torus_stl_soup(std::size_t triangles) {
  return parse_stl(encode_stl(torus_soup(triangles)), "torus.stl");
}

}  // namespace fabmesh::bench
