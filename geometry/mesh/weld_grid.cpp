// The tolerance weld on a two-level grid.
//
// Let S be the smallest power of two >= tol (1 + 1e-9) and f = S / 4. Every
// distinct position p lies in the fine cell floor(p / f) (exact: f is a power
// of two) and the coarse cell of side S containing it.
//  - Two positions in one fine cell are less than f sqrt(3) < 0.87 tol apart,
//    so their computed distance is <= tol: a fine cell's members are one
//    group with no test. A fine cell is one element of the union-find.
//  - Two positions whose computed distance is <= tol lie in the same or
//    adjacent coarse cells (their exact distance is < S). So only pairs of
//    fine cells in one coarse cell or in two adjacent ones are looked at,
//    each unordered pair once, and each is settled by the first rule that
//    applies: already in one group (skip); the tight boxes of their members
//    are farther apart than tol (skip); the farthest points of those boxes
//    are within tol (unite, no test); else test member pairs, stopping at the
//    first pair within tol.
// Cost: O(n) to hash the exact positions, O(m log m) to sort the m distinct
// positions, 13 hash look-ups per coarse cell, at most 27 * 64 fine-cell
// pairs per fine cell (O(1) each with path halving and union by size), plus
// the member tests of fine-cell pairs left undecided by their boxes. Those
// tests are the only superlinear term: a pair of fine cells with a and b
// members costs at most a * b tests, and only while no earlier test joined
// them; it needs two clusters whose boxes straddle the tolerance sphere
// without any witness pair. Everything in one cell (a tolerance larger than
// the model) costs O(m): one fine cell, or a few joined by their boxes.

#include "geometry/mesh/weld_grid.h"

#include <fmt/format.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "geometry/core/disjoint_sets.h"
#include "geometry/core/errors.h"
#include "geometry/mesh/hash_mix.h"

namespace fabmesh {
namespace {

/// Union-find over dense ids (geometry/core/disjoint_sets.h) that also
/// keeps, for each set, the lowest vertex index among its members.
class DisjointSetsWithLowest {
 public:
  explicit DisjointSetsWithLowest(std::vector<std::uint32_t> lowest)
      : sets_(lowest.size()), lowest_(std::move(lowest)) {}
  std::uint32_t find(std::uint32_t i) { return sets_.find(i); }
  void unite(std::uint32_t a, std::uint32_t b) {
    a = sets_.find(a);
    b = sets_.find(b);
    if (!sets_.unite(a, b)) return;
    const std::uint32_t root = std::min(a, b);  // DisjointSets keeps the smaller id as the root
    lowest_[root] = std::min(lowest_[a], lowest_[b]);
  }
  /// The lowest vertex index in the set of i.
  std::uint32_t lowest(std::uint32_t i) { return lowest_[sets_.find(i)]; }

 private:
  DisjointSets<std::uint32_t> sets_;
  std::vector<std::uint32_t> lowest_;
};

using Cell = std::array<std::int64_t, 3>;

/// floor(a / 4) for negative a too.
std::int64_t floor_div4(std::int64_t a) { return a >= 0 ? a / 4 : -((-a + 3) / 4); }

/// A distinct position: its fine cell, coarse cell and vertex index.
struct Site {
  Cell fine;
  Cell coarse;
  std::uint32_t index;
};

bool same(const Cell& a, const Cell& b) { return a[0] == b[0] && a[1] == b[1] && a[2] == b[2]; }

bool operator<(const Site& a, const Site& b) {
  for (int k = 0; k < 3; ++k) {
    if (a.coarse[k] != b.coarse[k]) return a.coarse[k] < b.coarse[k];
  }
  for (int k = 0; k < 3; ++k) {
    if (a.fine[k] != b.fine[k]) return a.fine[k] < b.fine[k];
  }
  return a.index < b.index;
}

/// Open-addressing map from coarse cell to its id, with a one-bit-per-slot
/// presence filter 8 times larger than the cell count: with a fine
/// tolerance most neighbours are empty, and the filter (1 MB per 1e6 cells,
/// cache-resident) answers those without touching the table.
class CellTable {
 public:
  explicit CellTable(const std::vector<Cell>& cells) : cells_(cells) {
    std::size_t size = 16;
    while (size < 2 * cells.size()) size *= 2;
    slots_.assign(size, 0);
    seen_.assign(size / 8 + 1, 0);  // 4 * size bits
    for (std::uint32_t c = 0; c < cells.size(); ++c) {
      const std::uint64_t h = hash(cells[c]);
      const std::uint64_t bit = (h >> 32) & (4 * size - 1);
      seen_[bit / 64] |= std::uint64_t{1} << (bit % 64);
      std::size_t s = h & (size - 1);
      while (slots_[s] != 0) s = (s + 1) & (size - 1);
      slots_[s] = c + 1;
    }
  }
  /// The id of `cell`, or -1 when no position lies in it.
  std::int64_t find(const Cell& cell) const {
    const std::uint64_t h = hash(cell);
    const std::size_t mask = slots_.size() - 1;
    const std::uint64_t bit = (h >> 32) & (4 * slots_.size() - 1);
    if (!(seen_[bit / 64] >> (bit % 64) & 1)) return -1;
    for (std::size_t s = h & mask; slots_[s] != 0; s = (s + 1) & mask) {
      if (same(cells_[slots_[s] - 1], cell)) return slots_[s] - 1;
    }
    return -1;
  }

