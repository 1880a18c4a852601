#include "geometry/validation/detail/topology.h"

#include <algorithm>
#include <cstdint>
#include <numeric>

#include "geometry/core/bucket_sort.h"
#include "geometry/core/disjoint_sets.h"

namespace fabmesh {

void DefectCount::add(const Vec3& where, std::size_t max_examples) {
  ++count;
  if (examples.size() < max_examples) examples.push_back(where);
}

namespace {

using Triangle = std::array<std::uint32_t, 3>;

bool index_degenerate(const Triangle& t) { return t[0] == t[1] || t[1] == t[2] || t[2] == t[0]; }

/// One directed side of a face: the undirected edge key, the face and the
/// corner the side starts at (side k runs from corner k to corner k + 1).
struct Side {
  std::uint64_t key;
  std::uint32_t face;
  std::uint32_t corner;
};

/// The sides sorted by (key, face, corner): a counting sort by the edge's
/// smaller vertex, faces and corners visited in order (so each bucket is in
/// (face, corner) order), then each bucket stably by key. Linear but for
/// the buckets of vertices of very high degree.
std::vector<Side> collect_sides(const TriangleSoup& soup) {
  std::vector<std::size_t> start(soup.vertices.size() + 1, 0);
  for (const Triangle& t : soup.triangles) {
    if (index_degenerate(t)) continue;
    for (std::uint32_t k = 0; k < 3; ++k) ++start[std::min(t[k], t[(k + 1) % 3]) + std::size_t{1}];
  }
  bucket_offsets(start);
  std::vector<Side> sides(start.back());
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (std::uint32_t f = 0; f < soup.triangles.size(); ++f) {
    const Triangle& t = soup.triangles[f];
    if (index_degenerate(t)) continue;
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint64_t a = t[k];
      const std::uint64_t b = t[(k + 1) % 3];
      sides[fill[std::min(a, b)]++] = {std::min(a, b) << 32 | std::max(a, b), f, k};
    }
  }
  sort_buckets(sides, start, [](const Side& x, const Side& y) { return x.key < y.key; });
  return sides;
}

/// Walks the sorted sides edge by edge: counts boundary, non-manifold and
/// inconsistent edges, and joins the corners of the two faces of each
/// manifold edge into fans.
void classify_edges(const TriangleSoup& soup, const std::vector<Side>& sides, std::size_t max_examples,
                    std::size_t max_locations, ExampleOrder order, Topology& topo,
                    DisjointSets<std::uint32_t>& fans, std::vector<char>& on_complex_edge) {
  const auto& tri = soup.triangles;
  auto midpoint = [&](std::uint64_t key) {
    return 0.5 * (soup.vertices[key >> 32] + soup.vertices[key & 0xffffffffu]);
  };
  // The edge of sides [i, j) as a location: its vertices and faces, ascending.
  auto edge_location = [&](std::size_t i, std::size_t j) {
    DefectLocation at{{},
                      {static_cast<std::uint32_t>(sides[i].key >> 32),
                       static_cast<std::uint32_t>(sides[i].key & 0xffffffffu)}};
    for (std::size_t k = i; k < j; ++k) at.faces.push_back(sides[k].face);
    std::sort(at.faces.begin(), at.faces.end());
    at.faces.erase(std::unique(at.faces.begin(), at.faces.end()), at.faces.end());
    return at;
  };
  const std::size_t kept_by_face = std::max(max_examples, max_locations);
  // By face: the first max_examples boundary sides in (face, corner) order, kept sorted.
  const bool by_face = order == ExampleOrder::ByFace;
  std::vector<const Side*> first_in_faces;
  const auto face_order = [](const Side* x, const Side* y) {
    return x->face != y->face ? x->face < y->face : x->corner < y->corner;
  };
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i;
    while (j < sides.size() && sides[j].key == sides[i].key) ++j;
    const std::size_t n = j - i;
    ++topo.edges;
    if (n == 1 && by_face) {
      ++topo.boundary_edges.count;
      const Side* s = &sides[i];
      if (first_in_faces.size() < kept_by_face ||
          (!first_in_faces.empty() && face_order(s, first_in_faces.back()))) {
        first_in_faces.insert(std::upper_bound(first_in_faces.begin(), first_in_faces.end(), s, face_order),
                              s);
        if (first_in_faces.size() > kept_by_face) first_in_faces.pop_back();
      }
    } else if (n == 1) {
      topo.boundary_edges.add(midpoint(sides[i].key), max_examples, max_locations,
                              [&] { return edge_location(i, j); });
    } else if (n > 2) {
      topo.non_manifold_edges.add(midpoint(sides[i].key), max_examples, max_locations,
                                  [&] { return edge_location(i, j); });
      on_complex_edge[sides[i].key >> 32] = 1;
      on_complex_edge[sides[i].key & 0xffffffffu] = 1;
    } else {
      const Side& s = sides[i];
      const Side& u = sides[i + 1];
      const std::uint32_t sa = tri[s.face][s.corner];
      const std::uint32_t ua = tri[u.face][u.corner];
      if (sa == ua) {
        topo.inconsistent_edges.add(midpoint(s.key), max_examples, max_locations,
                                    [&] { return edge_location(i, j); });
      }
      // Corner ids are 3 * face + k; join the corners that hold the same vertex.
      const std::uint32_t s0 = 3 * s.face + s.corner;
      const std::uint32_t s1 = 3 * s.face + (s.corner + 1) % 3;
      const std::uint32_t u0 = 3 * u.face + u.corner;
      const std::uint32_t u1 = 3 * u.face + (u.corner + 1) % 3;
      if (sa == ua) {
        fans.unite(s0, u0);
        fans.unite(s1, u1);
      } else {
        fans.unite(s0, u1);
        fans.unite(s1, u0);
      }
    }
    i = j;
  }
  for (const Side* s : first_in_faces) {
    if (topo.boundary_edges.examples.size() < max_examples)
      topo.boundary_edges.examples.push_back(midpoint(s->key));
    if (topo.boundary_edges.locations.size() < max_locations) {
      topo.boundary_edges.locations.push_back(
          {{s->face},
           {static_cast<std::uint32_t>(s->key >> 32), static_cast<std::uint32_t>(s->key & 0xffffffffu)}});
    }
  }
}

