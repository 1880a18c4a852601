#include "geometry/repair/surface_distance.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <unordered_set>

#include "geometry/mesh/bounding_box.h"
#include "geometry/mesh/hash_mix.h"

namespace fabmesh {
namespace {

using Corners = std::array<Vec3, 3>;

Corners corners_of(const TriangleSoup& soup, std::size_t f) {
  const auto& t = soup.triangles[f];
  return {soup.vertices[t[0]], soup.vertices[t[1]], soup.vertices[t[2]]};
}

/// A point for the distance queries' own arithmetic. A query visits tens of
/// tree nodes and triangles; written with Eigen's expression templates, this
/// kernel relies on the compiler inlining dozens of small functions, which a
/// sanitized build does not do (the repair tests' proofs ran there five times
/// slower than on plain coordinates). The operations and their order are
/// Eigen's for a 3-vector, so every result is the same to the bit.
struct P3 {
  double x, y, z;
};
P3 p3(const Vec3& v) {
  const double* d = v.data();
  return {d[0], d[1], d[2]};
}
P3 operator-(const P3& a, const P3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
P3 operator+(const P3& a, const P3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
P3 operator*(double s, const P3& a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(const P3& a, const P3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

/// The point of triangle (a, b, c) nearest to p (Ericson, Real-Time Collision
/// Detection 5.1.5), always formed as a + v (b - a) + w (c - a) with
/// v, w >= 0, v + w <= 1: a point of the triangle up to its rounding.
P3 closest_point(const P3& p, const P3& a, const P3& b, const P3& c) {
  const P3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const P3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + std::clamp(d1 / (d1 - d3), 0.0, 1.0) * ab;
  const P3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + std::clamp(d2 / (d2 - d6), 0.0, 1.0) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double w = std::clamp((d4 - d3) / ((d4 - d3) + (d5 - d6)), 0.0, 1.0);
    return b + w * (c - b);
  }
  const double sum = va + vb + vc;
  if (!(sum > 0.0)) {  // a degenerate triangle: the nearest of its edges' points
    const P3 e1 = a + std::clamp(dot(ab, ap) / std::max(dot(ab, ab), 1e-300), 0.0, 1.0) * ab;
    const P3 e2 = a + std::clamp(dot(ac, ap) / std::max(dot(ac, ac), 1e-300), 0.0, 1.0) * ac;
    const P3 bc = c - b;
    const P3 e3 = b + std::clamp(dot(bc, bp) / std::max(dot(bc, bc), 1e-300), 0.0, 1.0) * bc;
    const P3 f1 = p - e1, f2 = p - e2, f3 = p - e3;
    const double n1 = dot(f1, f1), n2 = dot(f2, f2), n3 = dot(f3, f3);
    return n1 <= n2 && n1 <= n3 ? e1 : n2 <= n3 ? e2 : e3;
  }
  double v = std::clamp(vb / sum, 0.0, 1.0), w = std::clamp(vc / sum, 0.0, 1.0);
  if (v + w > 1.0) {
    const double s = v + w;
    v /= s;
    w /= s;
  }
  return a + v * ab + w * ac;
}

double box_distance2(const P3& p, const P3& lo, const P3& hi) {
  const P3 d{std::max(std::max(lo.x - p.x, p.x - hi.x), 0.0), std::max(std::max(lo.y - p.y, p.y - hi.y), 0.0),
             std::max(std::max(lo.z - p.z, p.z - hi.z), 0.0)};
  return dot(d, d);
}

/// A bounding-volume hierarchy over the triangles of a soup, for nearest-point queries.
class TriangleTree {
 public:
  explicit TriangleTree(const TriangleSoup& soup) : soup_(soup), order_(soup.triangles.size()) {
    std::iota(order_.begin(), order_.end(), 0u);
    if (!order_.empty()) build(0, order_.size());
  }

  /// The nearest triangle to p: its index and an upper bound of the distance (computed, not yet padded).
  std::pair<std::uint32_t, double> nearest(const Vec3& point, std::uint32_t hint) const {
    const P3 p = p3(point);
    double best2 = std::numeric_limits<double>::infinity();
    std::uint32_t best = hint;
    if (hint != kNone) best2 = distance2(p, hint);
    // The tree splits at the median, so it is at most 32 levels deep and the
    // stack (the siblings of one path, and the root) never holds more than 33:
    // no allocation per query.
    std::array<std::uint32_t, 64> stack;
    std::size_t size = 0;
    stack[size++] = 0;
    while (size > 0) {
      const Node& n = nodes_[stack[--size]];
      if (box_distance2(p, n.lo, n.hi) >= best2) continue;
      if (n.count > 0) {
        for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
          const double d2 = distance2(p, order_[i]);
          if (d2 < best2) {
            best2 = d2;
            best = order_[i];
          }
        }
        continue;
      }
      const Node& l = nodes_[n.first];
      const Node& r = nodes_[n.second];
      const bool left_first = box_distance2(p, l.lo, l.hi) <= box_distance2(p, r.lo, r.hi);
      stack[size++] = left_first ? n.second : n.first;
      stack[size++] = left_first ? n.first : n.second;
    }
    return {best, std::sqrt(best2)};
  }

  double distance(const Vec3& p, std::uint32_t f) const { return std::sqrt(distance2(p3(p), f)); }

  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

 private:
  struct Node {
    P3 lo, hi;
    std::uint32_t first = 0;   ///< leaf: first index into order_; inner: the left child
    std::uint32_t second = 0;  ///< inner: the right child
    std::uint32_t count = 0;   ///< leaf: triangles; 0 for an inner node
  };

  double distance2(const P3& p, std::uint32_t f) const {
    const auto& t = soup_.triangles[f];
    const P3 d =
        p - closest_point(p, p3(soup_.vertices[t[0]]), p3(soup_.vertices[t[1]]), p3(soup_.vertices[t[2]]));
    return dot(d, d);
  }

  std::uint32_t build(std::size_t begin, std::size_t end) {
    const auto index = static_cast<std::uint32_t>(nodes_.size());
    nodes_.push_back({});
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    Vec3 clo = lo, chi = hi;
    for (std::size_t i = begin; i < end; ++i) {
      const Corners c = corners_of(soup_, order_[i]);
      for (const Vec3& p : c) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
      const Vec3 centre = (c[0] + c[1] + c[2]) / 3.0;
      clo = clo.cwiseMin(centre);
      chi = chi.cwiseMax(centre);
    }
    nodes_[index].lo = p3(lo);
    nodes_[index].hi = p3(hi);
    if (end - begin <= 4) {
      nodes_[index].first = static_cast<std::uint32_t>(begin);
      nodes_[index].count = static_cast<std::uint32_t>(end - begin);
      return index;
    }
    int axis = 0;
    (chi - clo).maxCoeff(&axis);
    const std::size_t mid = (begin + end) / 2;
    std::nth_element(order_.begin() + static_cast<std::ptrdiff_t>(begin),
                     order_.begin() + static_cast<std::ptrdiff_t>(mid),
                     order_.begin() + static_cast<std::ptrdiff_t>(end),
                     [&](std::uint32_t x, std::uint32_t y) {
                       const Corners a = corners_of(soup_, x), b = corners_of(soup_, y);
                       const double ka = a[0][axis] + a[1][axis] + a[2][axis];
                       const double kb = b[0][axis] + b[1][axis] + b[2][axis];
                       return ka != kb ? ka < kb : x < y;
                     });
    const std::uint32_t left = build(begin, mid);
    const std::uint32_t right = build(mid, end);
    nodes_[index].first = left;
    nodes_[index].second = right;
    return index;
  }

  const TriangleSoup& soup_;
  std::vector<std::uint32_t> order_;
  std::vector<Node> nodes_;
};

/// A face's corners as a key independent of their order (bit patterns, -0 as +0).
struct FaceKey {
  std::array<double, 9> c;
  bool operator==(const FaceKey& o) const { return c == o.c; }
};
struct FaceKeyHash {
  std::size_t operator()(const FaceKey& k) const {
    std::uint64_t h = 0;
    for (const double x : k.c) {
      std::uint64_t bits = 0;
      std::memcpy(&bits, &x, sizeof bits);
      h = mix64(h ^ bits);
    }
    return static_cast<std::size_t>(h);
  }
};

FaceKey face_key(const TriangleSoup& soup, std::size_t f) {
  Corners c = corners_of(soup, f);
  std::sort(c.begin(), c.end(), [](const Vec3& a, const Vec3& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
  FaceKey key{};
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t k = 0; k < 3; ++k) key.c[3 * i + k] = c[i][static_cast<Eigen::Index>(k)] + 0.0;
  return key;
}

/// The most a corner of `c` moved from `partner`'s under the best matching
/// of corners: the affine map between two triangles moves no point farther
/// than its corners (the displacement is affine, its norm convex).
double moved_by(const Corners& c, const Corners& partner) {
  std::array<std::size_t, 3> perm{0, 1, 2};
  double best = std::numeric_limits<double>::infinity();
  do {
    double worst = 0.0;
    for (std::size_t k = 0; k < 3; ++k) worst = std::max(worst, (c[k] - partner[perm[k]]).norm());
    best = std::min(best, worst);
  } while (std::next_permutation(perm.begin(), perm.end()));
  return best;
}

/// The bound of one face, refined as DistanceOptions say.
struct FaceBound {
  double upper = 0.0, lower = 0.0;
  Vec3 at = Vec3::Zero();
};

class FaceMeasure {
 public:
  FaceMeasure(const TriangleTree& tree, double resolution, double pad_scale, std::size_t budget)
      : tree_(tree), resolution_(resolution), pad_scale_(pad_scale), budget_(budget) {}

  /// The bound of the triangle `c`; `partner`, when given, is a triangle of
  /// the other surface it was made from by moving corners (see one_sided_distance).
  FaceBound measure(const Corners& c, const Corners* partner) {
    std::array<std::pair<std::uint32_t, double>, 3> near{};
    std::uint32_t hint = TriangleTree::kNone;
    for (int i = 0; i < 3; ++i) {
      near[static_cast<std::size_t>(i)] = tree_.nearest(c[static_cast<std::size_t>(i)], hint);
      hint = near[static_cast<std::size_t>(i)].first;
    }
    if (partner == nullptr) return refine(c, near, 0);
    FaceBound b;
    for (std::size_t i = 0; i < 3; ++i) {
      if (near[i].second >= b.lower) {
        b.lower = near[i].second;
        b.at = c[i];
      }
    }
    b.upper = pad(moved_by(c, *partner));
    if (b.upper - b.lower <= resolution_) return b;
    FaceBound refined = refine(c, near, 0);
    refined.upper = std::min(refined.upper, b.upper);
    return refined;
  }

 private:
  double pad(double d) const { return d + 1e-13 * (pad_scale_ + d); }

  FaceBound refine(const Corners& c, const std::array<std::pair<std::uint32_t, double>, 3>& near, int depth) {
    FaceBound b;
    for (int i = 0; i < 3; ++i) {
      if (near[static_cast<std::size_t>(i)].second >= b.lower) {
        b.lower = near[static_cast<std::size_t>(i)].second;
        b.at = c[static_cast<std::size_t>(i)];
      }
    }
    const double longest = std::max({(c[0] - c[1]).norm(), (c[1] - c[2]).norm(), (c[2] - c[0]).norm()});
    double upper = b.lower + 2.0 * longest / 3.0;
    // Candidates of the convexity bound: the triangles nearest to the corners
    // and to the centroid (a piece of one face, whose corners lie on its
    // edges, is nearest to that face in its middle).
    const std::uint32_t centre = tree_.nearest((c[0] + c[1] + c[2]) / 3.0, near[0].first).first;
    ++used_;
    for (const std::uint32_t t : {near[0].first, near[1].first, near[2].first, centre}) {
      double worst = 0.0;
      for (const Vec3& p : c) worst = std::max(worst, tree_.distance(p, t));
      upper = std::min(upper, worst);
    }
    b.upper = pad(upper);
    if (b.upper - b.lower <= resolution_ || depth >= 40 || used_ + 3 > budget_) return b;
    // Split in four at the edge midpoints.
    const Vec3 m01 = 0.5 * (c[0] + c[1]), m12 = 0.5 * (c[1] + c[2]), m20 = 0.5 * (c[2] + c[0]);
    std::array<std::pair<std::uint32_t, double>, 3> mid{};
    mid[0] = tree_.nearest(m01, near[0].first);
    mid[1] = tree_.nearest(m12, near[1].first);
    mid[2] = tree_.nearest(m20, near[2].first);
    used_ += 3;
    const std::array<Corners, 4> parts{Corners{c[0], m01, m20}, Corners{m01, c[1], m12},
                                       Corners{m20, m12, c[2]}, Corners{m01, m12, m20}};
    const std::array<std::array<std::pair<std::uint32_t, double>, 3>, 4> nears{{{near[0], mid[0], mid[2]},
                                                                                {mid[0], near[1], mid[1]},
                                                                                {mid[2], mid[1], near[2]},
                                                                                {mid[0], mid[1], mid[2]}}};
    FaceBound all;
    for (std::size_t k = 0; k < 4; ++k) {
      const FaceBound part = refine(parts[k], nears[k], depth + 1);
      all.upper = std::max(all.upper, part.upper);
      if (part.lower >= all.lower) {
        all.lower = part.lower;
        all.at = part.at;
      }
    }
    all.upper = std::min(all.upper, b.upper);
    return all;
  }

  const TriangleTree& tree_;
  double resolution_;
  double pad_scale_;
  std::size_t budget_;
  std::size_t used_ = 0;
};

double magnitude(const TriangleSoup& a, const TriangleSoup& b) {
  double m = 0.0;
  for (const Vec3& p : a.vertices) m = std::max(m, p.cwiseAbs().maxCoeff());
  for (const Vec3& p : b.vertices) m = std::max(m, p.cwiseAbs().maxCoeff());
  return m;
}

}  // namespace

DistanceBound one_sided_distance(const TriangleSoup& from, const std::vector<bool>& measure,
                                 const TriangleSoup& to, const DistanceOptions& options,
                                 const std::vector<std::uint32_t>& partners) {
  std::unordered_set<FaceKey, FaceKeyHash> shared;
  for (std::size_t f = 0; f < to.triangles.size(); ++f) shared.insert(face_key(to, f));
  std::vector<std::uint32_t> faces;
  for (std::size_t f = 0; f < from.triangles.size(); ++f) {
    if (!measure.empty() && !measure[f]) continue;
    if (shared.count(face_key(from, f)) == 0) faces.push_back(static_cast<std::uint32_t>(f));
  }
  DistanceBound result;
  result.faces = faces.size();
  if (faces.empty()) return result;
  if (to.triangles.empty()) {
    result.upper = result.lower = std::numeric_limits<double>::infinity();
    return result;
  }
  const TriangleTree tree(to);
  const BoundingBox box = bounding_box(from.vertices);
  const double resolution = options.resolution > 0.0 ? options.resolution : 1e-6 * box.size().norm();
  const double scale = magnitude(from, to);
  const std::size_t budget = std::max<std::size_t>(16, options.max_evaluations / faces.size());
  std::vector<FaceBound> bounds(faces.size());
  tbb::parallel_for(std::size_t{0}, faces.size(), [&](std::size_t i) {
    FaceMeasure m(tree, resolution, scale, budget);
    const std::uint32_t partner = partners.empty() ? kNoPartner : partners[faces[i]];
    const Corners other = partner == kNoPartner ? Corners{} : corners_of(to, partner);
    bounds[i] = m.measure(corners_of(from, faces[i]), partner == kNoPartner ? nullptr : &other);
  });
  for (const FaceBound& b : bounds) {
    result.upper = std::max(result.upper, b.upper);
    if (b.lower > result.lower) {
      result.lower = b.lower;
      result.at = b.at;
    }
  }
  return result;
}

DistanceBound hausdorff_distance(const TriangleSoup& a, const TriangleSoup& b,
                                 const DistanceOptions& options) {
  const DistanceBound ab = one_sided_distance(a, {}, b, options);
  const DistanceBound ba = one_sided_distance(b, {}, a, options);
  DistanceBound both = ab.lower >= ba.lower ? ab : ba;
  both.upper = std::max(ab.upper, ba.upper);
  both.faces = ab.faces + ba.faces;
  return both;
}

}  // namespace fabmesh
