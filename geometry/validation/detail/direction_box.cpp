#include "geometry/validation/detail/direction_box.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace fabmesh::detail {
namespace {

// Error analysis, shared by every bound below. Unit vectors are computed
// within 1e-14 of the exact ones (unit_from). Every other quantity is a
// sum of a few products of such unit vectors (dot and cross products, 3x3
// determinants), computed within 1e-14 of its exact value; a quotient by a
// computed quantity of size >= s is within about 1e-14 / s. A bound
// computed for inputs within delta of the exact ones bounds the exact set
// within about 2 delta (the arc or cone of the inputs moves by that much).
// Every bound is thus within 1e-8 of a true one, which kDirectionMargin
// covers; slack constants exceed the errors they cover by orders of
// magnitude (a larger bound is only a looser box, never a wrong one).

/// A vector by coordinate.
struct V {
  double c[3];
};

V operator-(const V& a, const V& b) { return {{a.c[0] - b.c[0], a.c[1] - b.c[1], a.c[2] - b.c[2]}}; }
V operator+(const V& a, const V& b) { return {{a.c[0] + b.c[0], a.c[1] + b.c[1], a.c[2] + b.c[2]}}; }
V operator*(double s, const V& a) { return {{s * a.c[0], s * a.c[1], s * a.c[2]}}; }
double dot(const V& a, const V& b) { return a.c[0] * b.c[0] + a.c[1] * b.c[1] + a.c[2] * b.c[2]; }
V cross(const V& a, const V& b) {
  return {{a.c[1] * b.c[2] - a.c[2] * b.c[1], a.c[2] * b.c[0] - a.c[0] * b.c[2],
           a.c[0] * b.c[1] - a.c[1] * b.c[0]}};
}
double norm(const V& a) { return std::sqrt(dot(a, a)); }
double det(const V& a, const V& b, const V& c) { return dot(a, cross(b, c)); }

/// Chords at most this long make a "short" arc: it bulges beyond the box of
/// its ends by at most chord^2 / 4 <= 2.5e-9, far inside the margin.
constexpr double kShortChord = 1e-4;
/// Cross products of unit vectors smaller than this are not normalized:
/// with a chord above kShortChord, only vectors within 1e-5 of opposite
/// have one. Above it, the unit normal is within 1e-11 of the exact one
/// for the computed vectors.
constexpr double kMinCross = 1e-5;
/// Great circles whose largest coordinate along an axis is below this are
/// bounded by that largest coordinate, not by their point farthest along
/// the axis (whose direction would carry errors above 1e-8).
constexpr double kMinFull = 1e-3;
/// Cones whose corners are not all within this cosine of their mean
/// direction span (nearly) a hemisphere: they get the sphere's box.
constexpr double kMinLow = 1e-6;

/// The unit vector along x - v, computed: within 1e-14 of the exact one
/// (each coordinate of x - v is rounded once, to relative 2^-53, and the
/// normalization adds a few roundings of that size), provided the squared
/// length is a normal double well away from overflow. False when it is not
/// (then no bound is claimed).
bool unit_from(const Vec3& v, const Vec3& x, V& u) {
  const V d{{x.x() - v.x(), x.y() - v.y(), x.z() - v.z()}};
  const double n2 = dot(d, d);
  if (!(n2 >= 1e-290 && n2 <= 1e290)) return false;
  u = (1.0 / std::sqrt(n2)) * d;
  return true;
}

/// An upper bound of s p_k over the minor great circle arc from x to y
/// (unit vectors less than 180 degrees apart; s = +1 or -1). The maximum of
/// s p_k over the whole great circle with unit normal n is
/// sqrt(1 - n_k^2) = sqrt(n_i^2 + n_j^2), attained at the unit vector m
/// along s (e_k - n_k n); over the arc it is that value when m is on the
/// arc ((x cross m) . n >= 0 and (m cross y) . n >= 0), else at an end.
double arc_max(const V& x, const V& y, int k, double s) {
  const double ends = std::max(s * x.c[k], s * y.c[k]);
  const double chord = norm(x - y);
  if (chord <= kShortChord) return ends + chord * chord / 4 + 1e-12;
  const V n0 = cross(x, y);
  const double nn = norm(n0);
  if (nn < kMinCross) return 1.0;  // nearly opposite ends: no useful bound
  const V n = (1.0 / nn) * n0;
  const int i = (k + 1) % 3;
  const int j = (k + 2) % 3;
  const double full = std::sqrt(n.c[i] * n.c[i] + n.c[j] * n.c[j]);  // within 1e-11
  if (full < kMinFull) return std::max(ends, full) + 1e-9;           // the circle stays near p_k = 0
  V m{{-n.c[k] * n.c[0], -n.c[k] * n.c[1], -n.c[k] * n.c[2]}};
  m.c[k] += 1.0;  // e_k - n_k n, of length full
  m = (s / full) * m;
  // m is within 1e-8 of the maximizer: a slack of 1e-6 keeps it when it is
  // on the arc. (Had it been dropped, it would have been within delta of an
  // end, whose value is then below full by at most delta^2 / 2.)
  if (dot(cross(x, m), n) >= -1e-6 && dot(cross(m, y), n) >= -1e-6) return full + 1e-9;
  return ends + 1e-9;
}

/// Whether the direction s e_k may be in the cone of a, b, c (pointed,
/// d = det(a, b, c) of size >= 1e-12): it is iff det(e, b, c),
/// det(a, e, c), det(a, b, e) all have the sign of d (or are 0); each is
/// computed within 1e-14.
bool may_contain_axis(const V& a, const V& b, const V& c, double d, int k, double s) {
  V e{{0, 0, 0}};
  e.c[k] = s;
  const double sign = d > 0 ? 1.0 : -1.0;
  return sign * det(e, b, c) >= -1e-13 && sign * det(a, e, c) >= -1e-13 && sign * det(a, b, e) >= -1e-13;
}

/// The box [-upper(k, -1), upper(k, +1)] over the axes k, grown by the
/// margin, within the sphere's box.
template <class Upper>
DirectionBox box_from(const Upper& upper) {
  DirectionBox box = sphere_box();
  for (int k = 0; k < 3; ++k) {
    box.lo[k] = std::max(box.lo[k], -upper(k, -1.0) - kDirectionMargin);
    box.hi[k] = std::min(box.hi[k], upper(k, 1.0) + kDirectionMargin);
  }
  return box;
}

/// The box of the arc between unit vectors x and y (the sphere's box when
/// they nearly oppose: their mean shorter than kMinLow).
DirectionBox arc_between(const V& x, const V& y) {
  if (!(norm(0.5 * (x + y)) >= kMinLow)) return sphere_box();
  return box_from([&](int k, double s) { return arc_max(x, y, k, s); });
}

/// The box of the spherical triangle (cone) of unit vectors u[0..3).
///
/// Pointed: with w the unit vector along their sum and low = min u_i . w,
/// every direction of the cone has . w >= low > 0 (it is q / |q| for q in
/// the hull H of the u, q . w >= low and |q| <= 1).
///
/// Nearly flat (the usual case for faces near a fan): take the edge x, y
/// with the largest |x cross y| and its unit normal n. A point of the cone
/// is p = q / |q| with q = alpha x + beta y + gamma z in H; p . n =
/// gamma (z . n) / |q|, and z . n = det / |x cross y|, so |p . n| <= eps :=
/// |det| / (|x cross y| low). Its projection onto the plane of x, y lies
/// along a direction of the wedge spanned by x, y and z' (z projected,
/// normalized): the union of the three minor arcs between them. So p_k <=
/// the maximum over those arcs + eps + eps^2 (the projection's length is
/// >= 1 - eps^2).
///
/// Otherwise: the maximum of p_k over the cone is on an edge, or is 1 when
/// e_k is in the cone.
DirectionBox triangle_box(const V (&u)[3]) {
  const double chord = std::max({norm(u[0] - u[1]), norm(u[1] - u[2]), norm(u[2] - u[0])});
  if (chord <= kShortChord) {
    // A small cone: each point is q / |q| with q in H and |q| >= 1 - chord^2
    // (H lies within its circumradius <= chord of each corner), so within 2 chord^2 of H.
    return box_from([&](int k, double s) {
      return std::max({s * u[0].c[k], s * u[1].c[k], s * u[2].c[k]}) + 2 * chord * chord + 1e-12;
    });
  }
  const V sum = u[0] + u[1] + u[2];
  const double sum_norm = norm(sum);
  if (!(sum_norm > 0)) return sphere_box();
  const V w = (1.0 / sum_norm) * sum;
  const double low = std::min({dot(u[0], w), dot(u[1], w), dot(u[2], w)}) - 1e-13;
  if (!(low >= kMinLow)) return sphere_box();
  int base = 0;  // the edge u[base], u[base + 1] with the largest cross product
  double best = -1;
  for (int e = 0; e < 3; ++e) {
    const double c = norm(cross(u[e], u[(e + 1) % 3]));
    if (c > best) {
      best = c;
      base = e;
    }
  }
  if (best < kMinCross) return sphere_box();
  const V& x = u[base];
  const V& y = u[(base + 1) % 3];
  const V& z = u[(base + 2) % 3];
  const double d = det(x, y, z);
  const double eps = (std::abs(d) + 1e-13) / (best * low) * (1 + 1e-9);
  if (eps <= 1e-3) {
    const V n = (1.0 / best) * cross(x, y);
    const V zp0 = z - dot(z, n) * n;
    const V zp = (1.0 / norm(zp0)) * zp0;  // |zp0| >= 1 - eps
    const double thick = eps + eps * eps + 1e-12;
    return box_from([&](int k, double s) {
      return std::max({arc_max(x, y, k, s), arc_max(y, zp, k, s), arc_max(zp, x, k, s)}) + thick;
    });
  }
  return box_from([&](int k, double s) {
    if (may_contain_axis(u[0], u[1], u[2], d, k, s)) return 1.0;
    return std::max({arc_max(u[0], u[1], k, s), arc_max(u[1], u[2], k, s), arc_max(u[2], u[0], k, s)});
  });
}

void grow(DirectionBox& a, const DirectionBox& b) {
  for (int c = 0; c < 3; ++c) {
    a.lo[c] = std::min(a.lo[c], b.lo[c]);
    a.hi[c] = std::max(a.hi[c], b.hi[c]);
  }
}

}  // namespace