 private:
  static std::uint64_t hash(const Cell& c) {
    std::uint64_t h = 0;
    for (const std::int64_t v : c) h = mix64(h ^ static_cast<std::uint64_t>(v));
    return h;
  }
  const std::vector<Cell>& cells_;
  std::vector<std::uint32_t> slots_;
  std::vector<std::uint64_t> seen_;
};

/// The grid: sites sorted by coarse cell, fine cell and index; fine cells
/// and coarse cells as ranges of it.
class Grid {
 public:
  Grid(const std::vector<Vec3>& vertices, std::vector<Site> sites, double tol)
      : vertices_(vertices), sites_(std::move(sites)), tol_(tol) {
    tbb::parallel_sort(sites_.begin(), sites_.end());
    for (std::size_t k = 0; k < sites_.size(); ++k) {
      if (k == 0 || !same(sites_[k].fine, sites_[k - 1].fine)) {
        if (k == 0 || !same(sites_[k].coarse, sites_[k - 1].coarse)) {
          coarse_.push_back(sites_[k].coarse);
          coarse_first_.push_back(static_cast<std::uint32_t>(fine_first_.size()));
        }
        fine_first_.push_back(static_cast<std::uint32_t>(k));
        box_.push_back({vertices[sites_[k].index], vertices[sites_[k].index]});
      }
      Box& b = box_.back();
      b.lo = b.lo.cwiseMin(vertices[sites_[k].index]);
      b.hi = b.hi.cwiseMax(vertices[sites_[k].index]);
    }
    fine_first_.push_back(static_cast<std::uint32_t>(sites_.size()));
    coarse_first_.push_back(static_cast<std::uint32_t>(box_.size()));
  }

  /// rep[i] for every site of the grid (other entries untouched).
  void groups(std::vector<std::uint32_t>& rep) const {
    std::vector<std::uint32_t> lowest(box_.size());
    for (std::size_t c = 0; c < box_.size(); ++c) lowest[c] = sites_[fine_first_[c]].index;
    DisjointSetsWithLowest sets(std::move(lowest));
    const CellTable table(coarse_);
    for (std::uint32_t c = 0; c < coarse_.size(); ++c) {
      for (std::uint32_t a = coarse_first_[c]; a < coarse_first_[c + 1]; ++a) {
        for (std::uint32_t b = a + 1; b < coarse_first_[c + 1]; ++b) settle(a, b, sets);
      }
      for (int dx = 0; dx <= 1; ++dx) {  // the 13 neighbours after c in lexicographic order
        for (int dy = dx == 0 ? 0 : -1; dy <= 1; ++dy) {
          for (int dz = dx == 0 && dy == 0 ? 1 : -1; dz <= 1; ++dz) {
            const std::int64_t d = table.find({coarse_[c][0] + dx, coarse_[c][1] + dy, coarse_[c][2] + dz});
            if (d < 0) continue;
            for (std::uint32_t a = coarse_first_[c]; a < coarse_first_[c + 1]; ++a) {
              for (std::uint32_t b = coarse_first_[d]; b < coarse_first_[d + 1]; ++b) settle(a, b, sets);
            }
          }
        }
      }
    }
    for (std::uint32_t c = 0; c < box_.size(); ++c) {
      const std::uint32_t low = sets.lowest(c);
      for (std::uint32_t k = fine_first_[c]; k < fine_first_[c + 1]; ++k) rep[sites_[k].index] = low;
    }
  }

