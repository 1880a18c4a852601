#include "geometry/validation/detail/vertex_star.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "geometry/validation/detail/face_pair_filter.h"

namespace fabmesh::detail {
namespace {

/// A box in direction space (around the unit sphere).
struct DirectionBox {
  double lo[3];
  double hi[3];
};

/// Margin added to every direction box: far above the rounding errors
/// bounded below (<= 1e-8), far below the arc of a face in any fan that
/// fits in memory (a 10^6-face fan: arcs of about 3e-6).
constexpr double kDirectionMargin = 1e-7;
/// Arcs whose end directions nearly oppose (|mid| below this) get the box of
/// the whole sphere: their bulge would not be bounded accurately.
constexpr double kMinMid = 1e-6;

/// The unit vector along d, computed: within 1e-14 of the exact one (a
/// difference of two doubles and a normalization, a few roundings of
/// relative size 2^-53 each; filterable coordinates keep every square
/// between 1e-92 and 1e61, away from underflow and overflow).
D3 unit(const D3& d) {
  const double n = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  return {d.x / n, d.y / n, d.z / n};
}

/// A box containing the directions from corner k of face `p` to all its
/// other points: the arc from ua to ub (the directions of the other two
/// corners, not opposite since the face is certified non-degenerate) is
/// {q / |q| : q on the segment ua ub}, with 1 <= 1 / |q| <= 1 / |mid|,
/// so it lies in the hull of ua, ub, K ua, K ub for any K >= 1 / |mid|.
/// Computed: ua, ub, mid within 1e-14 of the exact ones; K = (1 + 1e-6) /
/// |mid| exceeds the exact 1 / |mid| when |mid| >= 1e-6; the corners K ua,
/// K ub are then within 1e-8 of exact points of that hull. So the box of the
/// computed corners grown by kDirectionMargin contains the exact arc; and,
/// the arc being on the unit sphere, so does its intersection with the box
/// [-1, 1]^3 grown by the margin.
DirectionBox arc_box(const std::array<Vec3, 3>& p, int k) {
  const Vec3& v = p[k];
  const D3 ua = unit(sub(p[(k + 1) % 3], v));
  const D3 ub = unit(sub(p[(k + 2) % 3], v));
  const double limit = 1.0 + kDirectionMargin;
  DirectionBox box{{-limit, -limit, -limit}, {limit, limit, limit}};
  const D3 mid{0.5 * (ua.x + ub.x), 0.5 * (ua.y + ub.y), 0.5 * (ua.z + ub.z)};
  const double mid_norm = std::sqrt(dot(mid, mid));
  if (mid_norm < kMinMid) return box;
  const double far = (1.0 + 1e-6) / mid_norm;
  const double a[3] = {ua.x, ua.y, ua.z};
  const double b[3] = {ub.x, ub.y, ub.z};
  for (int c = 0; c < 3; ++c) {
    const double lo = std::min({a[c], b[c], far * a[c], far * b[c]}) - kDirectionMargin;
    const double hi = std::max({a[c], b[c], far * a[c], far * b[c]}) + kDirectionMargin;
    box.lo[c] = std::max(box.lo[c], lo);
    box.hi[c] = std::min(box.hi[c], hi);
  }
  return box;
}

bool overlap(const DirectionBox& a, const DirectionBox& b) {
  for (int c = 0; c < 3; ++c) {
    if (a.lo[c] > b.hi[c] || b.lo[c] > a.hi[c]) return false;
  }
  return true;
}

/// The smallest star centre faces a and b share (kNoStar when none).
std::uint32_t smallest_shared_centre(const VertexStars& stars, const std::array<std::uint32_t, 3>& a,
                                     const std::array<std::uint32_t, 3>& b) {
  std::uint32_t best = kNoStar;
  for (const std::uint32_t v : a) {
    if (stars.centre[v] && (v == b[0] || v == b[1] || v == b[2])) best = std::min(best, v);
  }
  return best;
}

/// The axis along which the box centres spread most: the sweep's axis.
int sweep_axis(const std::vector<DirectionBox>& boxes) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  double lo[3] = {kInfinity, kInfinity, kInfinity};
  double hi[3] = {-kInfinity, -kInfinity, -kInfinity};
  for (const DirectionBox& b : boxes) {
    for (int c = 0; c < 3; ++c) {
      const double m = 0.5 * (b.lo[c] + b.hi[c]);
      lo[c] = std::min(lo[c], m);
      hi[c] = std::max(hi[c], m);
    }
  }
  int axis = 0;
  for (int c = 1; c < 3; ++c) {
    if (hi[c] - lo[c] > hi[axis] - lo[axis]) axis = c;
  }
  return axis;
}

}  // namespace

