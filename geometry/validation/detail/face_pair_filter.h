#pragma once
// A floating-point filter in front of faces_intersect_exact: it proves, with
// rounding-error bounds, that two faces of a soup do not meet beyond what
// they share, and says "unknown" otherwise. It never says "intersect": every
// pair it cannot prove apart goes to the exact test, so the answer is always
// the exact one.
//
// Error bounds (standard model fl(a op b) = (a op b)(1 + d), |d| <= u = 2^-53;
// Higham, Accuracy and Stability of Numerical Algorithms, 3.1). Write each
// rounded difference of two coordinates as the exact difference times
// (1 + d). A polynomial in the exact differences, evaluated in floating
// point, then carries on each of its monomials a product of at most k such
// factors, where k counts the roundings: 1 per difference, and per operation
// 1 + the sum of its operands' counts for a product, 1 + their maximum for a
// sum. So the computed value is within gamma_k * A of the exact one, with
// A the expression evaluated on absolute values, + for - (computed in
// floating point, A is low by at most a factor 1 - gamma_k).
//   orientation det(e1, e2, e3) = (e1 x e2) . e3:  k = 8, gamma_8 < 8.9e-16;
//   (e1 x e2) . (e1 x e3), two normals:            k = 11, gamma_11 < 1.3e-15;
//   a 2 x 2 minor (a component of e1 x e2):        k = 4, gamma_4 < 4.5e-16;
//   a projection (x - o) . m on a double vector m: k = 4.
// The bounds below are these with a margin of 1.5 to 4. They hold while no
// intermediate overflows or underflows: the filter only reasons about faces
// whose every coordinate is 0 or has a magnitude in [1e-30, 1e30] (then every
// nonzero difference is >= 1e-46, every nonzero intermediate >= 1e-240,
// every intermediate <= 1e130).
//
// Internal to geometry/validation (validate.h is the public entry); the
// tests and the benchmarks include it to check and time this part alone.

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "geometry/core/soup.h"

