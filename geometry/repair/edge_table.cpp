#include "geometry/repair/edge_table.h"

#include <algorithm>
#include <array>
#include <limits>

namespace fabmesh {
namespace {

bool repeated_corner(const std::array<std::uint32_t, 3>& t) {
  return t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
}

std::pair<std::uint32_t, std::uint32_t> key(const FaceSide& s) {
  return {std::min(s.from, s.to), std::max(s.from, s.to)};
}

}  // namespace

EdgeTable edge_table(const TriangleSoup& soup) {
  EdgeTable table;
  table.sides.reserve(3 * soup.triangles.size());
  for (std::size_t f = 0; f < soup.triangles.size(); ++f) {
    const auto& t = soup.triangles[f];
    if (repeated_corner(t)) continue;
    for (int k = 0; k < 3; ++k)
      table.sides.push_back(FaceSide{static_cast<std::uint32_t>(f), t[k], t[(k + 1) % 3]});
  }
  std::sort(table.sides.begin(), table.sides.end(), [](const FaceSide& a, const FaceSide& b) {
    const auto ka = key(a), kb = key(b);
    return ka != kb ? ka < kb : a.face < b.face;
  });
  for (std::size_t i = 0; i < table.sides.size(); ++i) {
    if (i == 0 || key(table.sides[i]) != key(table.sides[i - 1])) table.starts.push_back(i);
  }
  table.starts.push_back(table.sides.size());
  if (table.sides.empty()) table.starts.clear();
  return table;
}

std::vector<bool> border_vertices(const TriangleSoup& soup, const EdgeTable& edges) {
  std::vector<bool> border(soup.vertices.size(), false);
  for (std::size_t e = 0; e < edges.edges(); ++e) {
    if (edges.faces_of(e) != 1) continue;
    border[edges.side(e, 0).from] = true;
    border[edges.side(e, 0).to] = true;
  }
  return border;
}

std::vector<std::array<std::size_t, 3>> face_edges(const TriangleSoup& soup, const EdgeTable& edges) {
  constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  std::vector<std::array<std::size_t, 3>> result(soup.triangles.size(), {kNone, kNone, kNone});
  for (std::size_t e = 0; e < edges.edges(); ++e) {
    for (std::size_t k = 0; k < edges.faces_of(e); ++k) {
      const FaceSide& s = edges.side(e, k);
      const auto& t = soup.triangles[s.face];
      for (int c = 0; c < 3; ++c) {
        if (t[c] == s.from && t[(c + 1) % 3] == s.to) result[s.face][c] = e;
      }
    }
  }
  return result;
}

}  // namespace fabmesh
