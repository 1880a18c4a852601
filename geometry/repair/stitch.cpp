#include "geometry/repair/stitch.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>
#include <utility>

#include "geometry/repair/edge_table.h"

namespace fabmesh {
namespace {

struct OnEdge {
  double t;
  std::uint32_t vertex;
};

/// A uniform grid of the border vertices.
class VertexGrid {
 public:
  VertexGrid(const std::vector<Vec3>& points, const std::vector<bool>& member, double cell) : cell_(cell) {
    for (std::uint32_t v = 0; v < points.size(); ++v) {
      if (member[v]) cells_[key(points[v])].push_back(v);
    }
  }
  /// The vertices in the cells that meet the box [lo, hi].
  template <class Visit>
  void visit(const Vec3& lo, const Vec3& hi, const Visit& visit) const {
    const auto a = key(lo), b = key(hi);
    for (long long x = a[0]; x <= b[0]; ++x)
      for (long long y = a[1]; y <= b[1]; ++y)
        for (long long z = a[2]; z <= b[2]; ++z) {
          const auto it = cells_.find({x, y, z});
          if (it == cells_.end()) continue;
          for (const std::uint32_t v : it->second) visit(v);
        }
  }

 private:
  std::array<long long, 3> key(const Vec3& p) const {
    return {static_cast<long long>(std::floor(p.x() / cell_)),
            static_cast<long long>(std::floor(p.y() / cell_)),
            static_cast<long long>(std::floor(p.z() / cell_))};
  }
  double cell_;
  std::map<std::array<long long, 3>, std::vector<std::uint32_t>> cells_;
};

double median_border_edge(const TriangleSoup& soup, const EdgeTable& edges) {
  std::vector<double> lengths;
  for (std::size_t e = 0; e < edges.edges(); ++e) {
    if (edges.faces_of(e) != 1) continue;
    const FaceSide& s = edges.side(e, 0);
    lengths.push_back((soup.vertices[s.to] - soup.vertices[s.from]).norm());
  }
  if (lengths.empty()) return 0.0;
  std::nth_element(lengths.begin(), lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2),
                   lengths.end());
  return lengths[lengths.size() / 2];
}

/// The border vertices within `tolerance` of the interior of border edge s, by position along it.
std::vector<OnEdge> vertices_on(const TrackedSoup& mesh, const FaceSide& s, const VertexGrid& grid,
                                double tolerance) {
  const Vec3& a = mesh.soup.vertices[s.from];
  const Vec3& b = mesh.soup.vertices[s.to];
  const Vec3 d = b - a;
  const double length2 = d.squaredNorm();
  std::vector<OnEdge> found;
  if (!(length2 > 0.0)) return found;
  const Vec3 pad = Vec3::Constant(tolerance);
  grid.visit(a.cwiseMin(b) - pad, a.cwiseMax(b) + pad, [&](std::uint32_t v) {
    if (v == s.from || v == s.to) return;
    const Vec3& p = mesh.soup.vertices[v];
    const double t = (p - a).dot(d) / length2;
    const double margin = tolerance / std::sqrt(length2);
    if (t <= margin || t >= 1.0 - margin) return;
    if ((a + t * d - p).norm() <= tolerance) found.push_back({t, v});
  });
  std::sort(found.begin(), found.end(), [](const OnEdge& x, const OnEdge& y) { return x.t < y.t; });
  return found;
}

/// Replaces face s.face (whose side s is) by the fan through `on` from its opposite corner.
void split_face(TrackedSoup& mesh, const FaceSide& s, const std::vector<OnEdge>& on,
                std::vector<std::array<std::uint32_t, 3>>& added, std::vector<std::uint32_t>& added_origin) {
  const auto& t = mesh.soup.triangles[s.face];
  std::uint32_t c = t[0];
  for (const std::uint32_t v : t) {
    if (v != s.from && v != s.to) c = v;
  }
  std::uint32_t previous = s.from;
  for (const OnEdge& o : on) {
    added.push_back({previous, o.vertex, c});
    added_origin.push_back(mesh.face_origin[s.face]);
    previous = o.vertex;
  }
  added.push_back({previous, s.to, c});
  added_origin.push_back(mesh.face_origin[s.face]);
}

std::size_t stitch_round(TrackedSoup& mesh, double tolerance, RepairLog& log) {
  const EdgeTable edges = edge_table(mesh.soup);
  const std::vector<bool> border = border_vertices(mesh.soup, edges);
  const double cell = std::max(median_border_edge(mesh.soup, edges), 4.0 * tolerance);
  if (!(cell > 0.0)) return 0;
  const VertexGrid grid(mesh.soup.vertices, border, cell);
  std::vector<bool> remove(mesh.soup.triangles.size(), false);
  std::vector<std::array<std::uint32_t, 3>> added;
  std::vector<std::uint32_t> added_origin;
  std::size_t inserted = 0;
  for (std::size_t e = 0; e < edges.edges(); ++e) {
    if (edges.faces_of(e) != 1) continue;
    const FaceSide& s = edges.side(e, 0);
    if (remove[s.face]) continue;  // one split per face and round
    const std::vector<OnEdge> on = vertices_on(mesh, s, grid, tolerance);
    if (on.empty()) continue;
    remove[s.face] = true;
    split_face(mesh, s, on, added, added_origin);
    for (const OnEdge& o : on) {
      RepairPlace place = vertex_place(mesh, o.vertex);
      place.face = mesh.face_origin[s.face];
      place.detail = fmt::format("border edge split at a vertex {:.3g} from it",
                                 (mesh.soup.vertices[s.from] +
                                  o.t * (mesh.soup.vertices[s.to] - mesh.soup.vertices[s.from]) - place.point)
                                     .norm());
      log.add(RepairStep::Stitch, place);
      ++inserted;
    }
  }
  remove_faces(mesh, remove);
  mesh.soup.triangles.insert(mesh.soup.triangles.end(), added.begin(), added.end());
  mesh.face_origin.insert(mesh.face_origin.end(), added_origin.begin(), added_origin.end());
  return inserted;
}

}  // namespace

std::size_t stitch_t_junctions(TrackedSoup& mesh, double tolerance, RepairLog& log) {
  std::size_t total = 0;
  for (int round = 0; round < 8; ++round) {
    const std::size_t inserted = stitch_round(mesh, tolerance, log);
    total += inserted;
    if (inserted == 0) break;
  }
  return total;
}

}  // namespace fabmesh