namespace fabmesh::detail {

/// Three doubles: a difference of two soup vertices.
struct D3 {
  double x, y, z;
};

inline D3 sub(const Vec3& a, const Vec3& b) { return {a.x() - b.x(), a.y() - b.y(), a.z() - b.z()}; }
inline D3 cross(const D3& a, const D3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
/// |a| x |b| with + for -: the magnitude bound of cross(a, b).
inline D3 cross_abs(const D3& a, const D3& b) {
  return {std::abs(a.y * b.z) + std::abs(a.z * b.y), std::abs(a.z * b.x) + std::abs(a.x * b.z),
          std::abs(a.x * b.y) + std::abs(a.y * b.x)};
}
inline double dot(const D3& a, const D3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline double dot_abs(const D3& a, const D3& b) {
  return std::abs(a.x) * std::abs(b.x) + std::abs(a.y) * std::abs(b.y) + std::abs(a.z) * std::abs(b.z);
}

constexpr double kOrientationBound = 2e-15;  ///< > gamma_8 / (1 - gamma_8)
constexpr double kNormalsBound = 3e-15;      ///< > gamma_11 / (1 - gamma_11)
constexpr double kProjectionBound = 1e-15;   ///< > gamma_4 / (1 - gamma_4)
constexpr double kCrossBound = 1e-15;        ///< > gamma_4 / (1 - gamma_4), a 2 x 2 minor

/// Certified sign of `value` (+1 or -1), or 0 when |value| <= bound * magnitude.
inline int certified_sign(double value, double magnitude, double bound) {
  const double e = bound * magnitude;
  return value > e ? 1 : value < -e ? -1 : 0;
}

/// Whether coordinates of this magnitude keep the filter's bounds valid.
inline bool filterable(double c) {
  const double a = std::abs(c);
  return a == 0.0 || (a >= 1e-30 && a <= 1e30);
}

/// The plane of a triangle through vertex o with edge vectors e1, e2:
/// orientation signs of other points, exact when certified.
struct Plane {
  D3 n;      ///< cross(e1, e2), computed
  D3 n_abs;  ///< its magnitude bound
  /// Certified sign of det(e1, e2, x - o), 0 when unknown.
  int side(const D3& d) const { return certified_sign(dot(n, d), dot_abs(n_abs, d), kOrientationBound); }
};

inline Plane plane(const D3& e1, const D3& e2) { return {cross(e1, e2), cross_abs(e1, e2)}; }

/// Whether the triangle (a, b, c) is certainly not degenerate (its
/// corners are not collinear): some component of (b - a) x (c - a) is
/// certified nonzero.
inline bool certified_nondegenerate(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Plane p = plane(sub(b, a), sub(c, a));
  return certified_sign(p.n.x, p.n_abs.x, kCrossBound) != 0 ||
         certified_sign(p.n.y, p.n_abs.y, kCrossBound) != 0 ||
         certified_sign(p.n.z, p.n_abs.z, kCrossBound) != 0;
}

/// An interval [lo, hi] that certainly contains the exact projections
/// (x - o) . m of some points, for a fixed double vector m.
struct Interval {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(const D3& d, const D3& m) {
    const double v = dot(d, m);
    const double e = 2.0 * kProjectionBound * dot_abs(d, m);  // doubled: covers the rounding of v -/+ e
    lo = std::min(lo, v - e);
    hi = std::max(hi, v + e);
  }
};

/// What the filter reads of one face, copied into the broad phase's order
/// so that faces near in space are near in memory.
struct FaceData {
  std::array<std::uint32_t, 3> v;  ///< vertex indices
  /// Nonzero when v has three distinct indices and the corners are
  /// filterable() and certified_nondegenerate: the filter only reasons about
  /// such faces.
  char certified;
  std::array<Vec3, 3> p;  ///< the corners
};

/// The FaceData of face f of `soup`.
inline FaceData face_data(const TriangleSoup& soup, std::uint32_t f) {
  const auto& t = soup.triangles[f];
  FaceData d{t, 0, {soup.vertices[t[0]], soup.vertices[t[1]], soup.vertices[t[2]]}};
  bool ok = t[0] != t[1] && t[1] != t[2] && t[0] != t[2];
  for (const Vec3& p : d.p) ok = ok && filterable(p.x()) && filterable(p.y()) && filterable(p.z());
  d.certified = static_cast<char>(ok && certified_nondegenerate(d.p[0], d.p[1], d.p[2]));
  return d;
}

/// Proves that two faces meet at most in what they share (the negation of
/// faces_intersect_exact), or gives up.
class FacePairFilter {
 public:
  /// True when the faces certainly do not intersect in the sense of
  /// faces_intersect_exact; false when the filter cannot tell.
  bool disjoint(const FaceData& a, const FaceData& b) const {
    if (!a.certified || !b.certified) return false;
    int shared = 0;
    int ia = -1;
    int ib = -1;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        if (a.v[i] == b.v[j]) {
          ++shared;
          ia = i;
          ib = j;
        }
      }
    }
    if (shared == 0) return apart(a.p, b.p);
    if (shared == 1) return touch_at_vertex_only(a.p, b.p, ia, ib);
    if (shared == 2) return not_folded(a, b);
    return true;  // the same face: never reported by the exact test either
  }

 private:
  using Corners = std::array<Vec3, 3>;

  /// Two faces sharing no vertex: a separating plane certifies they are
  /// disjoint, and then (both being non-degenerate) CGAL's exact
  /// triangle-triangle test is false too.
  static bool apart(const Corners& a, const Corners& b) {
    const Vec3& o = a[0];
    // 1. The line between the centroids, as a projection axis.
    const D3 m = sub(a[0] + a[1] + a[2], b[0] + b[1] + b[2]);
    Interval ia;
    Interval ib;
    for (int i = 0; i < 3; ++i) {
      ia.add(sub(a[i], o), m);
      ib.add(sub(b[i], o), m);
    }
    if (ia.lo > ib.hi || ib.lo > ia.hi) return true;
    // Both in one plane x, y or z = c (the top of a slab): the planes of 2.
    // cannot separate them, and 3. is a test in that plane.
    const int axis = common_axis_plane(a, b);
    if (axis >= 0) return beyond_an_edge_in_plane(a, b, axis) || beyond_an_edge_in_plane(b, a, axis);
    // 2. The plane of each face (exact orientation signs).
    if (all_one_side(a, b) || all_one_side(b, a)) return true;
    // 3. A plane through an edge of one face, across it (for faces in one
    //    plane, an edge's line in that plane): the separating axes of coplanar
    //    triangles, which the planes of 2. cannot give.
    return beyond_an_edge(a, b) || beyond_an_edge(b, a);
  }

  /// The axis k when every corner of a and b has the same coordinate k
  /// (exactly), else -1.
  static int common_axis_plane(const Corners& a, const Corners& b) {
    for (int k = 0; k < 3; ++k) {
      const double c = a[0][k];
      if (a[1][k] == c && a[2][k] == c && b[0][k] == c && b[1][k] == c && b[2][k] == c) return k;
    }
    return -1;
  }

  /// beyond_an_edge for faces in the plane normal to `axis`: there
  /// (e x x) . (e x f) is the product of the 2D cross products e x x and
  /// e x f, each certified as a 2 x 2 minor.
  static bool beyond_an_edge_in_plane(const Corners& s, const Corners& t, int axis) {
    const int u = (axis + 1) % 3;
    const int v = (axis + 2) % 3;
    const auto side = [&](const Vec3& o, const Vec3& e_end, const Vec3& x) {
      const double ex = e_end[u] - o[u], ey = e_end[v] - o[v];
      const double xx = x[u] - o[u], xy = x[v] - o[v];
      return certified_sign(ex * xy - ey * xx, std::abs(ex * xy) + std::abs(ey * xx), kCrossBound);
    };
    for (int i = 0; i < 3; ++i) {
      const Vec3& o = s[i];
      const Vec3& e = s[(i + 1) % 3];
      const int inside = side(o, e, s[(i + 2) % 3]);
      if (inside == 0) continue;
      if (side(o, e, t[0]) == -inside && side(o, e, t[1]) == -inside && side(o, e, t[2]) == -inside)
        return true;
    }
    return false;
  }

  /// Sign of (e x x) . (e x f), certified (0: unknown): which side of the
  /// plane through the line of e, across the face spanned by e and f, the
  /// point at x lies on (the face's side is positive).
  static int across(const D3& e, const D3& x, const D3& f) {
    return certified_sign(dot(cross(e, x), cross(e, f)), dot_abs(cross_abs(e, x), cross_abs(e, f)),
                          kNormalsBound);
  }

  /// Whether the corners of `t` lie strictly beyond one edge of `s`: on the
  /// side of the plane through that edge, across s, away from s's third corner.
  static bool beyond_an_edge(const Corners& s, const Corners& t) {
    for (int i = 0; i < 3; ++i) {
      const Vec3& o = s[i];
      const D3 e = sub(s[(i + 1) % 3], o);
      const D3 f = sub(s[(i + 2) % 3], o);
      if (across(e, sub(t[0], o), f) < 0 && across(e, sub(t[1], o), f) < 0 && across(e, sub(t[2], o), f) < 0)
        return true;
    }
    return false;
  }

  /// Whether the three corners of `t` lie strictly on one side of the plane of `s`.
  static bool all_one_side(const Corners& s, const Corners& t) {
    const Vec3& o = s[0];
    const Plane p = plane(sub(s[1], o), sub(s[2], o));
    const int s0 = p.side(sub(t[0], o));
    if (s0 == 0) return false;
    return p.side(sub(t[1], o)) == s0 && p.side(sub(t[2], o)) == s0;
  }

  /// Two faces sharing vertex p (a[ia] == b[ib]). The exact test asks whether
  /// the edge opposite p in one face touches the other; for non-degenerate
  /// faces that is the same as "they meet beyond p". Proved false by a plane
  /// through p with one face strictly on each side (apart from p), by the
  /// far edge of one face lying strictly on one side of the other's plane,
  /// or by the far corners of one face lying strictly beyond the plane
  /// through p and an edge of the other, across it (that face lies on the
  /// other side, touching the plane only along its edge: for a1 and a2 from
  /// p, (a1 x a2) . (a1 x a2) > 0 and (a1 x a1) = 0).
  static bool touch_at_vertex_only(const Corners& a, const Corners& b, int ia, int ib) {
    const Vec3& p = a[ia];
    const D3 a1 = sub(a[(ia + 1) % 3], p);
    const D3 a2 = sub(a[(ia + 2) % 3], p);
    const D3 b1 = sub(b[(ib + 1) % 3], p);
    const D3 b2 = sub(b[(ib + 2) % 3], p);
    // 1. A plane through p between the two wedges: normal (a1 + a2) - (b1 + b2).
    const D3 m{(a1.x + a2.x) - (b1.x + b2.x), (a1.y + a2.y) - (b1.y + b2.y), (a1.z + a2.z) - (b1.z + b2.z)};
    Interval wa;
    Interval wb;
    wa.add(a1, m);
    wa.add(a2, m);
    wb.add(b1, m);
    wb.add(b2, m);
    if ((wa.lo > 0.0 && wb.hi < 0.0) || (wa.hi < 0.0 && wb.lo > 0.0)) return true;
    // 2. The far edge of one face strictly on one side of the other's plane.
    const Plane pa = plane(a1, a2);
    const int s1 = pa.side(b1);
    if (s1 != 0 && pa.side(b2) == s1) return true;
    const Plane pb = plane(b1, b2);
    const int s2 = pb.side(a1);
    if (s2 != 0 && pb.side(a2) == s2) return true;
    // 3. The plane through p and one edge of one face, across that face,
    //    with the other face's far corners strictly beyond it (coplanar fans).
    return (across(a1, b1, a2) < 0 && across(a1, b2, a2) < 0) ||
           (across(a2, b1, a1) < 0 && across(a2, b2, a1) < 0) ||
           (across(b1, a1, b2) < 0 && across(b1, a2, b2) < 0) ||
           (across(b2, a1, b1) < 0 && across(b2, a2, b1) < 0);
  }

  /// Two faces sharing edge pq, with third vertices r (in a) and s (in b).
  /// The exact test is "coplanar and r, s on the same side of pq": false when
  /// the normals of pqr and pqs certainly point apart (if the four points are
  /// coplanar, r and s are then on opposite sides) or when the four points
  /// are certainly not coplanar.
  static bool not_folded(const FaceData& a, const FaceData& b) {
    int r = 0;  // corner of a not in b, and of b not in a
    int s = 0;
    for (int i = 0; i < 3; ++i) {
      if (a.v[i] != b.v[0] && a.v[i] != b.v[1] && a.v[i] != b.v[2]) r = i;
      if (b.v[i] != a.v[0] && b.v[i] != a.v[1] && b.v[i] != a.v[2]) s = i;
    }
    // p, q: the other two corners of a, in a's order (as the reference takes them).
    const Vec3& p = a.p[r == 0 ? 1 : 0];
    const Vec3& q = a.p[r == 2 ? 1 : 2];
    const D3 e1 = sub(q, p);
    const D3 e2 = sub(a.p[r], p);
    const D3 e3 = sub(b.p[s], p);
    const Plane n1 = plane(e1, e2);
    const Plane n2 = plane(e1, e3);
    if (certified_sign(dot(n1.n, n2.n), dot_abs(n1.n_abs, n2.n_abs), kNormalsBound) < 0) return true;
    return n1.side(e3) != 0;
  }
};

}  // namespace fabmesh::detail
