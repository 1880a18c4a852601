#include "geometry/repair/weld_borders.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include "geometry/mesh/bounding_box.h"
#include "geometry/mesh/weld.h"
#include "geometry/mesh/weld_grid.h"
#include "geometry/repair/edge_table.h"

namespace fabmesh {
namespace {

double median_edge_length(const TriangleSoup& mesh) {
  std::vector<double> lengths;
  lengths.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      const double l = (mesh.vertices[t[k]] - mesh.vertices[t[(k + 1) % 3]]).norm();
      if (l > 0.0) lengths.push_back(l);
    }
  }
  if (lengths.empty()) return 0.0;
  auto mid = lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2);
  std::nth_element(lengths.begin(), mid, lengths.end());
  return *mid;
}

/// Per vertex, the sorted vertices sharing a face with it (border vertices only).
std::vector<std::vector<std::uint32_t>> face_neighbours(const TriangleSoup& mesh,
                                                        const std::vector<bool>& border) {
  std::vector<std::vector<std::uint32_t>> near(mesh.vertices.size());
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      if (!border[t[k]]) continue;
      near[t[k]].push_back(t[(k + 1) % 3]);
      near[t[k]].push_back(t[(k + 2) % 3]);
    }
  }
  for (auto& n : near) {
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
  }
  return near;
}

struct CellKey {
  long long x, y, z;
  bool operator==(const CellKey& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct CellHash {
  std::size_t operator()(const CellKey& k) const {
    return std::hash<long long>()(k.x * 73856093LL ^ k.y * 19349663LL ^ k.z * 83492791LL);
  }
};

/// Each border vertex's gap to its nearest border vertex sharing no face, when within `cap`.
std::vector<double> border_gaps(const TriangleSoup& mesh, const std::vector<bool>& border, double cap) {
  const auto near = face_neighbours(mesh, border);
  std::unordered_map<CellKey, std::vector<std::uint32_t>, CellHash> grid;
  auto cell = [&](const Vec3& p) {
    return CellKey{static_cast<long long>(std::floor(p.x() / cap)),
                   static_cast<long long>(std::floor(p.y() / cap)),
                   static_cast<long long>(std::floor(p.z() / cap))};
  };
  for (std::uint32_t v = 0; v < mesh.vertices.size(); ++v) {
    if (border[v]) grid[cell(mesh.vertices[v])].push_back(v);
  }
  std::vector<double> gaps;
  for (std::uint32_t v = 0; v < mesh.vertices.size(); ++v) {
    if (!border[v]) continue;
    const CellKey c = cell(mesh.vertices[v]);
    double best = cap;
    bool found = false;
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          const auto it = grid.find(CellKey{c.x + dx, c.y + dy, c.z + dz});
          if (it == grid.end()) continue;
          for (const std::uint32_t w : it->second) {
            if (w == v || std::binary_search(near[v].begin(), near[v].end(), w)) continue;
            const double d = (mesh.vertices[w] - mesh.vertices[v]).norm();
            if (d <= best) {
              best = d;
              found = true;
            }
          }
        }
    if (found) gaps.push_back(best);
  }
  return gaps;
}

}  // namespace

WeldChoice choose_weld_distance(const TriangleSoup& mesh, double requested) {
  WeldChoice choice;
  if (requested >= 0.0) {
    choice.distance = requested;
    choice.why = requested > 0.0 ? fmt::format("border vertices within {:g} (as asked)", requested)
                                 : "no border weld (as asked)";
    return choice;
  }
  const std::vector<bool> border = border_vertices(mesh, edge_table(mesh));
  if (std::none_of(border.begin(), border.end(), [](bool b) { return b; })) {
    choice.why = "no border: nothing to weld";
    return choice;
  }
  const BoundingBox box = bounding_box(mesh.vertices);
  choice.cap = std::min(1e-3 * box.size().norm(), 0.5 * median_edge_length(mesh));
  if (!(choice.cap > 0.0)) return choice;
  std::vector<double> gaps = border_gaps(mesh, border, choice.cap);
  choice.gaps = gaps.size();
  if (gaps.empty()) {
    choice.why = fmt::format("no border vertex within {:g} of another: no weld", choice.cap);
    return choice;
  }
  std::sort(gaps.begin(), gaps.end());
  // The jitter is most of the gaps: look for the jump from the median up.
  std::size_t last = gaps.size() - 1;
  for (std::size_t i = gaps.size() / 2; i + 1 < gaps.size(); ++i) {
    if (gaps[i + 1] > 10.0 * gaps[i] && gaps[i] > 0.0) {
      last = i;
      break;
    }
  }
  // Never below a few thousand rounding steps of the coordinates (the grid
  // weld's resolution): gaps that small are rounding, not shape.
  double magnitude = 0.0;
  for (const Vec3& p : mesh.vertices) magnitude = std::max(magnitude, p.cwiseAbs().maxCoeff());
  // Three times the largest jitter gap (copies of one corner chain beyond
  // their nearest neighbours), a third of the way to the first feature gap.
  double distance = 3.0 * gaps[last];
  if (last + 1 < gaps.size()) distance = std::min(distance, gaps[last + 1] / 3.0);
  choice.distance = std::max(std::min(distance, choice.cap), 1e-12 * magnitude);
  choice.why = fmt::format(
      "the largest of {} border vertex gaps below the first ten-fold jump above their median (gaps {:g} to "
      "{:g}; "
      "considered up to {:g}: 1e-3 of the size or half the median edge; at least 1e-12 of the largest "
      "coordinate)",
      last + 1, gaps.front(), gaps[last], choice.cap);
  return choice;
}

std::size_t weld_exact(TrackedSoup& mesh) {
  const WeldResult welded = weld(mesh.soup);
  std::vector<std::uint32_t> origin(welded.soup.vertices.size(), kNoIndex);
  for (std::size_t f = 0; f < welded.soup.triangles.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      std::uint32_t& o = origin[welded.soup.triangles[f][k]];
      o = std::min(o, mesh.vertex_origin[mesh.soup.triangles[f][k]]);
    }
  }
  mesh.soup = welded.soup;
  mesh.vertex_origin = std::move(origin);
  return welded.merged_vertices;
}

void weld_borders(TrackedSoup& mesh, double distance, RepairLog& log) {
  if (!(distance > 0.0)) return;
  const std::vector<bool> border = border_vertices(mesh.soup, edge_table(mesh.soup));
  std::vector<std::uint32_t> members;
  std::vector<Vec3> points;
  for (std::uint32_t v = 0; v < mesh.soup.vertices.size(); ++v) {
    if (!border[v]) continue;
    members.push_back(v);
    points.push_back(mesh.soup.vertices[v]);
  }
  std::vector<std::uint32_t> identity(points.size());
  std::iota(identity.begin(), identity.end(), 0u);
  const std::vector<std::uint32_t> groups = tolerance_groups(points, identity, distance);
  std::vector<std::uint32_t> target(mesh.soup.vertices.size());
  std::iota(target.begin(), target.end(), 0u);
  for (std::size_t i = 0; i < members.size(); ++i) {
    if (groups[i] == i) continue;
    const std::uint32_t v = members[i], into = members[groups[i]];
    target[v] = into;
    RepairPlace place = vertex_place(mesh, v);
    place.detail = fmt::format("moved {:.3g} onto vertex {}", (mesh.soup.vertices[into] - place.point).norm(),
                               mesh.vertex_origin[into]);
    log.add(RepairStep::Weld, place);
  }
  for (auto& t : mesh.soup.triangles) {
    for (std::uint32_t& v : t) v = target[v];
  }
  compact_vertices(mesh);
}

}  // namespace fabmesh