// The faces' sorted vertex triples with their faces, sorted (as pairs): a
// counting sort by the smallest vertex, then each bucket stably by the rest.
void count_duplicates(const TriangleSoup& soup, std::size_t max_examples, std::size_t max_locations,
                      Topology& topo) {
  const auto ordered = [](Triangle t) {
    std::sort(t.begin(), t.end());
    return t;
  };
  std::vector<std::size_t> start(soup.vertices.size() + 1, 0);
  for (const Triangle& t : soup.triangles) {
    if (!index_degenerate(t)) ++start[std::min({t[0], t[1], t[2]}) + std::size_t{1}];
  }
  bucket_offsets(start);
  std::vector<std::pair<Triangle, std::uint32_t>> sorted(start.back());
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (std::uint32_t f = 0; f < soup.triangles.size(); ++f) {
    if (index_degenerate(soup.triangles[f])) continue;
    const Triangle t = ordered(soup.triangles[f]);
    sorted[fill[t[0]]++] = {t, f};
  }
  sort_buckets(sorted, start, [](const auto& x, const auto& y) { return x.first < y.first; });
  for (std::size_t k = 1; k < sorted.size(); ++k) {
    if (sorted[k].first != sorted[k - 1].first) continue;
    const Triangle& t = sorted[k].first;
    const Vec3 centroid = (soup.vertices[t[0]] + soup.vertices[t[1]] + soup.vertices[t[2]]) / 3.0;
    topo.duplicate_faces.add(centroid, max_examples, max_locations, [&] {
      return DefectLocation{{std::min(sorted[k - 1].second, sorted[k].second),
                             std::max(sorted[k - 1].second, sorted[k].second)},
                            {t[0], t[1], t[2]}};
    });
  }
}

