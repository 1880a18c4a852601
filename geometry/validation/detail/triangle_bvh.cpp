#include "geometry/validation/detail/triangle_bvh.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace fabmesh {
namespace {

/// The float nearest to x that is <= x (resp. >= x), clamped to the finite
/// floats. Clamping is monotone, so boxes that overlap exactly still overlap;
/// and no box reaches an infinity, so none overlaps an empty box (lo = +inf,
/// hi = -inf), which a box from -inf to +inf would.
float round_down(double x) {
  constexpr float kMax = std::numeric_limits<float>::max();
  if (x >= static_cast<double>(kMax)) return kMax;
  if (x <= -static_cast<double>(kMax)) return -kMax;
  float f = static_cast<float>(x);
  if (static_cast<double>(f) > x) f = std::nextafter(f, -kMax);
  return f;
}
float round_up(double x) { return -round_down(-x); }

BoxF empty_box() {
  const float inf = std::numeric_limits<float>::infinity();
  return {{inf, inf, inf}, {-inf, -inf, -inf}};
}

void grow(BoxF& a, const BoxF& b) {
  for (int k = 0; k < 3; ++k) {
    a.lo[k] = std::min(a.lo[k], b.lo[k]);
    a.hi[k] = std::max(a.hi[k], b.hi[k]);
  }
}

/// Spreads the low 10 bits of x so that there are two zero bits between each.
std::uint64_t spread_bits(std::uint64_t x) {
  x &= 0x3ff;
  x = (x | (x << 16)) & 0x030000ff;
  x = (x | (x << 8)) & 0x0300f00f;
  x = (x | (x << 4)) & 0x030c30c3;
  x = (x | (x << 2)) & 0x09249249;
  return x;
}

template <class Body>
void for_range(std::size_t n, bool parallel, const Body& body) {
  if (parallel && n > 4096) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 2048),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t i = r.begin(); i != r.end(); ++i) body(i);
                      });
  } else {
    for (std::size_t i = 0; i < n; ++i) body(i);
  }
}

}  // namespace

BoxF triangle_box(const TriangleSoup& soup, std::uint32_t f) {
  const auto& t = soup.triangles[f];
  const Vec3& p = soup.vertices[t[0]];
  const Vec3& q = soup.vertices[t[1]];
  const Vec3& r = soup.vertices[t[2]];
  BoxF b;
  for (int k = 0; k < 3; ++k) {
    b.lo[k] = round_down(std::min({p[k], q[k], r[k]}));
    b.hi[k] = round_up(std::max({p[k], q[k], r[k]}));
  }
  return b;
}

BoxF rounded_box(const Vec3& lo, const Vec3& hi) {
  BoxF b;
  for (int k = 0; k < 3; ++k) {
    b.lo[k] = round_down(lo[k]);
    b.hi[k] = round_up(hi[k]);
  }
  return b;
}

TriangleBvh::TriangleBvh(const TriangleSoup& soup, const std::vector<char>& skip, bool parallel) {
  std::vector<std::uint32_t> active;
  active.reserve(soup.triangles.size());
  for (std::uint32_t f = 0; f < soup.triangles.size(); ++f) {
    if (skip.empty() || !skip[f]) active.push_back(f);
  }
  std::vector<BoxF> box(active.size());
  for_range(active.size(), parallel, [&](std::size_t i) { box[i] = triangle_box(soup, active[i]); });
  build(std::move(box), active, parallel);
}

TriangleBvh::TriangleBvh(std::vector<BoxF> boxes, const std::vector<std::uint32_t>& ids, bool parallel) {
  build(std::move(boxes), ids, parallel);
}

