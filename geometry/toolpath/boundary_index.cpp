#include "geometry/toolpath/boundary_index.h"

#include <algorithm>

#include "geometry/core/error_checks.h"

namespace fabmesh {
namespace {

Vec2 closest_on_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double len2 = d.squaredNorm();
  if (len2 == 0.0) return a;
  return a + std::clamp((p - a).dot(d) / len2, 0.0, 1.0) * d;
}

bool segments_cross(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, Vec2* where) {
  const Vec2 r = b - a, s = d - c;
  const double den = cross2(r, s);
  if (den == 0.0) return false;
  const double t = cross2(c - a, s) / den, u = cross2(c - a, r) / den;
  if (t < 0.0 || t > 1.0 || u < 0.0 || u > 1.0) return false;
  *where = a + t * r;
  return true;
}

}  // namespace

double segment_distance(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, Vec2* on_first,
                        Vec2* on_second) {
  Vec2 x;
  if (segments_cross(a, b, c, d, &x)) {
    if (on_first) *on_first = x;
    if (on_second) *on_second = x;
    return 0.0;
  }
  double best = INFINITY;
  Vec2 p1, p2;
  auto consider = [&](const Vec2& on1, const Vec2& on2) {
    const double dist = (on1 - on2).norm();
    if (dist < best) best = dist, p1 = on1, p2 = on2;
  };
  consider(a, closest_on_segment(a, c, d));
  consider(b, closest_on_segment(b, c, d));
  consider(closest_on_segment(c, a, b), c);
  consider(closest_on_segment(d, a, b), d);
  if (on_first) *on_first = p1;
  if (on_second) *on_second = p2;
  return best;
}

BoundaryIndex::BoundaryIndex(std::vector<BoundaryEdge> edges, double cell)
    : edges_(std::move(edges)), cell_(cell) {
  require_positive("cell", cell);
  for (std::size_t i = 0; i < edges_.size(); ++i) {
    const BoundaryEdge& e = edges_[i];
    // Cover the edge with the boxes of sub-pieces no longer than a cell (a long edge touches few cells).
    const int pieces = std::max(1, static_cast<int>(std::ceil((e.b - e.a).norm() / cell_)));
    std::vector<std::int64_t> keys;
    for (int k = 0; k < pieces; ++k) {
      const Vec2 p = e.a + (e.b - e.a) * (static_cast<double>(k) / pieces);
      const Vec2 q = e.a + (e.b - e.a) * (static_cast<double>(k + 1) / pieces);
      for (std::int64_t ix = cell_of(std::min(p.x(), q.x())); ix <= cell_of(std::max(p.x(), q.x())); ++ix) {
        for (std::int64_t iy = cell_of(std::min(p.y(), q.y())); iy <= cell_of(std::max(p.y(), q.y())); ++iy) {
          keys.push_back(key(ix, iy));
        }
      }
    }
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    for (std::int64_t k : keys) grid_[k].push_back(static_cast<std::uint32_t>(i));
  }
}

BoundaryIndex::Nearest BoundaryIndex::nearest(const Vec2& p, const Vec2& q, double radius,
                                              std::size_t skip_loop) const {
  std::vector<std::uint32_t> candidates;
  const int pieces = std::max(1, static_cast<int>(std::ceil((q - p).norm() / cell_)));
  for (int k = 0; k < pieces; ++k) {
    const Vec2 a = p + (q - p) * (static_cast<double>(k) / pieces);
    const Vec2 b = p + (q - p) * (static_cast<double>(k + 1) / pieces);
    const std::int64_t x0 = cell_of(std::min(a.x(), b.x()) - radius),
                       x1 = cell_of(std::max(a.x(), b.x()) + radius);
    const std::int64_t y0 = cell_of(std::min(a.y(), b.y()) - radius),
                       y1 = cell_of(std::max(a.y(), b.y()) + radius);
    for (std::int64_t ix = x0; ix <= x1; ++ix) {
      for (std::int64_t iy = y0; iy <= y1; ++iy) {
        const auto it = grid_.find(key(ix, iy));
        if (it != grid_.end()) candidates.insert(candidates.end(), it->second.begin(), it->second.end());
      }
    }
  }
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  Nearest best;
  for (std::uint32_t i : candidates) {
    const BoundaryEdge& e = edges_[i];
    if (e.loop == skip_loop) continue;
    Vec2 on_query, on_edge;
    const double d = segment_distance(p, q, e.a, e.b, &on_query, &on_edge);
    if (d <= radius && d < best.distance) {
      best.distance = d;
      best.edge = i;
      best.on_edge = on_edge;
      best.on_query = on_query;
    }
  }
  return best;
}

}  // namespace fabmesh
