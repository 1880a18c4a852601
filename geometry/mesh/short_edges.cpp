#include "geometry/mesh/short_edges.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <optional>
#include <tuple>
#include <vector>

namespace fabmesh {
namespace {

using Index = std::uint32_t;
using Face = std::array<Index, 3>;

bool has(const Face& f, Index v) { return f[0] == v || f[1] == v || f[2] == v; }

// The soup's faces around each vertex, kept as edges collapse.
class Collapser {
 public:
  explicit Collapser(TriangleSoup& soup)
      : soup_(soup),
        faces_of_(soup.vertices.size()),
        live_(soup.triangles.size(), true),
        took_(soup.vertices.size()) {
    for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
      for (const Index v : soup.triangles[t]) faces_of_[v].push_back(t);
    }
  }

  // The live edges shorter than `length` (each once, its lower index first),
  // shortest first; ties in index order, so the result is deterministic.
  std::vector<std::tuple<double, Index, Index>> short_edges(double length) const {
    std::vector<std::tuple<double, Index, Index>> edges;
    for (std::size_t t = 0; t < soup_.triangles.size(); ++t) {
      if (!live_[t]) continue;
      const Face& f = soup_.triangles[t];
      for (int i = 0; i < 3; ++i) {
        const Index a = std::min(f[i], f[(i + 1) % 3]), b = std::max(f[i], f[(i + 1) % 3]);
        const double l = (soup_.vertices[a] - soup_.vertices[b]).norm();
        if (l < length) edges.emplace_back(l, a, b);
      }
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    return edges;
  }

  // Collapses the edge (a, b) if the surface stays a closed 2-manifold with
  // no face turned over or flattened; whether it did.
  // With `keep_shape`, only if the end that stays lies on the planes of the
  // other's faces (within a millionth of `length`).
  bool collapse(Index a, Index b, double length, bool keep_shape) {
    std::vector<std::size_t> edge_faces;
    for (const std::size_t t : live_faces(a)) {
      if (has(soup_.triangles[t], b)) edge_faces.push_back(t);
    }
    if (edge_faces.size() != 2) return false;
    const Index o1 = third(edge_faces[0], a, b), o2 = third(edge_faces[1], a, b);
    if (o1 == o2) return false;
    // The link condition: a and b share no neighbour but o1 and o2.
    std::vector<Index> na = neighbours(a), nb = neighbours(b), common;
    std::set_intersection(na.begin(), na.end(), nb.begin(), nb.end(), std::back_inserter(common));
    if (common != std::vector<Index>{std::min(o1, o2), std::max(o1, o2)}) return false;
    // o1 and o2 each lose a face, and keep at least three.
    if (live_faces(o1).size() < 4 || live_faces(o2).size() < 4) return false;

    const auto admissible = [&](std::optional<double> off) {
      return off && (!keep_shape || *off <= 1e-6 * length) ? off : std::nullopt;
    };
    const std::optional<double> keep_a = admissible(off_planes(b, a, edge_faces, length));
    const std::optional<double> keep_b = admissible(off_planes(a, b, edge_faces, length));
    if (!keep_a && !keep_b) return false;
    const bool a_stays = keep_a && (!keep_b || *keep_a <= *keep_b);
    const Index stays = a_stays ? a : b, goes = a_stays ? b : a;

    for (const std::size_t t : edge_faces) live_[t] = false;
    for (const std::size_t t : live_faces(goes)) {
      for (Index& v : soup_.triangles[t]) {
        if (v == goes) v = stays;
      }
      faces_of_[stays].push_back(t);
    }
    faces_of_[goes].clear();
    took_[stays].push_back(goes);
    took_[stays].insert(took_[stays].end(), took_[goes].begin(), took_[goes].end());
    took_[goes].clear();
    return true;
  }

  // The surface with the collapsed faces and the vertices no face uses any
  // more left out, the rest in their order.
  void compact() {
    constexpr Index kUnused = ~Index{0};
    std::vector<Index> renumbered(soup_.vertices.size(), kUnused);
    for (std::size_t t = 0; t < soup_.triangles.size(); ++t) {
      if (!live_[t]) continue;
      for (const Index v : soup_.triangles[t]) renumbered[v] = 0;
    }
    std::vector<Vec3> vertices;
    for (std::size_t v = 0; v < soup_.vertices.size(); ++v) {
      if (renumbered[v] == kUnused) continue;
      renumbered[v] = static_cast<Index>(vertices.size());
      vertices.push_back(soup_.vertices[v]);
    }
    std::vector<Face> faces;
    for (std::size_t t = 0; t < soup_.triangles.size(); ++t) {
      if (!live_[t]) continue;
      const Face& f = soup_.triangles[t];
      faces.push_back({renumbered[f[0]], renumbered[f[1]], renumbered[f[2]]});
    }
    soup_.vertices = std::move(vertices);
    soup_.triangles = std::move(faces);
  }

 private:
  std::vector<std::size_t> live_faces(Index v) const {
    std::vector<std::size_t> faces;
    for (const std::size_t t : faces_of_[v]) {
      if (live_[t]) faces.push_back(t);
    }
    return faces;
  }

  std::vector<Index> neighbours(Index v) const {
    std::vector<Index> out;
    for (const std::size_t t : live_faces(v)) {
      for (const Index w : soup_.triangles[t]) {
        if (w != v) out.push_back(w);
      }
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

  Index third(std::size_t t, Index a, Index b) const {
    for (const Index v : soup_.triangles[t]) {
      if (v != a && v != b) return v;
    }
    return a;  // not reached: the face has a, b and a third vertex
  }

  // How far `stays` lies off the planes of the faces of `goes` that move onto
  // it (0: the surface keeps its shape), or none when one of them would
  // turn over or flatten, or when `goes` or a vertex whose place it took is
  // `length` or more from `stays`.
  std::optional<double> off_planes(Index goes, Index stays, const std::vector<std::size_t>& edge_faces,
                                   double length) const {
    const Vec3& to = soup_.vertices[stays];
    if (!((soup_.vertices[goes] - to).norm() < length)) return std::nullopt;
    for (const Index v : took_[goes]) {
      if (!((soup_.vertices[v] - to).norm() < length)) return std::nullopt;
    }
    double most = 0.0;
    for (const std::size_t t : live_faces(goes)) {
      if (t == edge_faces[0] || t == edge_faces[1]) continue;
      Face moved = soup_.triangles[t];
      for (Index& v : moved) {
        if (v == goes) v = stays;
      }
      const Vec3 before = normal(soup_.triangles[t]), after = normal(moved);
      const double nb = before.norm(), na = after.norm();
      if (!(nb > 0.0) || !(na > 0.0) || !(before.dot(after) > 0.0)) return std::nullopt;
      most = std::max(most, std::abs(before.dot(to - soup_.vertices[goes])) / nb);
    }
    return most;
  }

  Vec3 normal(const Face& f) const {
    const std::vector<Vec3>& p = soup_.vertices;
    return (p[f[1]] - p[f[0]]).cross(p[f[2]] - p[f[0]]);
  }

  TriangleSoup& soup_;
  std::vector<std::vector<std::size_t>> faces_of_;
  std::vector<bool> live_;
  std::vector<std::vector<Index>> took_;  // the vertices whose places a vertex took
};

}  // namespace

std::size_t collapse_short_edges(TriangleSoup& soup, double length) {
  Collapser collapser(soup);
  std::size_t collapsed = 0;
  // One collapse per look at the short edges, shortest first: one that keeps
  // the surface's shape if any does, else any other (it can free one that
  // keeps the shape: the end that had to stay may then go). A few hairs per
  // piece: the looks cost their number times the faces.
  const auto collapse_one = [&](bool keep_shape) {
    for (const auto& edge : collapser.short_edges(length)) {
      if (collapser.collapse(std::get<1>(edge), std::get<2>(edge), length, keep_shape)) return true;
    }
    return false;
  };
  while (collapse_one(true) || collapse_one(false)) ++collapsed;
  if (collapsed > 0) collapser.compact();
  return collapsed;
}

}  // namespace fabmesh
