#include "geometry/repair/manifold_split.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include "geometry/core/disjoint_sets.h"
#include "geometry/repair/edge_table.h"

namespace fabmesh {
namespace {

/// Face sides paired across an edge: partner[side index] = the side it is joined to, or SIZE_MAX.
using Partners = std::vector<std::size_t>;
constexpr std::size_t kUnpaired = static_cast<std::size_t>(-1);

struct Radial {
  double angle;
  std::size_t side;  ///< index into EdgeTable::sides
  bool forward;      ///< the face runs the edge from its smaller to its larger vertex
};

/// The sides of edge e sorted by the angle of their faces' third corners around the edge.
std::vector<Radial> radial_order(const TriangleSoup& soup, const EdgeTable& edges, std::size_t e) {
  const FaceSide& first = edges.side(e, 0);
  const std::uint32_t lo = std::min(first.from, first.to), hi = std::max(first.from, first.to);
  const Vec3 axis = (soup.vertices[hi] - soup.vertices[lo]).normalized();
  Vec3 x_axis = Vec3::Zero();
  std::vector<Radial> order;
  for (std::size_t k = 0; k < edges.faces_of(e); ++k) {
    const FaceSide& s = edges.side(e, k);
    const auto& t = soup.triangles[s.face];
    std::uint32_t c = t[0];
    for (const std::uint32_t v : t) {
      if (v != s.from && v != s.to) c = v;
    }
    Vec3 r = soup.vertices[c] - soup.vertices[lo];
    r -= r.dot(axis) * axis;
    if (k == 0) x_axis = r.normalized();
    const Vec3 y_axis = axis.cross(x_axis);
    order.push_back({std::atan2(r.dot(y_axis), r.dot(x_axis)), edges.starts[e] + k, s.from == lo});
  }
  std::sort(order.begin(), order.end(), [](const Radial& a, const Radial& b) { return a.angle < b.angle; });
  return order;
}

/// Pairs the sides of a non-manifold edge (see split_non_manifold).
void pair_radially(const std::vector<Radial>& order, Partners& partner) {
  const std::size_t n = order.size();
  bool alternating = n % 2 == 0;
  for (std::size_t i = 0; i < n && alternating; ++i)
    alternating = order[i].forward != order[(i + 1) % n].forward;
  // A face running lo -> hi has its solid clockwise about the axis lo -> hi
  // (toward smaller angles); one running hi -> lo counterclockwise. So a
  // backward face pairs with the next face counterclockwise.
  std::size_t start = 0;
  if (alternating && order[0].forward) start = 1;
  for (std::size_t i = 0; i + 1 < n; i += 2) {
    const std::size_t a = order[(start + i) % n].side, b = order[(start + i + 1) % n].side;
    partner[a] = b;
    partner[b] = a;
  }
}

Partners pair_sides(const TriangleSoup& soup, const EdgeTable& edges, TrackedSoup& mesh, RepairLog& log) {
  Partners partner(edges.sides.size(), kUnpaired);
  for (std::size_t e = 0; e < edges.edges(); ++e) {
    const std::size_t n = edges.faces_of(e);
    if (n == 2) {
      partner[edges.starts[e]] = edges.starts[e] + 1;
      partner[edges.starts[e] + 1] = edges.starts[e];
    } else if (n > 2) {
      pair_radially(radial_order(soup, edges, e), partner);
      const FaceSide& s = edges.side(e, 0);
      log.add(RepairStep::NonManifoldEdge,
              RepairPlace{mesh.face_origin[s.face], mesh.vertex_origin[s.from],
                          0.5 * (soup.vertices[s.from] + soup.vertices[s.to]), fmt::format("{} faces", n)});
    }
  }
  return partner;
}

}  // namespace

void split_non_manifold(TrackedSoup& mesh, double separation, RepairLog& log) {
  const EdgeTable edges = edge_table(mesh.soup);
  const Partners partner = pair_sides(mesh.soup, edges, mesh, log);
  // Fans: corners (face, vertex) joined when their faces are paired across an edge at the vertex.
  const std::size_t faces = mesh.soup.triangles.size();
  DisjointSets<> corners(3 * faces);
  auto corner_of = [&](std::uint32_t f, std::uint32_t v) {
    const auto& t = mesh.soup.triangles[f];
    return 3 * static_cast<std::size_t>(f) + static_cast<std::size_t>(t[0] == v ? 0 : t[1] == v ? 1 : 2);
  };
  for (std::size_t i = 0; i < edges.sides.size(); ++i) {
    if (partner[i] == kUnpaired || partner[i] < i) continue;
    const FaceSide& a = edges.sides[i];
    const FaceSide& b = edges.sides[partner[i]];
    for (const std::uint32_t v : {a.from, a.to}) corners.unite(corner_of(a.face, v), corner_of(b.face, v));
  }
  // One vertex per fan: the fan of the lowest corner keeps the vertex.
  std::map<std::pair<std::uint32_t, std::size_t>, std::uint32_t> copy;  // (vertex, fan root) -> vertex
  std::vector<std::size_t> fans(mesh.soup.vertices.size(), 0);
  const std::size_t vertices_before = mesh.soup.vertices.size();
  for (std::uint32_t f = 0; f < faces; ++f) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh.soup.triangles[f][k];
      const std::size_t root = corners.find(3 * static_cast<std::size_t>(f) + static_cast<std::size_t>(k));
      auto [it, fresh] = copy.try_emplace({v, root}, v);
      if (fresh) {
        if (fans[v]++ > 0) it->second = add_vertex(mesh, mesh.soup.vertices[v], v);
      }
      mesh.soup.triangles[f][k] = it->second;
    }
  }
  for (std::uint32_t v = 0; v < vertices_before; ++v) {
    if (fans[v] <= 1) continue;
    RepairPlace place{kNoIndex, mesh.vertex_origin[v], mesh.soup.vertices[v],
                      fmt::format("{} fans, copies moved {:.3g} apart into their fans", fans[v], separation)};
    log.add(RepairStep::NonManifoldVertex, place);
  }
  // Move each copy into its own fan.
  std::vector<Vec3> pull(mesh.soup.vertices.size(), Vec3::Zero());
  std::vector<int> pulls(mesh.soup.vertices.size(), 0);
  auto split = [&](std::uint32_t v) { return v >= vertices_before || fans[v] > 1; };
  for (const auto& t : mesh.soup.triangles) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = t[k];
      const std::uint32_t base = v < vertices_before ? v : kNoIndex;
      if (base != kNoIndex && fans[base] <= 1) continue;
      pull[v] += 0.5 * (mesh.soup.vertices[t[(k + 1) % 3]] + mesh.soup.vertices[t[(k + 2) % 3]]);
      ++pulls[v];
    }
  }
  for (std::uint32_t v = 0; v < mesh.soup.vertices.size(); ++v) {
    if (pulls[v] == 0 || !split(v)) continue;
    const Vec3 towards = pull[v] / pulls[v] - mesh.soup.vertices[v];
    if (towards.norm() > 0.0) mesh.soup.vertices[v] += separation * towards.normalized();
  }
}

}  // namespace fabmesh
