// The weld candidate: boundary edges by sorting the faces' edges, then for
// each boundary edge the other boundary edge whose ends are nearest its own,
// found through the boundary vertices on a grid whose cells are the largest
// tolerance worth suggesting (a fraction of the mean edge), so only the 27
// cells around an end can hold a partner near enough.

#include "geometry/mesh/weld_hint.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace fabmesh {
namespace {

/// The boundary edges (edges of exactly one face) as (lower, higher) vertex pairs, ascending.
std::vector<std::pair<std::uint32_t, std::uint32_t>> boundary_edges(const TriangleSoup& soup) {
  std::vector<std::uint64_t> edges;
  edges.reserve(3 * soup.triangles.size());
  for (const auto& t : soup.triangles) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k];
      const std::uint32_t b = t[(k + 1) % 3];
      if (a != b) edges.push_back((std::uint64_t{std::min(a, b)} << 32) | std::max(a, b));
    }
  }
  std::sort(edges.begin(), edges.end());
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i == 1)
      out.emplace_back(static_cast<std::uint32_t>(edges[i] >> 32),
                       static_cast<std::uint32_t>(edges[i] & 0xffffffffu));
    i = j;
  }
  return out;
}

double mean_edge_length(const TriangleSoup& soup) {
  double sum = 0.0;
  for (const auto& t : soup.triangles) {
    for (int k = 0; k < 3; ++k) sum += (soup.vertices[t[(k + 1) % 3]] - soup.vertices[t[k]]).norm();
  }
  return soup.triangles.empty() ? 0.0 : sum / (3.0 * static_cast<double>(soup.triangles.size()));
}

/// x rounded up to two significant digits (1.23e-5 -> 1.3e-5): the double
/// nearest that decimal (which prints as it), never below x.
double round_up_two_digits(double x) {
  const int exponent = static_cast<int>(std::floor(std::log10(x))) - 1;  // of the second digit
  long digits = std::lround(std::floor(x / std::pow(10.0, exponent)));
  double value = 0.0;
  for (;; ++digits) {
    value = std::stod(std::to_string(digits) + "e" + std::to_string(exponent));
    if (value >= x) return value;
  }
}

using Cell = std::array<std::int64_t, 3>;

/// Boundary vertices sorted by grid cell, for lookups of the 27 cells around one.
class CellIndex {
 public:
  CellIndex(const TriangleSoup& soup, const std::vector<std::uint32_t>& vertices, double side) : side_(side) {
    entries_.reserve(vertices.size());
    for (const std::uint32_t v : vertices) entries_.push_back({cell_of(soup.vertices[v]), v});
    std::sort(entries_.begin(), entries_.end());
  }

  Cell cell_of(const Vec3& p) const {
    return {static_cast<std::int64_t>(std::floor(p.x() / side_)),
            static_cast<std::int64_t>(std::floor(p.y() / side_)),
            static_cast<std::int64_t>(std::floor(p.z() / side_))};
  }

  /// Calls visit(w) for each vertex w in the cell `c`.
  template <class Visit>
  void for_each_in(const Cell& c, Visit&& visit) const {
    auto it = std::lower_bound(entries_.begin(), entries_.end(), Entry{c, 0});
    for (; it != entries_.end() && it->cell == c; ++it) visit(it->vertex);
  }

 private:
  struct Entry {
    Cell cell;
    std::uint32_t vertex;
    bool operator<(const Entry& o) const { return cell != o.cell ? cell < o.cell : vertex < o.vertex; }
  };
  double side_;
  std::vector<Entry> entries_;
};

constexpr std::size_t kComparisonsPerVertex = 64;  ///< beyond this on average, no candidate

}  // namespace

std::optional<WeldCandidate> weld_candidate(const TriangleSoup& soup) {
  for (const Vec3& p : soup.vertices) {
    if (!p.allFinite()) return std::nullopt;
  }
  const auto edges = boundary_edges(soup);
  if (edges.empty()) return std::nullopt;
  WeldCandidate out;
  out.mean_edge = mean_edge_length(soup);
  const double limit = kWeldHintFraction * out.mean_edge;
  if (!(limit > 0.0) || !std::isfinite(limit)) return std::nullopt;
  // The boundary edges at each vertex, and the boundary vertices on a grid.
  std::vector<std::uint32_t> vertices;
  for (const auto& [a, b] : edges) {
    vertices.push_back(a);
    vertices.push_back(b);
  }
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  for (const std::uint32_t v : vertices) {
    if (soup.vertices[v].cwiseAbs().maxCoeff() / limit > 1e15) return std::nullopt;  // as weld refuses
  }
  std::vector<std::pair<std::uint32_t, std::uint32_t>> at;  // (vertex, other end), sorted
  for (const auto& [a, b] : edges) {
    at.emplace_back(a, b);
    at.emplace_back(b, a);
  }
  std::sort(at.begin(), at.end());
  const CellIndex index(soup, vertices, limit);
  std::size_t budget = kComparisonsPerVertex * vertices.size();
  const auto distance = [&](std::uint32_t v, std::uint32_t w) {
    return v == w ? 0.0 : (soup.vertices[v] - soup.vertices[w]).norm();
  };
  for (const auto& edge : edges) {
    // The other boundary edge (c, d) with c near a and d near b that needs the least tolerance.
    const std::uint32_t a = edge.first;
    const std::uint32_t b = edge.second;
    double best = std::numeric_limits<double>::infinity();
    const Vec3& p = soup.vertices[a];
    const Cell cell = index.cell_of(p);
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          index.for_each_in({cell[0] + dx, cell[1] + dy, cell[2] + dz}, [&](std::uint32_t c) {
            const double ac = distance(a, c);
            if (!(ac <= limit)) return;
            auto it = std::lower_bound(at.begin(), at.end(), std::make_pair(c, std::uint32_t{0}));
            for (; it != at.end() && it->first == c; ++it) {
              if (budget > 0) --budget;
              const std::uint32_t d = it->second;
              if ((c == a && d == b) || (c == b && d == a)) continue;  // the edge itself
              best = std::min(best, std::max(ac, distance(b, d)));
            }
          });
        }
      }
    }
    if (budget == 0 || !(best <= limit)) return std::nullopt;
    out.closing_distance = std::max(out.closing_distance, best);
  }
  if (!(out.closing_distance > 0.0)) return std::nullopt;
  out.tolerance = round_up_two_digits(out.closing_distance);
  return out;
}

}  // namespace fabmesh
