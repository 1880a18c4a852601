#include "geometry/mesh/slab.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "geometry/core/bucket_sort.h"
#include "geometry/core/budget.h"
#include "geometry/core/error_checks.h"
#include "geometry/core/soup.h"
#include "geometry/section/simple_polygon.h"

namespace fabmesh {

std::size_t slab_triangle_count(const PlanarTriangulation& t) {
  std::size_t walls = 0;
  for (const auto& loop : t.boundary) walls += 2 * loop.size();
  return 2 * t.triangles.size() + walls;
}

namespace {

using Corners = std::array<std::uint32_t, 3>;

// The slab's faces: top (normal +z), bottom (-z), then two per boundary edge.
std::vector<Corners> slab_faces(const PlanarTriangulation& t) {
  const auto n = static_cast<std::uint32_t>(t.vertices.size());
  std::vector<Corners> faces;
  faces.reserve(slab_triangle_count(t));
  for (const auto& f : t.triangles) faces.push_back({n + f[0], n + f[1], n + f[2]});
  for (const auto& f : t.triangles) faces.push_back({f[0], f[2], f[1]});
  // Walls: boundary edge a -> b has the region on its left, so the outside is on its right.
  for (const auto& loop : t.boundary) {
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const std::uint32_t a = loop[i], b = loop[(i + 1) % loop.size()];
      faces.push_back({a, b, n + b});
      faces.push_back({a, n + b, n + a});
    }
  }
  return faces;
}

[[noreturn]] void refuse(const Corners& f) {
  throw std::logic_error(
      fmt::format("extrude: face ({}, {}, {}) refused: the triangulation is not a manifold "
                  "disc with holes",
                  f[0], f[1], f[2]));
}

}  // namespace

// The halfedge arrays are written directly (as revolve does): every side of
// every face is paired with the opposite side of exactly one other face, found
// by sorting the sides; anything else is refused, so the result is closed.
Mesh extrude(const PlanarTriangulation& t, double thickness) {
  require_positive("thickness", thickness);
  const std::size_t n = t.vertices.size();
  const std::vector<Corners> faces = slab_faces(t);
  // Side 3 f + k runs from corner k to corner k + 1 of face f; sorted by
  // (undirected edge, side): counted into buckets by the edge's smaller
  // vertex in side order, then each bucket by edge.
  struct Side {
    std::uint64_t key;
    std::uint32_t side;
  };
  std::vector<std::size_t> start(2 * n + 1, 0);
  for (const Corners& face : faces) {
    for (std::uint32_t k = 0; k < 3; ++k) {
      if (face[k] == face[(k + 1) % 3]) refuse(face);
      ++start[std::min(face[k], face[(k + 1) % 3]) + std::size_t{1}];
    }
  }
  bucket_offsets(start);
  std::vector<Side> sides(3 * faces.size());
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (std::uint32_t f = 0; f < faces.size(); ++f) {
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint64_t a = faces[f][k], b = faces[f][(k + 1) % 3];
      sides[fill[std::min(a, b)]++] = {std::min(a, b) << 32 | std::max(a, b), 3 * f + k};
    }
  }
  sort_buckets(sides, start, [](const Side& x, const Side& y) { return x.key < y.key; });
  Mesh mesh;
  mesh.resize(2 * n, sides.size() / 2, faces.size());
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& p = t.vertices[i];
    mesh.set_point(Mesh::VertexHandle(static_cast<int>(i)), Mesh::Point(p.x(), p.y(), 0.0));
    mesh.set_point(Mesh::VertexHandle(static_cast<int>(n + i)), Mesh::Point(p.x(), p.y(), thickness));
  }
  // Halfedge of each side: edges numbered in key order, the lower side first.
  std::vector<int> halfedge_of(sides.size());
  for (std::size_t i = 0; i < sides.size(); i += 2) {
    const Side& s = sides[i];
    const std::uint32_t fs = s.side / 3, ks = s.side % 3;
    if (i + 1 >= sides.size() || sides[i + 1].key != s.key ||
        (i + 2 < sides.size() && sides[i + 2].key == s.key))
      refuse(faces[fs]);
    const Side& u = sides[i + 1];
    const std::uint32_t fu = u.side / 3, ku = u.side % 3;
    if (faces[fs][ks] != faces[fu][(ku + 1) % 3]) refuse(faces[fu]);  // both sides run the same way
    halfedge_of[s.side] = static_cast<int>(i);
    halfedge_of[u.side] = static_cast<int>(i + 1);
  }
  for (std::uint32_t f = 0; f < faces.size(); ++f) {
    const Mesh::FaceHandle fh(static_cast<int>(f));
    for (std::uint32_t k = 0; k < 3; ++k) {
      const Mesh::HalfedgeHandle h(halfedge_of[3 * f + k]);
      const auto to = Mesh::VertexHandle(static_cast<int>(faces[f][(k + 1) % 3]));
      mesh.set_vertex_handle(h, to);
      mesh.set_face_handle(h, fh);
      mesh.set_next_halfedge_handle(h, Mesh::HalfedgeHandle(halfedge_of[3 * f + (k + 1) % 3]));
      mesh.set_halfedge_handle(Mesh::VertexHandle(static_cast<int>(faces[f][k])), h);  // an outgoing one
    }
    mesh.set_halfedge_handle(fh, Mesh::HalfedgeHandle(halfedge_of[3 * f + 2]));
  }
  return mesh;
}

