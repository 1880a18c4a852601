#include "geometry/mesh/revolve.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "geometry/core/error_checks.h"

namespace fabmesh {

int angular_segments(double max_radius, double tolerance) {
  require_positive("tolerance", tolerance);
  if (max_radius <= tolerance) return 3;
  const double half_angle = std::acos(1.0 - tolerance / max_radius);
  const double n = std::ceil(M_PI / half_angle);
  return static_cast<int>(std::max(3.0, std::min(n, 1e9)));
}

std::size_t revolved_triangles_per_step(const std::vector<Vec2>& loop) {
  std::size_t count = 0;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const bool a = loop[i].x() == 0.0, b = loop[(i + 1) % loop.size()].x() == 0.0;
    count += (a && b) ? 0 : (a || b) ? 1 : 2;
  }
  return count;
}

std::size_t revolved_triangle_count(const std::vector<std::vector<Vec2>>& loops, int segments) {
  std::size_t per_slice = 0;
  for (const auto& loop : loops) per_slice += revolved_triangles_per_step(loop);
  return per_slice * static_cast<std::size_t>(segments);
}

std::array<double, 2> revolve_direction(std::size_t j, int segments) {
  const double theta = 2.0 * M_PI * static_cast<double>(j) / static_cast<double>(segments);
  return {std::cos(theta), std::sin(theta)};
}

std::size_t revolved_vertex_count(const std::vector<std::vector<Vec2>>& loops, int segments) {
  std::size_t count = 0;
  for (const auto& loop : loops) {
    for (const Vec2& p : loop) count += p.x() == 0.0 ? 1 : static_cast<std::size_t>(segments);
  }
  return count;
}

namespace {

// Every axis vertex needs exactly one neighbour on the axis: then it is the
// apex of one fan, and axis edges (which make no faces) never chain.
void require_axis_contacts_along_edges(const std::vector<Vec2>& loop) {
  const std::size_t n = loop.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (loop[i].x() != 0.0) continue;
    const int neighbours = (loop[(i + n - 1) % n].x() == 0.0) + (loop[(i + 1) % n].x() == 0.0);
    if (neighbours != 1) {
      throw GeometryError("section",
                          fmt::format("section vertex (r 0, z {}) is on the axis with {} axis neighbours; "
                                      "a loop may meet the axis only along single axis edges",
                                      loop[i].y(), neighbours));
    }
  }
}

// The faces of one revolved loop, by index arithmetic on the revolution grid.
// Vertex (i, j) is loop vertex i at angle step j (j mod m), or i's pole.
// Faces of loop edge e = (a, b) at step j (for_each_edge_face; counter-clockwise
// loop, outward normals): T1 = a_j a_{j+1} b_{j+1} when a is off the axis,
// T2 = a_j b_{j+1} b_j when b is off the axis.
// Each grid edge then has exactly two faces, which traverse it in opposite
// directions: ring edge a_j a_{j+1} has T1 of the edge leaving a and T2 of the
// edge arriving at a; meridian a_j b_j has T2 of step j and T1 of step j - 1;
// diagonal a_j b_{j+1} has T1 and T2 of the same step. Around a ring vertex
// the faces of the two loop edges at it form one disc; around a pole, the
// m faces of its one off-axis loop edge form one fan.
void revolve_loop(const std::vector<Vec2>& loop, const std::vector<std::array<double, 2>>& directions,
                  TriangleSoup& out) {
  const LoopGrid grid =
      append_loop_grid(loop, directions.size(), out.vertices,
                       [&](std::size_t i, std::size_t j) { return revolved_point(loop[i], directions[j]); });
  for_each_grid_face(grid, directions.size(), [&](std::uint32_t c0, std::uint32_t c1, std::uint32_t c2) {
    out.triangles.push_back({c0, c1, c2});
  });
}

// The components of one loop's revolution and their Euler characteristics,
// appended in order of their lowest vertex. Without axis vertices the loop sweeps a torus (V = E - F = n m,
// chi 0). Otherwise every axis edge is a seam that makes no faces, so each
// arc between two axis edges sweeps its own sphere: k ring vertices and two
// poles give V = k m + 2, F = 2 m k, E = 3 m k, chi 2.
void loop_components(const std::vector<Vec2>& loop, TopologyProof& proof) {
  const std::size_t n = loop.size();
  std::size_t axis_edges = 0;
  for (std::size_t i = 0; i < n; ++i) axis_edges += loop[i].x() == 0.0 && loop[(i + 1) % n].x() == 0.0;
  proof.components += axis_edges == 0 ? 1 : axis_edges;
  // Vertices are numbered in loop order, so ordering by lowest vertex is
  // ordering by lowest loop index, which every component has the same chi.
  proof.euler_characteristics.insert(proof.euler_characteristics.end(), axis_edges == 0 ? 1 : axis_edges,
                                     axis_edges == 0 ? 0L : 2L);
}

}  // namespace

RevolvedSoup revolve(const std::vector<std::vector<Vec2>>& loops, const RevolveOptions& options) {
  if (options.segments < 3) {
    throw RangeError("segments", options.segments,
                     fmt::format("segments = {} must be >= 3", options.segments));
  }
  const auto m = static_cast<std::size_t>(options.segments);
  std::vector<std::array<double, 2>> directions(m);
  for (std::size_t j = 0; j < m; ++j) directions[j] = revolve_direction(j, options.segments);
  for (const auto& loop : loops) {
    require_axis_contacts_along_edges(loop);
    for (const Vec2& p : loop) {
      if (p.x() < 0.0) throw RangeError("radius", p.x(), fmt::format("loop vertex radius {} < 0", p.x()));
    }
  }
  const std::size_t vertex_count = revolved_vertex_count(loops, options.segments);
  constexpr std::size_t kMaxVertices = std::numeric_limits<std::uint32_t>::max();
  if (vertex_count > kMaxVertices) {
    throw BudgetError(static_cast<double>(vertex_count), static_cast<double>(kMaxVertices),
                      fmt::format("the mesh needs {} vertices, more than the {} 32-bit indices can number "
                                  "(lower max_triangles or raise the tolerance)",
                                  vertex_count, kMaxVertices));
  }
  const std::size_t faces = revolved_triangle_count(loops, options.segments);
  RevolvedSoup out;
  out.soup.vertices.reserve(vertex_count);
  out.soup.triangles.reserve(faces);
  for (const auto& loop : loops) {
    revolve_loop(loop, directions, out.soup);
    loop_components(loop, out.topology);
  }
  if (out.soup.vertices.size() != vertex_count || out.soup.triangles.size() != faces) {
    throw std::logic_error("revolve: element counts disagree with the revolution grid");
  }
  out.topology.statement = fmt::format(
      "closed, manifold and consistently oriented by construction: a revolution grid of {} angular steps "
      "whose every edge has one face on each side, traversed in opposite directions",
      m);
  return out;
}

}  // namespace fabmesh
