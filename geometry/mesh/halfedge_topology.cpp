#include "geometry/mesh/halfedge_topology.h"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "geometry/core/disjoint_sets.h"

namespace fabmesh {
namespace {

Vec3 to_vec(const Mesh::Point& p) { return {p[0], p[1], p[2]}; }

// What one pass over the edges finds: faces joined across edges and at
// vertices, boundary edges, and how many halfedges (and boundary halfedges)
// leave each vertex. 32-bit counters: OpenMesh numbers elements with an int.
struct EdgePass {
  std::vector<std::int32_t> outgoing;       // halfedges with a face on either side, by from-vertex
  std::vector<std::uint8_t> boundary_out;   // of those, without a face (saturates at 2)
  std::vector<std::int32_t> face_at;        // a face at each vertex, -1 for none
  std::vector<std::int32_t> boundary_face;  // the face of each boundary edge
};

EdgePass scan_edges(const Mesh& mesh, DisjointSets<int>& comp, Topology& topo, std::size_t max_examples) {
  EdgePass pass;
  pass.outgoing.assign(mesh.n_vertices(), 0);
  pass.boundary_out.assign(mesh.n_vertices(), 0);
  pass.face_at.assign(mesh.n_vertices(), -1);
  // Every face at a vertex joins the first face seen there, whatever fan it
  // is in: components are faces sharing an edge, then a vertex.
  auto at_vertex = [&](int v, int f) {
    std::int32_t& rep = pass.face_at[v];
    if (rep < 0) {
      rep = f;
    } else {
      comp.unite(rep, f);
    }
  };
  for (const auto e : mesh.edges()) {
    const auto h0 = mesh.halfedge_handle(e, 0), h1 = mesh.halfedge_handle(e, 1);
    const int f0 = mesh.face_handle(h0).idx(), f1 = mesh.face_handle(h1).idx();
    if (f0 < 0 && f1 < 0) continue;                  // an isolated edge: no part of any face
    const int v0 = mesh.to_vertex_handle(h0).idx();  // h0: v1 -> v0, h1: v0 -> v1
    const int v1 = mesh.to_vertex_handle(h1).idx();
    ++pass.outgoing[v1];
    ++pass.outgoing[v0];
    if (f0 >= 0) at_vertex(v0, f0);
    if (f1 >= 0) at_vertex(v1, f1);
    if (f0 >= 0 && f1 >= 0) {
      comp.unite(f0, f1);
      continue;
    }
    std::uint8_t& open = pass.boundary_out[f0 < 0 ? v1 : v0];
    open = static_cast<std::uint8_t>(std::min(open + 1, 2));
    pass.boundary_face.push_back(f0 >= 0 ? f0 : f1);
    topo.boundary_edges.add(
        to_vec(0.5 * (mesh.point(Mesh::VertexHandle(v0)) + mesh.point(Mesh::VertexHandle(v1)))),
        max_examples);
  }
  return pass;
}

}  // namespace

Topology analyse_topology(const Mesh& mesh, std::size_t max_examples) {
  Topology topo;
  topo.edges = mesh.n_edges();
  const auto faces = static_cast<int>(mesh.n_faces());
  std::vector<std::int32_t> component;  // dense id of each face's component
  std::vector<std::int32_t> face_at, boundary_face;
  {
    DisjointSets<int> comp(mesh.n_faces());
    EdgePass pass = scan_edges(mesh, comp, topo, max_examples);

    // A vertex is manifold when its faces form one fan: at most one boundary
    // halfedge leaves it (OpenMesh links boundary fans into one circulation),
    // and circulating reaches every halfedge leaving it.
    for (const auto v : mesh.vertices()) {
      const std::int32_t out = pass.outgoing[v.idx()];
      if (out == 0) continue;
      ++topo.referenced_vertices;
      std::int32_t around = 0;
      for (auto it = mesh.cvoh_iter(v); it.is_valid() && around <= out; ++it) ++around;
      if (pass.boundary_out[v.idx()] > 1 || around != out) {
        topo.non_manifold_vertices.add(to_vec(mesh.point(v)), max_examples);
      }
    }
    face_at = std::move(pass.face_at);
    boundary_face = std::move(pass.boundary_face);
    pass = EdgePass();  // the counts' memory is free before the components'

    // Components numbered by their smallest face (the representative).
    component.resize(static_cast<std::size_t>(faces));
    std::int32_t count = 0;
    for (int f = 0; f < faces; ++f) {
      const int root = comp.find(f);
      component[f] = root == f ? count++ : component[root];
    }
    topo.components = static_cast<std::size_t>(count);
  }

  // Duplicate faces: a face whose three neighbours are one and the same face.
  for (const auto f : mesh.faces()) {
    const auto h = mesh.halfedge_handle(f);
    const auto g = mesh.opposite_face_handle(h);
    if (!g.is_valid() || g.idx() < f.idx()) continue;
    if (mesh.opposite_face_handle(mesh.next_halfedge_handle(h)) == g &&
        mesh.opposite_face_handle(mesh.prev_halfedge_handle(h)) == g) {
      Mesh::Point c(0, 0, 0);
      for (const auto v : mesh.fv_range(f)) c += mesh.point(v);
      topo.duplicate_faces.add(to_vec(c / 3.0), max_examples);
    }
  }

  // V - E + F of each component, doubled: a triangle mesh has E = (3F + B) / 2
  // with B its boundary edges, so 2 (V - E + F) = 2V - F - B.
  std::vector<long> twice_chi(topo.components, 0);
  std::vector<std::int32_t> lowest_vertex(topo.components, -1);
  for (int f = 0; f < faces; ++f) twice_chi[component[f]] -= 1;
  for (const std::int32_t f : boundary_face) twice_chi[component[f]] -= 1;
  for (const auto v : mesh.vertices()) {
    if (face_at[v.idx()] < 0) continue;
    const std::int32_t c = component[face_at[v.idx()]];
    twice_chi[c] += 2;
    if (lowest_vertex[c] < 0) lowest_vertex[c] = v.idx();
  }
  std::vector<std::pair<std::int32_t, std::int32_t>> order;  // (lowest vertex, component)
  order.reserve(topo.components);
  for (std::size_t c = 0; c < topo.components; ++c)
    order.emplace_back(lowest_vertex[c], static_cast<std::int32_t>(c));
  std::sort(order.begin(), order.end());
  for (const auto& [vertex, c] : order) topo.euler_characteristics.push_back(twice_chi[c] / 2);
  return topo;
}

}  // namespace fabmesh