void count_components(const TriangleSoup& soup, const std::vector<Side>& sides, Topology& topo) {
  const std::size_t nv = soup.vertices.size();
  DisjointSets<std::uint32_t> parts(nv);
  std::vector<char> used(nv, 0);
  for (const auto& t : soup.triangles) {
    if (index_degenerate(t)) continue;
    parts.unite(t[0], t[1]);
    parts.unite(t[1], t[2]);
    for (const std::uint32_t v : t) used[v] = 1;
  }
  constexpr std::uint32_t kNone = UINT32_MAX;
  std::vector<std::uint32_t> component(nv, kNone);  // by root vertex
  for (std::uint32_t v = 0; v < nv; ++v) {
    if (!used[v]) continue;
    ++topo.referenced_vertices;
    const std::uint32_t r = parts.find(v);
    if (component[r] == kNone) {
      component[r] = static_cast<std::uint32_t>(topo.components++);
      topo.euler_characteristics.push_back(0);
    }
    ++topo.euler_characteristics[component[r]];  // + V
  }
  for (std::size_t i = 0; i < sides.size(); ++i) {
    if (i > 0 && sides[i].key == sides[i - 1].key) continue;
    --topo.euler_characteristics[component[parts.find(
        static_cast<std::uint32_t>(sides[i].key >> 32))]];  // - E
  }
  for (const auto& t : soup.triangles) {
    if (!index_degenerate(t)) ++topo.euler_characteristics[component[parts.find(t[0])]];  // + F
  }
}

/// Adds to each non-manifold vertex's location every face around it.
void add_vertex_faces(const TriangleSoup& soup, std::vector<DefectLocation>& locations) {
  if (locations.empty()) return;
  std::vector<std::uint32_t> slot(soup.vertices.size(), UINT32_MAX);
  for (std::uint32_t i = 0; i < locations.size(); ++i) slot[locations[i].vertices.front()] = i;
  for (std::uint32_t f = 0; f < soup.triangles.size(); ++f) {
    const Triangle& t = soup.triangles[f];
    if (index_degenerate(t)) continue;
    for (const std::uint32_t v : t) {
      if (slot[v] != UINT32_MAX) locations[slot[v]].faces.push_back(f);
    }
  }
}

}  // namespace

Topology analyse_topology(const TriangleSoup& soup, std::size_t max_examples, ExampleOrder order,
                          std::size_t max_locations) {
  require_indices_in_range(soup);
  Topology topo;
  // Each pass's arrays are freed before the next's are made (the duplicates'
  // sorted triples before the sides, the fans before the components): the
  // peak is the sides' (16 bytes a side) and the fans' (4 bytes a corner).
  count_duplicates(soup, max_examples, max_locations, topo);
  const std::vector<Side> sides = collect_sides(soup);
  std::vector<char> on_complex_edge(soup.vertices.size(), 0);
  std::vector<std::uint32_t> fan_count(soup.vertices.size(), 0);
  {
    DisjointSets<std::uint32_t> fans(3 * soup.triangles.size());
    classify_edges(soup, sides, max_examples, max_locations, order, topo, fans, on_complex_edge);
    // Each fan root is a corner; a vertex with more than one root has several fans.
    for (std::uint32_t f = 0; f < soup.triangles.size(); ++f) {
      if (index_degenerate(soup.triangles[f])) continue;
      for (std::uint32_t k = 0; k < 3; ++k) {
        if (fans.find(3 * f + k) == 3 * f + k) ++fan_count[soup.triangles[f][k]];
      }
    }
  }
  for (std::size_t v = 0; v < soup.vertices.size(); ++v) {
    if (fan_count[v] > 1 || on_complex_edge[v]) {
      topo.non_manifold_vertices.add(soup.vertices[v], max_examples, max_locations, [&] {
        return DefectLocation{{}, {static_cast<std::uint32_t>(v)}};
      });
    }
  }
  add_vertex_faces(soup, topo.non_manifold_vertices.locations);
  count_components(soup, sides, topo);
  return topo;
}

}  // namespace fabmesh