 private:
  struct Box {
    Vec3 lo, hi;
  };

  /// Decides whether fine cells a and b are joined (see the file comment).
  void settle(std::uint32_t a, std::uint32_t b, DisjointSetsWithLowest& sets) const {
    if (sets.find(a) == sets.find(b)) return;
    const Box& p = box_[a];
    const Box& q = box_[b];
    double near2 = 0.0;
    double far2 = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double gap = std::max({0.0, q.lo[k] - p.hi[k], p.lo[k] - q.hi[k]});
      const double span = std::max(q.hi[k] - p.lo[k], p.hi[k] - q.lo[k]);
      near2 += gap * gap;
      far2 += span * span;
    }
    const double tol2 = tol_ * tol_;
    if (near2 > tol2 * (1 + 1e-9)) return;  // every computed distance > tol
    if (far2 < tol2 * (1 - 1e-9)) {         // every computed distance < tol
      sets.unite(a, b);
      return;
    }
    for (std::uint32_t i = fine_first_[a]; i < fine_first_[a + 1]; ++i) {
      const Vec3& x = vertices_[sites_[i].index];
      for (std::uint32_t j = fine_first_[b]; j < fine_first_[b + 1]; ++j) {
        if ((vertices_[sites_[j].index] - x).norm() <= tol_) {
          sets.unite(a, b);
          return;
        }
      }
    }
  }

  const std::vector<Vec3>& vertices_;
  std::vector<Site> sites_;
  double tol_;
  std::vector<Cell> coarse_;                 ///< coarse cells, in sorted order
  std::vector<std::uint32_t> coarse_first_;  ///< first fine cell of each coarse cell (+ end)
  std::vector<std::uint32_t> fine_first_;    ///< first site of each fine cell (+ end)
  std::vector<Box> box_;                     ///< tight box of each fine cell's members
};

}  // namespace

std::vector<std::uint32_t> tolerance_groups(const std::vector<Vec3>& vertices,
                                            const std::vector<std::uint32_t>& exact, double tol) {
  int e = 0;
  std::frexp(tol * (1 + 1e-9), &e);         // 2^(e-1) <= t < 2^e
  const double f = std::ldexp(1.0, e - 2);  // fine cell: S / 4 with S = 2^e >= tol (1 + 1e-9)
  if (!(f > 0.0)) {
    throw RangeError("weld tolerance", tol, fmt::format("weld tolerance = {} is too small", tol));
  }
  std::vector<Site> sites;
  for (std::uint32_t i = 0; i < vertices.size(); ++i) {
    const Vec3& p = vertices[i];
    if (exact[i] != i || !std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z())) continue;
    Site s{{}, {}, i};
    for (int a = 0; a < 3; ++a) {
      if (std::abs(std::floor(p[a] / tol)) > 1e15) {  // cells must stay exact in int64 and double
        throw RangeError("weld tolerance", tol,
                         fmt::format("weld tolerance = {} is too small for coordinate {}", tol, p[a]));
      }
      const double q = p[a] / f;  // exact but for underflow, which only matters at 0
      s.fine[a] = static_cast<std::int64_t>(p[a] < 0 && q == 0 ? -1.0 : std::floor(q));
      s.coarse[a] = floor_div4(s.fine[a]);
    }
    sites.push_back(s);
  }
  std::vector<std::uint32_t> rep(vertices.size());
  for (std::uint32_t i = 0; i < vertices.size(); ++i) rep[i] = exact[i];
  Grid(vertices, std::move(sites), tol).groups(rep);
  // Vertices at a site's position follow the site.
  for (std::uint32_t i = 0; i < vertices.size(); ++i) rep[i] = rep[exact[i]];
  return rep;
}

}  // namespace fabmesh
