// Slivers cut into slabs across their longest edge d = C - B: piece j holds
// the points X of the triangle with t(X) = (X - B) . d in [s_j, s_j+1], the
// first piece unbounded below and the last above, so that the pieces cover
// the triangle, and neighbouring slabs overlap by 1e-6 of a slab's width (at
// least |d|^2 / k), far more than the rounding of t (about 1e-15 |d|^2): the
// computed piece j contains the exact triangle's points with t in
// [s_j, s_j+1]. A piece is the convex hull of its edges' parts in the slab;
// its box is the box of those parts' ends. An edge whose extent in t is at
// most the slab width is taken whole in every slab it meets; a longer one
// is clipped at u = (s - t(P)) / (t(Q) - t(P)) (rounding error below 1e-12,
// widened by 1e-9). The ends P + u (Q - P) are within a few units in the
// last place of the largest coordinate, and each box is grown by 1e-12 of
// it before rounding outwards to floats.

#include "geometry/validation/detail/sliver_pieces.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace fabmesh::detail {
namespace {

constexpr double kWiden = 1e-9;  ///< added to each end of a clipped edge's parameter range

/// The number of pieces of the triangle p (1: not a sliver).
std::size_t piece_count(const std::array<Vec3, 3>& p) {
  const Vec3 lo = p[0].cwiseMin(p[1]).cwiseMin(p[2]);
  const Vec3 hi = p[0].cwiseMax(p[1]).cwiseMax(p[2]);
  std::array<double, 3> extent{hi.x() - lo.x(), hi.y() - lo.y(), hi.z() - lo.z()};
  std::sort(extent.begin(), extent.end());
  const double area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
  if (!(area > 0.0)) return 1;
  const double excess = extent[1] * extent[2] / area;
  if (!std::isfinite(excess) || !(excess > kSliverExcess)) return 1;
  return static_cast<std::size_t>(std::min(std::ceil(excess / 16.0), static_cast<double>(kMaxPieces)));
}

/// Grows [lo, hi] by the points of edge pq whose parameter t lies in [s0, s1].
void add_edge_part(const Vec3& p, const Vec3& q, double tp, double tq, double s0, double s1, double width,
                   Vec3& lo, Vec3& hi) {
  const double a = std::min(tp, tq);
  const double b = std::max(tp, tq);
  if (b < s0 || a > s1) return;
  const auto grow = [&](const Vec3& x) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  };
  if (b - a <= width) {
    grow(p);
    grow(q);
    return;
  }
  const double u0 = (std::max(s0, a) - tp) / (tq - tp);
  const double u1 = (std::min(s1, b) - tp) / (tq - tp);
  const double from = std::max(0.0, std::min(u0, u1) - kWiden);
  const double to = std::min(1.0, std::max(u0, u1) + kWiden);
  grow(p + from * (q - p));
  grow(p + to * (q - p));
}

/// Appends the k pieces' boxes of the triangle p.
void cut(const std::array<Vec3, 3>& p, std::size_t k, std::vector<BoxF>& boxes) {
  int longest = 0;  // the longest edge is B -> C
  for (int i = 1; i < 3; ++i) {
    if ((p[(i + 1) % 3] - p[i]).squaredNorm() > (p[(longest + 1) % 3] - p[longest]).squaredNorm())
      longest = i;
  }
  const Vec3& b = p[longest];
  const Vec3 d = p[(longest + 1) % 3] - b;
  std::array<double, 3> t{};
  for (int i = 0; i < 3; ++i) t[i] = (p[i] - b).dot(d);
  const double t_lo = std::min({t[0], t[1], t[2]});
  const double width = (std::max({t[0], t[1], t[2]}) - t_lo) / static_cast<double>(k);
  const double scale =
      std::max({p[0].cwiseAbs().maxCoeff(), p[1].cwiseAbs().maxCoeff(), p[2].cwiseAbs().maxCoeff()});
  const Vec3 grown = Vec3::Constant(1e-12 * scale);
  const double inf = std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < k; ++j) {
    const double s0 = j == 0 ? -inf : t_lo + width * (static_cast<double>(j) - 1e-6);
    const double s1 = j + 1 == k ? inf : t_lo + width * (static_cast<double>(j + 1) + 1e-6);
    Vec3 lo = Vec3::Constant(inf);
    Vec3 hi = Vec3::Constant(-inf);
    for (int i = 0; i < 3; ++i)
      add_edge_part(p[i], p[(i + 1) % 3], t[i], t[(i + 1) % 3], s0, s1, width, lo, hi);
    if (lo.x() > hi.x()) continue;  // no part of the triangle in this slab
    boxes.push_back(rounded_box(lo - grown, hi + grown));
  }
}

}  // namespace

std::size_t append_pieces(const TriangleSoup& soup, std::uint32_t f, std::vector<BoxF>& boxes) {
  const auto& t = soup.triangles[f];
  const std::array<Vec3, 3> p{soup.vertices[t[0]], soup.vertices[t[1]], soup.vertices[t[2]]};
  const std::size_t before = boxes.size();
  const std::size_t k = piece_count(p);
  if (k == 1) {
    boxes.push_back(triangle_box(soup, f));
  } else {
    cut(p, k, boxes);
  }
  return boxes.size() - before;
}

}  // namespace fabmesh::detail