VertexStars find_vertex_stars(const TriangleSoup& soup, const std::vector<char>& skip,
                              std::size_t min_degree) {
  VertexStars stars;
  const std::size_t faces = soup.triangles.size();
  stars.group.assign(faces, kNoStar);
  stars.centre.assign(soup.vertices.size(), 0);
  std::vector<char> member(faces, 0);  // certified and taking part
  std::vector<std::uint32_t> degree(soup.vertices.size(), 0);
  for (std::size_t f = 0; f < faces; ++f) {
    if (!skip.empty() && skip[f]) continue;
    member[f] = face_data(soup, static_cast<std::uint32_t>(f)).certified;
    if (!member[f]) continue;
    for (const std::uint32_t v : soup.triangles[f]) ++degree[v];
  }
  std::vector<std::size_t> index(soup.vertices.size(), 0);
  for (std::size_t v = 0; v < degree.size(); ++v) {
    if (degree[v] < min_degree) continue;
    stars.centre[v] = 1;
    index[v] = stars.centres.size();
    stars.centres.push_back(static_cast<std::uint32_t>(v));
  }
  stars.offsets.assign(stars.centres.size() + 1, 0);
  for (std::size_t s = 0; s < stars.centres.size(); ++s) {
    stars.offsets[s + 1] = stars.offsets[s] + degree[stars.centres[s]];
  }
  stars.faces.resize(stars.offsets.back());
  std::vector<std::size_t> next(stars.offsets.begin(), stars.offsets.end() - 1);
  for (std::size_t f = 0; f < faces; ++f) {
    if (!member[f]) continue;
    for (const std::uint32_t v : soup.triangles[f]) {
      if (!stars.centre[v]) continue;
      stars.faces[next[index[v]]++] = static_cast<std::uint32_t>(f);
      stars.group[f] = std::min(stars.group[f], v);
    }
  }
  return stars;
}

void for_each_star_candidate(const TriangleSoup& soup, const VertexStars& stars, std::size_t s,
                             const std::function<bool(std::uint32_t, std::uint32_t)>& visit) {
  const std::uint32_t v = stars.centres[s];
  const std::size_t first = stars.offsets[s];
  const std::size_t d = stars.offsets[s + 1] - first;
  std::vector<DirectionBox> boxes(d);
  for (std::size_t i = 0; i < d; ++i) {
    const auto& t = soup.triangles[stars.faces[first + i]];
    const int k = t[0] == v ? 0 : t[1] == v ? 1 : 2;
    boxes[i] = arc_box({soup.vertices[t[0]], soup.vertices[t[1]], soup.vertices[t[2]]}, k);
  }
  const int axis = sweep_axis(boxes);
  std::vector<std::size_t> order(d);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
    return boxes[i].lo[axis] != boxes[j].lo[axis] ? boxes[i].lo[axis] < boxes[j].lo[axis] : i < j;
  });
  for (std::size_t x = 0; x < d; ++x) {
    const DirectionBox& a = boxes[order[x]];
    for (std::size_t y = x + 1; y < d && boxes[order[y]].lo[axis] <= a.hi[axis]; ++y) {
      if (!overlap(a, boxes[order[y]])) continue;
      const std::uint32_t f = std::min(stars.faces[first + order[x]], stars.faces[first + order[y]]);
      const std::uint32_t g = std::max(stars.faces[first + order[x]], stars.faces[first + order[y]]);
      if (smallest_shared_centre(stars, soup.triangles[f], soup.triangles[g]) != v) continue;
      if (!visit(f, g)) return;
    }
  }
}

}  // namespace fabmesh::detail
