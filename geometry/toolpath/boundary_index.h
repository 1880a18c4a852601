#pragma once
// The part's boundary as short edges sampled from the exact curves, in a
// uniform grid, for nearest-edge queries: the web between loops and the
// clearance of the tool-centre path.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

#include "geometry/core/types.h"

namespace fabmesh {

/// One edge of a sampled loop and where it comes from.
struct BoundaryEdge {
  Vec2 a{0.0, 0.0}, b{0.0, 0.0};
  std::size_t loop = 0;     ///< index of the loop (0: the outline, then the holes)
  std::size_t segment = 0;  ///< the curve segment the edge samples (of its start point)
};

/// Distance between segments [a, b] and [c, d]; the closest points go to
/// `on_first` / `on_second` when given.
double segment_distance(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, Vec2* on_first = nullptr,
                        Vec2* on_second = nullptr);

class BoundaryIndex {
 public:
  /// The closest edge found by a query.
  struct Nearest {
    double distance = std::numeric_limits<double>::infinity();
    std::size_t edge = 0;
    Vec2 on_edge{0.0, 0.0};   ///< closest point on the edge
    Vec2 on_query{0.0, 0.0};  ///< closest point on the queried segment
  };

  /// Indexes `edges` in square cells of side `cell` (> 0).
  BoundaryIndex(std::vector<BoundaryEdge> edges, double cell);

  const std::vector<BoundaryEdge>& edges() const { return edges_; }

  /// The edge nearest to segment [p, q] among those within `radius`, skipping
  /// edges of loop `skip_loop` (npos: none). Ties go to the lower edge index,
  /// so results do not depend on the grid's hashing. distance = infinity when
  /// no edge lies within `radius`.
  Nearest nearest(const Vec2& p, const Vec2& q, double radius,
                  std::size_t skip_loop = static_cast<std::size_t>(-1)) const;

 private:
  std::int64_t key(std::int64_t ix, std::int64_t iy) const { return ix * 4294967311LL + iy; }
  std::int64_t cell_of(double v) const { return static_cast<std::int64_t>(std::floor(v / cell_)); }

  std::vector<BoundaryEdge> edges_;
  double cell_;
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> grid_;
};

}  // namespace fabmesh
