#include "geometry/validation/detail/vertex_star.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "geometry/validation/detail/direction_box.h"
#include "geometry/validation/detail/face_pair_filter.h"

namespace fabmesh::detail {
namespace {

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

void for_each_star_neighbour_candidate(const TriangleSoup& soup, const VertexStars& stars, std::size_t s,
                                       const std::vector<std::uint32_t>& others,
                                       const std::function<bool(std::uint32_t, std::uint32_t)>& visit) {
  const std::uint32_t v = stars.centres[s];
  const Vec3& centre = soup.vertices[v];
  const auto corners = [&](std::uint32_t f) {
    const auto& t = soup.triangles[f];
    return std::array<Vec3, 3>{soup.vertices[t[0]], soup.vertices[t[1]], soup.vertices[t[2]]};
  };
  std::vector<std::uint32_t> own;  // the faces whose smallest star centre is v
  std::vector<DirectionBox> arcs;
  for (std::size_t i = stars.offsets[s]; i < stars.offsets[s + 1]; ++i) {
    const std::uint32_t f = stars.faces[i];
    if (stars.group[f] != v) continue;
    const auto& t = soup.triangles[f];
    own.push_back(f);
    arcs.push_back(arc_box(corners(f), t[0] == v ? 0 : t[1] == v ? 1 : 2));
  }
  if (own.empty()) return;
  const DirectionTree tree(arcs);
  for (const std::uint32_t g : others) {
    const auto& tg = soup.triangles[g];
    const bool member = stars.group[g] != kNoStar;
    const bool touches = tg[0] == v || tg[1] == v || tg[2] == v;
    const DirectionBox cone = touches ? sphere_box() : cone_box(centre, corners(g));
    const bool go_on = tree.for_each_overlapping(cone, [&](std::uint32_t i) {
      const std::uint32_t f = own[i];
      if (member && stars.shares_centre(soup.triangles[f], tg)) return true;  // a star's own pair
      return visit(f, g);
    });
    if (!go_on) return;
  }
}

}  // namespace fabmesh::detail