DirectionBox sphere_box() {
  const double limit = 1.0 + kDirectionMargin;
  return {{-limit, -limit, -limit}, {limit, limit, limit}};
}

bool overlap(const DirectionBox& a, const DirectionBox& b) {
  for (int c = 0; c < 3; ++c) {
    if (a.lo[c] > b.hi[c] || b.lo[c] > a.hi[c]) return false;
  }
  return true;
}

DirectionBox arc_box(const std::array<Vec3, 3>& p, int k) {
  V x;
  V y;
  if (!unit_from(p[k], p[(k + 1) % 3], x) || !unit_from(p[k], p[(k + 2) % 3], y)) return sphere_box();
  return arc_between(x, y);
}

DirectionBox cone_box(const Vec3& v, const std::array<Vec3, 3>& p) {
  V u[3];
  for (int k = 0; k < 3; ++k) {
    if (!unit_from(v, p[k], u[k])) return sphere_box();
  }
  return triangle_box(u);
}

DirectionTree::DirectionTree(const std::vector<DirectionBox>& boxes) : boxes_(boxes) {
  const std::size_t n = boxes.size();
  std::vector<std::pair<std::uint32_t, std::uint32_t>> keyed(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t code = 0;
    for (int c = 0; c < 3; ++c) {
      const double centre = 0.5 * (boxes[i].lo[c] + boxes[i].hi[c]);
      const auto cell = static_cast<std::uint32_t>(std::clamp((centre + 1.0) * 511.5, 0.0, 1023.0));
      for (int bit = 0; bit < 10; ++bit) code |= ((cell >> bit) & 1u) << (3 * bit + c);
    }
    keyed[i] = {code, static_cast<std::uint32_t>(i)};
  }
  std::sort(keyed.begin(), keyed.end());
  order_.resize(n);
  for (std::size_t i = 0; i < n; ++i) order_[i] = keyed[i].second;
  const std::size_t leaves = (n + kLeaf - 1) / kLeaf;
  while (leaf_base_ < leaves) leaf_base_ *= 2;
  const double inf = std::numeric_limits<double>::infinity();
  nodes_.assign(2 * leaf_base_, DirectionBox{{inf, inf, inf}, {-inf, -inf, -inf}});
  for (std::size_t i = 0; i < n; ++i) grow(nodes_[leaf_base_ + i / kLeaf], boxes[order_[i]]);
  for (std::size_t node = leaf_base_ - 1; node >= 1; --node) {
    nodes_[node] = nodes_[2 * node];
    grow(nodes_[node], nodes_[2 * node + 1]);
  }
}

}  // namespace fabmesh::detail
