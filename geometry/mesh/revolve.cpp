#include "geometry/mesh/revolve.h"

#include <fmt/format.h>

#include <cmath>

#include "geometry/core/errors.h"

namespace fabmesh {

int angular_segments(double max_radius, double tolerance) {
  require_positive("tolerance", tolerance);
  if (max_radius <= tolerance) return 3;
  const double half_angle = std::acos(1.0 - tolerance / max_radius);
  const double n = std::ceil(M_PI / half_angle);
  return static_cast<int>(std::max(3.0, std::min(n, 1e9)));
}

std::size_t revolved_triangle_count(const std::vector<std::vector<Vec2>>& loops, int segments) {
  std::size_t per_slice = 0;
  for (const auto& loop : loops) {
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const bool a = loop[i].x() == 0.0, b = loop[(i + 1) % loop.size()].x() == 0.0;
      per_slice += (a && b) ? 0 : (a || b) ? 1 : 2;
    }
  }
  return per_slice * static_cast<std::size_t>(segments);
}

namespace {

void revolve_loop(const std::vector<Vec2>& loop, const std::vector<double>& cs, const std::vector<double>& sn,
                  Mesh& mesh) {
  const std::size_t n = loop.size();
  const std::size_t m = cs.size();
  // first[i]: handle of ring i's vertex at angle 0 (its pole when on the axis).
  std::vector<Mesh::VertexHandle> first(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& p = loop[i];
    if (p.x() == 0.0) {
      first[i] = mesh.add_vertex(Mesh::Point(0.0, 0.0, p.y()));
      continue;
    }
    for (std::size_t j = 0; j < m; ++j) {
      const Mesh::VertexHandle v = mesh.add_vertex(Mesh::Point(p.x() * cs[j], p.x() * sn[j], p.y()));
      if (j == 0) first[i] = v;
    }
  }
  auto ring = [&](std::size_t i, std::size_t j) {
    if (loop[i].x() == 0.0) return first[i];
    return Mesh::VertexHandle(first[i].idx() + static_cast<int>(j % m));
  };
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k = (i + 1) % n;
    const bool a_axis = loop[i].x() == 0.0, b_axis = loop[k].x() == 0.0;
    if (a_axis && b_axis) continue;
    for (std::size_t j = 0; j < m; ++j) {
      // For a counter-clockwise loop, (a_j, a_j+1, b_j+1) and (a_j, b_j+1, b_j) face outward.
      if (!a_axis) mesh.add_face(ring(i, j), ring(i, j + 1), ring(k, j + 1));
      if (!b_axis) mesh.add_face(ring(i, j), ring(k, j + 1), ring(k, j));
    }
  }
}

}  // namespace

Mesh revolve(const std::vector<std::vector<Vec2>>& loops, const RevolveOptions& options) {
  if (options.segments < 3) {
    throw RangeError("segments", options.segments, fmt::format("segments = {} must be >= 3", options.segments));
  }
  const auto m = static_cast<std::size_t>(options.segments);
  std::vector<double> cs(m), sn(m);
  for (std::size_t j = 0; j < m; ++j) {
    const double theta = 2.0 * M_PI * static_cast<double>(j) / static_cast<double>(m);
    cs[j] = std::cos(theta);
    sn[j] = std::sin(theta);
  }
  std::size_t vertex_count = 0;
  for (const auto& loop : loops) {
    for (const Vec2& p : loop) {
      if (p.x() < 0.0) throw RangeError("radius", p.x(), fmt::format("loop vertex radius {} < 0", p.x()));
      vertex_count += p.x() == 0.0 ? 1 : m;
    }
  }
  const std::size_t faces = revolved_triangle_count(loops, options.segments);
  Mesh mesh;
  mesh.reserve(vertex_count, 3 * faces / 2, faces);
  for (const auto& loop : loops) revolve_loop(loop, cs, sn, mesh);
  return mesh;
}

}  // namespace fabmesh
