#include "geometry/mesh/revolve.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>

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

using HalfedgeHandle = Mesh::HalfedgeHandle;
using VertexHandle = Mesh::VertexHandle;

HalfedgeHandle opposite(HalfedgeHandle h) { return HalfedgeHandle(h.idx() ^ 1); }

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

// Builds the halfedge structure of one revolved loop directly: the
// connectivity of the revolution grid is known, so every halfedge gets its
// face by index arithmetic (no searches), and the result is closed by
// construction: each of the 2E halfedges below is used by exactly one face.
//   R(i,j): ring edge a_j -> a_{j+1} of off-axis vertex i
//   M(e,j): meridian a_j -> b_j of loop edge e = (a, b), unless both are on the axis
//   D(e,j): diagonal a_j -> b_{j+1}, when both ends are off the axis
// Faces of e at j (counter-clockwise loop, outward normals):
//   T1 = (a_j, a_{j+1}, b_{j+1}) when a is off the axis: R(a,j), M(e,j+1), -D(e,j) (or -M(e,j) if b is a
//   pole) T2 = (a_j, b_{j+1}, b_j)     when b is off the axis: D(e,j) (or M(e,j+1) if a is a pole), -R(b,j),
//   -M(e,j)
// Next free vertex, edge and face slots of a mesh sized in advance.
struct Slots {
  int vertex = 0, edge = 0, face = 0;
};

void revolve_loop(const std::vector<Vec2>& loop, const std::vector<double>& cs, const std::vector<double>& sn,
                  Mesh& mesh, Slots& next) {
  const std::size_t n = loop.size();
  const std::size_t m = cs.size();
  auto on_axis = [&](std::size_t i) { return loop[i].x() == 0.0; };

  std::vector<int> first(n);  // vertex index of ring i at angle 0, or its pole
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& p = loop[i];
    first[i] = next.vertex;
    if (on_axis(i)) {
      mesh.set_point(VertexHandle(next.vertex++), Mesh::Point(0.0, 0.0, p.y()));
      continue;
    }
    for (std::size_t j = 0; j < m; ++j) {
      mesh.set_point(VertexHandle(next.vertex++), Mesh::Point(p.x() * cs[j], p.x() * sn[j], p.y()));
    }
  }
  auto v = [&](std::size_t i, std::size_t j) {
    return VertexHandle(on_axis(i) ? first[i] : first[i] + static_cast<int>(j % m));
  };

  // Edges, in a fixed order; each family's first halfedge is remembered.
  auto new_edge = [&](VertexHandle from, VertexHandle to) {
    const HalfedgeHandle h(2 * next.edge++);
    mesh.set_vertex_handle(h, to);
    mesh.set_vertex_handle(opposite(h), from);
    return h.idx();
  };
  std::vector<int> ring(n, -1), meridian(n, -1), diagonal(n, -1);  // halfedge index at j = 0; +2 per step
  for (std::size_t i = 0; i < n; ++i) {
    if (on_axis(i)) continue;
    ring[i] = new_edge(v(i, 0), v(i, 1));
    for (std::size_t j = 1; j < m; ++j) new_edge(v(i, j), v(i, j + 1));
  }
  for (std::size_t e = 0; e < n; ++e) {
    const std::size_t a = e, b = (e + 1) % n;
    if (on_axis(a) && on_axis(b)) continue;
    meridian[e] = new_edge(v(a, 0), v(b, 0));
    for (std::size_t j = 1; j < m; ++j) new_edge(v(a, j), v(b, j));
    if (on_axis(a) || on_axis(b)) continue;
    diagonal[e] = new_edge(v(a, 0), v(b, 1));
    for (std::size_t j = 1; j < m; ++j) new_edge(v(a, j), v(b, j + 1));
  }
  auto he = [&](int base, std::size_t j) { return HalfedgeHandle(base + 2 * static_cast<int>(j % m)); };
  auto add_face = [&](HalfedgeHandle h0, HalfedgeHandle h1, HalfedgeHandle h2) {
    const Mesh::FaceHandle f(next.face++);
    mesh.set_halfedge_handle(f, h0);
    for (auto [h, following] : {std::pair{h0, h1}, std::pair{h1, h2}, std::pair{h2, h0}}) {
      mesh.set_face_handle(h, f);
      mesh.set_next_halfedge_handle(h, following);
    }
  };
  for (std::size_t e = 0; e < n; ++e) {
    const std::size_t a = e, b = (e + 1) % n;
    if (on_axis(a) && on_axis(b)) continue;
    for (std::size_t j = 0; j < m; ++j) {
      if (!on_axis(a)) {
        const HalfedgeHandle back = on_axis(b) ? opposite(he(meridian[e], j)) : opposite(he(diagonal[e], j));
        add_face(he(ring[a], j), he(meridian[e], j + 1), back);
      }
      if (!on_axis(b)) {
        const HalfedgeHandle out = on_axis(a) ? he(meridian[e], j + 1) : he(diagonal[e], j);
        add_face(out, opposite(he(ring[b], j)), opposite(he(meridian[e], j)));
      }
    }
  }
  // Each vertex's outgoing halfedge: its ring edge, or for a pole its meridian.
  for (std::size_t i = 0; i < n; ++i) {
    if (!on_axis(i)) {
      for (std::size_t j = 0; j < m; ++j) mesh.set_halfedge_handle(v(i, j), he(ring[i], j));
      continue;
    }
    const std::size_t out_edge =
        on_axis((i + 1) % n) ? (i + n - 1) % n : i;  // the loop edge leaving the axis here
    const HalfedgeHandle h = he(meridian[out_edge], 0);
    mesh.set_halfedge_handle(v(i, 0), out_edge == i ? h : opposite(h));
  }
}

}  // namespace

Mesh revolve(const std::vector<std::vector<Vec2>>& loops, const RevolveOptions& options) {
  if (options.segments < 3) {
    throw RangeError("segments", options.segments,
                     fmt::format("segments = {} must be >= 3", options.segments));
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
    require_axis_contacts_along_edges(loop);
    for (const Vec2& p : loop) {
      if (p.x() < 0.0) throw RangeError("radius", p.x(), fmt::format("loop vertex radius {} < 0", p.x()));
      vertex_count += p.x() == 0.0 ? 1 : m;
    }
  }
  const std::size_t faces = revolved_triangle_count(loops, options.segments);
  // OpenMesh numbers halfedges (3 per triangle) with an int.
  constexpr std::size_t kMaxFaces = static_cast<std::size_t>(std::numeric_limits<int>::max()) / 3;
  if (faces > kMaxFaces) {
    throw BudgetError(static_cast<double>(faces), static_cast<double>(kMaxFaces),
                      fmt::format("the mesh needs {} triangles, more than the {} a halfedge mesh can hold "
                                  "(lower max_triangles or raise the tolerance)",
                                  faces, kMaxFaces));
  }
  Mesh mesh;
  mesh.resize(vertex_count, 3 * faces / 2, faces);  // closed triangle mesh: E = 3F/2
  Slots next;
  for (const auto& loop : loops) revolve_loop(loop, cs, sn, mesh, next);
  if (static_cast<std::size_t>(next.vertex) != vertex_count ||
      static_cast<std::size_t>(next.edge) != 3 * faces / 2 || static_cast<std::size_t>(next.face) != faces) {
    throw std::logic_error("revolve: element counts disagree with the closed-surface formula");
  }
  return mesh;
}

}  // namespace fabmesh
