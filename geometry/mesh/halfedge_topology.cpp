#include "geometry/mesh/halfedge_topology.h"

#include <algorithm>
#include <numeric>
#include <vector>

#include "geometry/core/disjoint_sets.h"

namespace fabmesh {
namespace {

Vec3 to_vec(const Mesh::Point& p) { return {p[0], p[1], p[2]}; }

}  // namespace

Topology analyse_topology(const Mesh& mesh, std::size_t max_examples) {
  Topology topo;
  topo.edges = mesh.n_edges();
  const auto faces = static_cast<int>(mesh.n_faces());
  DisjointSets<int> comp(mesh.n_faces());

  for (const auto e : mesh.edges()) {
    const auto h0 = mesh.halfedge_handle(e, 0), h1 = mesh.halfedge_handle(e, 1);
    const auto f0 = mesh.face_handle(h0), f1 = mesh.face_handle(h1);
    if (!f0.is_valid() || !f1.is_valid()) {
      if (f0.is_valid() || f1.is_valid()) {
        const auto mid =
            0.5 * (mesh.point(mesh.to_vertex_handle(h0)) + mesh.point(mesh.to_vertex_handle(h1)));
        topo.boundary_edges.add(to_vec(mid), max_examples);
      }
      continue;
    }
    comp.unite(f0.idx(), f1.idx());
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

  // A vertex is manifold when its faces form one fan: at most one boundary
  // halfedge leaves it (OpenMesh links boundary fans into one circulation),
  // and circulating reaches every halfedge leaving it.
  std::vector<int> outgoing(mesh.n_vertices(), 0), boundary_out(mesh.n_vertices(), 0);
  for (const auto h : mesh.halfedges()) {
    const bool has_face = mesh.face_handle(h).is_valid();
    if (has_face || mesh.face_handle(mesh.opposite_halfedge_handle(h)).is_valid()) {
      ++outgoing[mesh.from_vertex_handle(h).idx()];
      if (!has_face) ++boundary_out[mesh.from_vertex_handle(h).idx()];
    }
  }
  for (const auto v : mesh.vertices()) {
    if (outgoing[v.idx()] == 0) continue;
    ++topo.referenced_vertices;
    int around = 0;
    for (auto it = mesh.cvoh_iter(v); it.is_valid() && around <= outgoing[v.idx()]; ++it) ++around;
    if (boundary_out[v.idx()] > 1 || around != outgoing[v.idx()]) {
      topo.non_manifold_vertices.add(to_vec(mesh.point(v)), max_examples);
    }
  }

  // Components (faces sharing an edge, then a vertex) and their V - E + F.
  // (every face at a vertex, whatever fan it is in: no circulation here).
  std::vector<int> face_at(mesh.n_vertices(), -1);
  for (const auto h : mesh.halfedges()) {
    const auto f = mesh.face_handle(h);
    if (!f.is_valid()) continue;
    int& rep = face_at[mesh.to_vertex_handle(h).idx()];
    if (rep < 0) {
      rep = f.idx();
    } else {
      comp.unite(rep, f.idx());
    }
  }
  std::vector<int> root_of(faces);
  for (int f = 0; f < faces; ++f) root_of[f] = comp.find(f);
  std::vector<long> chi(static_cast<std::size_t>(faces), 0);
  std::vector<int> lowest_vertex(static_cast<std::size_t>(faces), -1);
  for (int f = 0; f < faces; ++f) chi[root_of[f]] += 1;
  for (const auto e : mesh.edges()) {
    const auto f = mesh.face_handle(mesh.halfedge_handle(e, 0)).is_valid()
                       ? mesh.face_handle(mesh.halfedge_handle(e, 0))
                       : mesh.face_handle(mesh.halfedge_handle(e, 1));
    if (f.is_valid()) chi[root_of[f.idx()]] -= 1;
  }
  for (const auto v : mesh.vertices()) {
    if (face_at[v.idx()] < 0) continue;
    const int root = root_of[face_at[v.idx()]];
    chi[root] += 1;
    if (lowest_vertex[root] < 0) lowest_vertex[root] = v.idx();
  }
  std::vector<std::pair<int, int>> order;  // (lowest vertex, root)
  for (int f = 0; f < faces; ++f) {
    if (root_of[f] == f) order.emplace_back(lowest_vertex[f], f);
  }
  std::sort(order.begin(), order.end());
  topo.components = order.size();
  for (const auto& [vertex, root] : order) topo.euler_characteristics.push_back(chi[root]);
  return topo;
}

}  // namespace fabmesh