PlanarTriangulation slab_top(const Region2& region, const SlabOptions& options) {
  TriangulateOptions to;
  to.max_edge = options.max_edge;
  to.max_triangles = options.max_triangles / 2;
  PlanarTriangulation triangulation = triangulate(region, to);
  const std::size_t triangles = slab_triangle_count(triangulation);
  require_within_budget(
      triangles, options.max_triangles, [&] { return fmt::format("the slab needs {} triangles", triangles); },
      "raise max_triangles, the tolerance or max_edge");
  return triangulation;
}

SlabMesh build_slab(const Region2& region, const SlabOptions& options) {
  require_positive("thickness", options.thickness);
  return extrude_slab(region, slab_top(region, options), options);
}

SlabMesh extrude_slab(const Region2& region, PlanarTriangulation triangulation, const SlabOptions& options) {
  require_positive("thickness", options.thickness);
  EmbeddingProof proof;
  proof.statement =
      region.proof + fmt::format(
                         "; top and bottom are a CGAL constrained Delaunay triangulation of that region "
                         "({} faces, each counter-clockwise by the exact orientation predicate) at z = {} "
                         "and z = 0, walls vertical over its {} boundary cycle(s), which meet only at shared "
                         "vertices: an extruded planar embedding",
                         triangulation.triangles.size(), options.thickness, triangulation.boundary.size());
  // A moved copy (rounded to float32, scaled) is again an extrusion when the
  // top and bottom stay level and every wall vertical; then it is embedded
  // when its planar triangulation is (is_planar_embedding, exact).
  proof.recheck = [n = triangulation.vertices.size(), triangles = triangulation.triangles,
                   cycles = triangulation.boundary](const TriangleSoup& moved) {
    if (moved.vertices.size() != 2 * n || n == 0) return false;
    const double bottom = moved.vertices[0].z(), top = moved.vertices[n].z();
    if (!(top > bottom)) return false;
    std::vector<Vec2> plane(n);
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3& b = moved.vertices[i];
      const Vec3& t = moved.vertices[n + i];
      if (b.z() != bottom || t.z() != top || b.x() != t.x() || b.y() != t.y()) return false;
      plane[i] = Vec2(b.x(), b.y());
    }
    return is_planar_embedding(plane, triangles, cycles);
  };
  proof.recheck_statement =
      "it is still the extrusion of a planar triangulation (top and bottom level, walls vertical) whose "
      "triangles are counter-clockwise and whose boundary cycles are simple, disjoint and nested as "
      "built (exact predicates)";
  // extrude pairs every side of every face with the opposite side of exactly
  // one other face, or refuses: closed, edge-manifold, consistently oriented.
  // The region's boundary cycles are simple and disjoint, so each boundary
  // vertex has one fan of top, wall and bottom faces (vertex-manifold), and
  // a region of one outline and its holes is connected: one component, a
  // closed surface of genus = holes.
  TopologyProof topology;
  const long holes = static_cast<long>(triangulation.boundary.size()) - 1;
  topology.components = 1;
  topology.euler_characteristics = {2 - 2 * holes};
  topology.statement = fmt::format(
      "closed, manifold and consistently oriented by construction: the extrusion of a triangulated region "
      "with {} hole(s), every side of every face paired with the opposite side of exactly one other face",
      holes);
  // Braced initialisers run in order: the mesh is extruded (in place) before the triangulation moves.
  return SlabMesh{extrude(triangulation, options.thickness), std::move(triangulation), std::move(proof),
                  std::move(topology)};
}

}  // namespace fabmesh
