#include "geometry/mould/casting_case.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "geometry/core/errors.h"
#include "geometry/mesh/bounding_box.h"

namespace fabmesh {
namespace {

using Index = std::uint32_t;
using Triangle = std::array<Index, 3>;

// The sign of the orientation of the triangle (a, b, c) of the plane:
// +1 counter-clockwise, -1 clockwise, 0 collinear, or none when floating
// point cannot decide it. Shewchuk's first filter: the computed determinant's
// sign is the exact one once it exceeds its rounding bound; a factor that is
// exactly zero (two equal coordinates: a face parallel to an axis) makes its
// product exactly zero.
std::optional<int> orientation_sign(const std::array<double, 2>& a, const std::array<double, 2>& b,
                                    const std::array<double, 2>& c) {
  const double ax = a[0] - c[0], ay = a[1] - c[1], bx = b[0] - c[0], by = b[1] - c[1];
  const double left = ax * by;
  const double right = ay * bx;
  const double det = left - right;
  constexpr double kUnit = std::numeric_limits<double>::epsilon() / 2.0;  // the unit roundoff
  const double bound = (3.0 + 16.0 * kUnit) * kUnit * (std::abs(left) + std::abs(right));
  if (det > bound) return 1;
  if (-det > bound) return -1;
  const bool left_zero = ax == 0.0 || by == 0.0;
  const bool right_zero = ay == 0.0 || bx == 0.0;
  if (left_zero && right_zero) return 0;
  return std::nullopt;
}

// An axis direction: sign x e_k.
struct Axis {
  int k = 0;
  int sign = 1;
};

std::string axis_name(const Axis& a) { return std::string(a.sign > 0 ? "+" : "-") + "xyz"[a.k]; }

Vec3 axis_vector(const Axis& a) {
  Vec3 v = Vec3::Zero();
  v[a.k] = a.sign;
  return v;
}

// The two in-plane coordinates of the plane across axis k, in the cyclic
// order that makes a triangle's 2D orientation the sign of its normal's k component.
std::array<double, 2> in_plane(const Vec3& p, int k) { return {p[(k + 1) % 3], p[(k + 2) % 3]}; }

std::string point_text(const Vec3& p) { return fmt::format("({:.4g}, {:.4g}, {:.4g})", p.x(), p.y(), p.z()); }

// What holds the part along one direction, or the case when nothing does.
struct Attempt {
  std::optional<CastingCase> built;
  std::string why_not;
};

// Whether the point is a corner of the rectangle lo..hi.
bool is_corner(const std::array<double, 2>& q, const std::array<double, 2>& lo,
               const std::array<double, 2>& hi) {
  return (q[0] == lo[0] || q[0] == hi[0]) && (q[1] == lo[1] || q[1] == hi[1]);
}

Attempt attempt(const TriangleSoup& part, const std::string& name, const Axis& axis,
                const CaseOptions& options, const std::function<std::string(const Vec3&)>& what_is_at) {
  const int k = axis.k;
  const BoundingBox box = bounding_box(part.vertices);
  const double extreme = axis.sign > 0 ? box.hi[k] : box.lo[k];
  const std::array<double, 2> lo = in_plane(box.lo, k), hi = in_plane(box.hi, k);
  const std::string dir = axis_name(axis);

  // The pour face: the triangles in the extreme plane. Every other triangle
  // must face away from the pull or along it.
  const auto in_pour_plane = [&](const Triangle& t) {
    return part.vertices[t[0]][k] == extreme && part.vertices[t[1]][k] == extreme &&
           part.vertices[t[2]][k] == extreme;
  };
  std::vector<Triangle> pour, rest;
  for (const Triangle& t : part.triangles) (in_pour_plane(t) ? pour : rest).push_back(t);
  if (pour.empty()) {
    return {std::nullopt, fmt::format("it has no flat face across {} to pour through (its outside there is "
                                      "curved or stepped)",
                                      dir)};
  }
  std::size_t parallel = 0;
  for (const Triangle& t : part.triangles) {
    const Vec3 &a = part.vertices[t[0]], &b = part.vertices[t[1]], &c = part.vertices[t[2]];
    const std::optional<int> s = orientation_sign(in_plane(a, k), in_plane(b, k), in_plane(c, k));
    // Where the face is, for a refusal only.
    const auto at = [&] {
      const Vec3 centroid = (a + b + c) / 3.0;
      return point_text(centroid) + (what_is_at ? what_is_at(centroid) : std::string());
    };
    if (in_pour_plane(t)) {
      if (s != axis.sign) {
        return {std::nullopt, fmt::format("its face at {} in its {} plane does not face {}", at(), dir, dir)};
      }
    } else if (!s) {
      return {std::nullopt,
              fmt::format("whether its face at {} faces {} cannot be decided in floating point", at(), dir)};
    } else if (*s * axis.sign > 0) {
      return {std::nullopt,
              fmt::format("its face at {} faces {}: pulled that way, the part would catch on the case there",
                          at(), dir)};
    } else if (*s == 0) {
      ++parallel;
    }
  }

  // The pour face's border: its edges used once, one loop along the
  // bounding rectangle through its four corners (then, the mesh being closed
  // and embedded, the face is the whole rectangle).
  std::map<std::pair<Index, Index>, int> edges;
  for (const Triangle& t : pour) {
    for (int e = 0; e < 3; ++e) edges[{t[e], t[(e + 1) % 3]}] += 1;
  }
  std::map<Index, Index> next;  // border: u -> v
  for (const auto& [e, n] : edges) {
    if (edges.count({e.second, e.first}) == 0) {
      if (n != 1 || !next.emplace(e.first, e.second).second) {
        return {std::nullopt, fmt::format("its face across {} is not one simple region", dir)};
      }
    }
  }
  const auto not_rectangle = [&] {
    return Attempt{std::nullopt,
                   fmt::format("its flat face across {} does not cover its whole outline there (the outline "
                               "is not a rectangle), so plaster poured level would not reproduce it",
                               dir)};
  };
  std::optional<Index> start;
  for (const auto& [u, v] : next) {
    const std::array<double, 2> q = in_plane(part.vertices[u], k);
    if (q[0] != lo[0] && q[0] != hi[0] && q[1] != lo[1] && q[1] != hi[1]) return not_rectangle();
    if (!start && is_corner(q, lo, hi)) start = u;
  }
  if (!start) return not_rectangle();
  // Walk the loop from a corner: the runs between consecutive corners are the sides.
  std::vector<std::vector<Index>> sides;
  Index u = *start;
  std::size_t walked = 0;
  do {
    if (is_corner(in_plane(part.vertices[u], k), lo, hi)) {
      if (!sides.empty()) sides.back().push_back(u);
      sides.emplace_back();
    }
    sides.back().push_back(u);
    u = next.at(u);
    if (++walked > next.size()) return not_rectangle();
  } while (u != *start);
  sides.back().push_back(u);
  if (walked != next.size() || sides.size() != 4) return not_rectangle();
  for (const std::vector<Index>& side : sides) {  // each side straight along the rectangle
    const std::array<double, 2> a = in_plane(part.vertices[side.front()], k);
    const std::array<double, 2> b = in_plane(part.vertices[side.back()], k);
    const int along = a[0] == b[0] ? 0 : (a[1] == b[1] ? 1 : -1);
    if (along < 0) return not_rectangle();
    for (Index w : side) {
      if (in_plane(part.vertices[w], k)[along] != a[along]) return not_rectangle();
    }
  }

  // The case: the part's other triangles turned inside out, the rim in the
  // pour plane from the face's border out to the box, the walls and the floor.
  CastingCase out;
  std::vector<Index> remap(part.vertices.size(), std::numeric_limits<Index>::max());
  const auto vertex = [&](Index v) {
    if (remap[v] == std::numeric_limits<Index>::max()) {
      remap[v] = static_cast<Index>(out.soup.vertices.size());
      out.soup.vertices.push_back(part.vertices[v]);
    }
    return remap[v];
  };
  for (const Triangle& t : rest) out.soup.triangles.push_back({vertex(t[0]), vertex(t[2]), vertex(t[1])});
  const double w = options.wall;
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  std::array<Index, 4> rim{}, floor{};  // by corner, in loop order
  for (std::size_t n = 0; n < 4; ++n) {
    Vec3 o = part.vertices[sides[n].front()];
    o[i] += o[i] == box.hi[i] ? w : -w;
    o[j] += o[j] == box.hi[j] ? w : -w;
    Vec3 f = o;
    f[k] = axis.sign > 0 ? box.lo[k] - w : box.hi[k] + w;
    rim[n] = static_cast<Index>(out.soup.vertices.size());
    out.soup.vertices.push_back(o);
    floor[n] = static_cast<Index>(out.soup.vertices.size());
    out.soup.vertices.push_back(f);
  }
  for (std::size_t n = 0; n < 4; ++n) {
    const std::size_t m = (n + 1) % 4;
    const std::vector<Index>& side = sides[n];  // from corner n to corner m, along the loop
    // The trapezoid rim[n], rim[m], then the side backwards: a fan from rim[n].
    out.soup.triangles.push_back({rim[n], rim[m], vertex(side.back())});
    for (std::size_t p = side.size() - 1; p > 0; --p) {
      out.soup.triangles.push_back({rim[n], vertex(side[p]), vertex(side[p - 1])});
    }
    out.soup.triangles.push_back({rim[m], rim[n], floor[n]});
    out.soup.triangles.push_back({rim[m], floor[n], floor[m]});
  }
  out.soup.triangles.push_back({floor[0], floor[3], floor[2]});
  out.soup.triangles.push_back({floor[0], floor[2], floor[1]});

  out.pull = axis_vector(axis);
  out.lo = box.lo - Vec3::Constant(w);
  out.hi = box.hi + Vec3::Constant(w);
  (axis.sign > 0 ? out.hi : out.lo)[k] = extreme;
  out.pour_area = (hi[0] - lo[0]) * (hi[1] - lo[1]);
  out.release_proof = fmt::format(
      "{} leaves its case along {}: its flat face across {} ({:.6g} x {:.6g}) is the case's opening, and "
      "none of its other {} faces faces {} ({} run along it), by exact orientation signs",
      name, dir, dir, hi[0] - lo[0], hi[1] - lo[1], rest.size(), dir, parallel);
  return {std::move(out), {}};
}

}  // namespace

TriangleSoup standing(const CastingCase& c, const Vec3& corner) {
  // A right-handed frame of axis vectors with z along the pull: coordinates
  // in it are the old ones permuted and negated, so nothing rounds.
  const Vec3 ez = c.pull;
  const Vec3 ex = std::abs(ez.z()) == 1.0 ? Vec3(1.0, 0.0, 0.0) : Vec3(0.0, 0.0, 1.0);
  const Vec3 ey = ez.cross(ex);
  const auto turned = [&](const Vec3& p) { return Vec3(p.dot(ex), p.dot(ey), p.dot(ez)); };
  const Vec3 a = turned(c.lo), b = turned(c.hi);
  const Vec3 lo = a.cwiseMin(b);
  TriangleSoup out = c.soup;
  for (Vec3& p : out.vertices) p = turned(p) - lo + corner;
  return out;
}

CastingCase build_casting_case(const TriangleSoup& part, const std::string& name, const Vec3& outward,
                               const CaseOptions& options,
                               const std::function<std::string(const Vec3&)>& what_is_at) {
  if (!(options.wall > 0.0) || !std::isfinite(options.wall)) {
    throw RangeError("wall", options.wall,
                     fmt::format("case.wall = {} must be a length above 0", options.wall),
                     ErrorLocation{"case.wall"});
  }
  if (part.triangles.empty()) throw GeometryError("case", name + " has no triangles to make a case of");
  std::vector<Axis> axes;
  for (int k = 0; k < 3; ++k) {
    for (int sign : {1, -1}) axes.push_back({k, sign});
  }
  std::stable_sort(axes.begin(), axes.end(), [&](const Axis& a, const Axis& b) {
    return outward[a.k] * a.sign > outward[b.k] * b.sign;
  });
  std::string first_reason;
  for (const Axis& axis : axes) {
    Attempt a = attempt(part, name, axis, options, what_is_at);
    if (a.built) return std::move(*a.built);
    if (first_reason.empty()) first_reason = fmt::format("pulled along {}, {}", axis_name(axis), a.why_not);
  }
  throw GeometryError("case", fmt::format("no one-piece casting case releases {}: {}; no other axis "
                                          "direction has a flat face to pour through that releases it "
                                          "either",
                                          name, first_reason));
}

}  // namespace fabmesh