void TriangleBvh::build(std::vector<BoxF> box, const std::vector<std::uint32_t>& active, bool parallel) {
  const std::size_t n = active.size();
  // Morton keys of the box centres on a 1024^3 grid over their bounding box.
  float lo[3] = {INFINITY, INFINITY, INFINITY};
  float hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (const BoxF& b : box) {
    for (int k = 0; k < 3; ++k) {
      const float c = 0.5f * b.lo[k] + 0.5f * b.hi[k];
      lo[k] = std::min(lo[k], c);
      hi[k] = std::max(hi[k], c);
    }
  }
  double scale[3];
  for (int k = 0; k < 3; ++k) {
    const double extent = static_cast<double>(hi[k]) - static_cast<double>(lo[k]);
    scale[k] = extent > 0.0 && std::isfinite(extent) ? 1023.0 / extent : 0.0;
  }
  std::vector<std::uint64_t> key(n);
  for_range(n, parallel, [&](std::size_t i) {
    std::uint64_t code = 0;
    for (int k = 0; k < 3; ++k) {
      const double c = 0.5 * static_cast<double>(box[i].lo[k]) + 0.5 * static_cast<double>(box[i].hi[k]);
      double cell = (c - static_cast<double>(lo[k])) * scale[k];
      if (!(cell > 0.0)) cell = 0.0;  // NaN too (a box reaching both infinities)
      if (cell > 1023.0) cell = 1023.0;
      code |= spread_bits(static_cast<std::uint64_t>(cell)) << k;
    }
    key[i] = (code << 32) | i;  // unique keys: the order is the same for every sort
  });
  if (parallel) {
    tbb::parallel_sort(key.begin(), key.end());
  } else {
    std::sort(key.begin(), key.end());
  }
  faces_.resize(n);
  for_range(n, parallel, [&](std::size_t k) { faces_[k] = active[key[k] & 0xffffffffu]; });
  // Leaves, then each level of the tree from its children.
  const std::size_t leaves = leaf_count();
  leaf_base_ = 1;
  while (leaf_base_ < leaves) leaf_base_ *= 2;
  nodes_.assign(2 * leaf_base_, empty_box());
  leaf_boxes_.resize(leaves);
  for_range(leaves, parallel, [&](std::size_t l) {
    BoxF& b = nodes_[leaf_base_ + l];
    LeafBoxes& lanes = leaf_boxes_[l];
    for (std::size_t lane = 0; lane < kLeafSize; ++lane) {
      const std::size_t k = l * kLeafSize + lane;
      const BoxF tri = k < n ? box[key[k] & 0xffffffffu] : empty_box();
      grow(b, tri);
      for (int c = 0; c < 3; ++c) {
        lanes.lo[c][lane] = tri.lo[c];
        lanes.hi[c][lane] = tri.hi[c];
      }
    }
  });
  for (std::size_t level = leaf_base_ / 2; level >= 1; level /= 2) {
    for_range(level, parallel, [&](std::size_t i) {
      BoxF& b = nodes_[level + i];
      b = nodes_[2 * (level + i)];
      grow(b, nodes_[2 * (level + i) + 1]);
    });
  }
}

TriangleBvh::TaskCursor::TaskCursor(const TriangleBvh& bvh, std::size_t leaves_per_task)
    : bvh_(bvh), level_(1) {
  while (bvh.leaf_base_ / level_ > std::max<std::size_t>(leaves_per_task, 1)) level_ *= 2;
  stack_.push_back({1, 1});
}

bool TriangleBvh::TaskCursor::next(std::size_t n, std::vector<Task>& out) {
  out.clear();
  // The depth-first order of self(n) = [self(2n), self(2n + 1), pair(2n, 2n + 1)]
  // and pair(a, b) = [pair(2a, 2b), pair(2a, 2b + 1), pair(2a + 1, 2b), pair(2a + 1, 2b + 1)].
  while (!stack_.empty() && out.size() < n) {
    const Task t = stack_.back();
    stack_.pop_back();
    const BoxF& box = bvh_.nodes_[t.a];
    if (t.a == t.b ? box.lo[0] > box.hi[0] : !overlap(box, bvh_.nodes_[t.b])) {
      continue;
    }
    if (t.a >= level_) {
      out.push_back(t);
    } else if (t.a == t.b) {
      stack_.push_back({2 * t.a, 2 * t.a + 1});
      stack_.push_back({2 * t.a + 1, 2 * t.a + 1});
      stack_.push_back({2 * t.a, 2 * t.a});
    } else {
      stack_.push_back({2 * t.a + 1, 2 * t.b + 1});
      stack_.push_back({2 * t.a + 1, 2 * t.b});
      stack_.push_back({2 * t.a, 2 * t.b + 1});
      stack_.push_back({2 * t.a, 2 * t.b});
    }
  }
  return !out.empty();
}

}  // namespace fabmesh
