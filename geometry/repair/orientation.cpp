#include "geometry/repair/orientation.h"

#include <algorithm>
#include <deque>
#include <numeric>

#include "geometry/core/disjoint_sets.h"
#include "geometry/repair/edge_table.h"

namespace fabmesh {

FaceComponents face_components(const TriangleSoup& soup) {
  DisjointSets<std::uint32_t> sets(static_cast<std::uint32_t>(soup.vertices.size()));
  for (const auto& t : soup.triangles) {
    sets.unite(t[0], t[1]);
    sets.unite(t[1], t[2]);
  }
  // Number the roots in order of their lowest used vertex.
  std::vector<bool> used(soup.vertices.size(), false);
  for (const auto& t : soup.triangles) {
    for (const std::uint32_t v : t) used[v] = true;
  }
  std::vector<std::uint32_t> number(soup.vertices.size(), kNoIndex);
  FaceComponents components;
  for (std::uint32_t v = 0; v < soup.vertices.size(); ++v) {
    if (!used[v]) continue;
    std::uint32_t& n = number[sets.find(v)];
    if (n == kNoIndex) n = static_cast<std::uint32_t>(components.count++);
  }
  components.of_face.reserve(soup.triangles.size());
  for (const auto& t : soup.triangles) components.of_face.push_back(number[sets.find(t[0])]);
  return components;
}

namespace {

/// Per face, its neighbours across edges of two faces and whether they agree (traverse the edge oppositely).
struct Neighbour {
  std::uint32_t face;
  bool agree;
};

std::vector<std::vector<Neighbour>> neighbours(const TriangleSoup& soup) {
  const EdgeTable edges = edge_table(soup);
  std::vector<std::vector<Neighbour>> result(soup.triangles.size());
  for (std::size_t e = 0; e < edges.edges(); ++e) {
    if (edges.faces_of(e) != 2) continue;
    const FaceSide& a = edges.side(e, 0);
    const FaceSide& b = edges.side(e, 1);
    const bool agree = a.from == b.to;
    result[a.face].push_back({b.face, agree});
    result[b.face].push_back({a.face, agree});
  }
  return result;
}

}  // namespace

bool orient_consistently(TrackedSoup& mesh, RepairLog& log, RepairPlace* where) {
  const auto next = neighbours(mesh.soup);
  const std::size_t n = mesh.soup.triangles.size();
  std::vector<int> flip(n, -1);  // -1 unvisited, 0 keep, 1 flip
  for (std::uint32_t seed = 0; seed < n; ++seed) {
    if (flip[seed] != -1) continue;
    std::vector<std::uint32_t> part{seed};
    flip[seed] = 0;
    for (std::size_t i = 0; i < part.size(); ++i) {
      const std::uint32_t f = part[i];
      for (const Neighbour& g : next[f]) {
        const int want = flip[f] ^ (g.agree ? 0 : 1);
        if (flip[g.face] == -1) {
          flip[g.face] = want;
          part.push_back(g.face);
        } else if (flip[g.face] != want) {
          if (where != nullptr) *where = face_place(mesh, g.face);
          return false;
        }
      }
    }
    const auto flipped = static_cast<std::size_t>(
        std::count_if(part.begin(), part.end(), [&](std::uint32_t f) { return flip[f] == 1; }));
    if (2 * flipped > part.size()) {
      for (const std::uint32_t f : part) flip[f] ^= 1;
    }
  }
  for (std::uint32_t f = 0; f < n; ++f) {
    if (flip[f] != 1) continue;
    auto& t = mesh.soup.triangles[f];
    std::swap(t[1], t[2]);
    log.add(RepairStep::Orientation, face_place(mesh, f));
  }
  return true;
}

void flip_components(TrackedSoup& mesh, const FaceComponents& components, const std::vector<bool>& flip) {
  for (std::size_t f = 0; f < mesh.soup.triangles.size(); ++f) {
    if (flip[components.of_face[f]]) std::swap(mesh.soup.triangles[f][1], mesh.soup.triangles[f][2]);
  }
}

}  // namespace fabmesh
