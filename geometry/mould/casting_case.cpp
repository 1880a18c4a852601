#include "geometry/mould/casting_case.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "geometry/core/errors.h"
#include "geometry/mesh/bounding_box.h"
#include "geometry/mesh/short_edges.h"
#include "geometry/mesh/volume.h"
#include "geometry/mould/case_pins.h"
#include "geometry/repair/exact_booleans.h"
#include "geometry/section/region.h"
#include "geometry/section/triangulate.h"
#include "geometry/validation/validate.h"

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

// Where the part's triangle t is (its centroid), and what feature of the
// part is there when `what_is_at` says, for a refusal's message.
std::string where(const TriangleSoup& part, std::size_t t,
                  const std::function<std::string(const Vec3&)>& what_is_at) {
  const auto& tri = part.triangles[t];
  const Vec3 centroid = (part.vertices[tri[0]] + part.vertices[tri[1]] + part.vertices[tri[2]]) / 3.0;
  return point_text(centroid) + (what_is_at ? what_is_at(centroid) : std::string());
}

// What holds the part along one direction, or the case when nothing does.
struct Attempt {
  std::optional<CastingCase> built;
  std::string why_not;
  bool catches = false;  // the pour face is fine but faces catch: carving may release it
};

// Whether the point is a corner of the rectangle lo..hi.
bool is_corner(const std::array<double, 2>& q, const std::array<double, 2>& lo,
               const std::array<double, 2>& hi) {
  return (q[0] == lo[0] || q[0] == hi[0]) && (q[1] == lo[1] || q[1] == hi[1]);
}

constexpr Index kNone = std::numeric_limits<Index>::max();

// The side of its plane a triangle faces: the sign of its normal's
// component along axis k, exactly (the filter first; a face along the axis
// but across none other, whose two products cancel, decided exactly).
int facing(const TriangleSoup& part, const Triangle& t, int k) {
  const Vec3 &a = part.vertices[t[0]], &b = part.vertices[t[1]], &c = part.vertices[t[2]];
  if (const std::optional<int> s = orientation_sign(in_plane(a, k), in_plane(b, k), in_plane(c, k)))
    return *s;
  Vec3 along = Vec3::Zero();
  along[k] = 1.0;
  return exact_facing(a, b, c, along);
}

// Appends triangles covering the region bounded by the simple polygon
// `cycle` less the simple polygons `holes` inside it (indices into
// soup.vertices, lying in a plane across axis k), facing sign x e_k: a
// constrained triangulation of their points, none added. False when the
// points do not bound such a region.
bool fill_region(TriangleSoup& soup, const std::vector<Index>& cycle,
                 const std::vector<std::vector<Index>>& holes, int k, int sign) {
  std::map<std::array<double, 2>, Index> at;
  Region2 region;
  std::size_t points = 0;
  // A loop's points in the plane, counter-clockwise (outer) or clockwise (hole).
  const auto loop = [&](const std::vector<Index>& c, bool outer, std::vector<Vec2>& into) {
    double twice_area = 0.0;
    for (std::size_t n = 0; n < c.size(); ++n) {
      const std::array<double, 2> q = in_plane(soup.vertices[c[n]], k);
      if (!at.emplace(q, c[n]).second) return false;
      into.emplace_back(q[0], q[1]);
      const std::array<double, 2> r = in_plane(soup.vertices[c[(n + 1) % c.size()]], k);
      twice_area += q[0] * r[1] - q[1] * r[0];
    }
    if (c.size() < 3 || twice_area == 0.0) return false;
    if ((twice_area < 0.0) == outer) std::reverse(into.begin(), into.end());
    points += c.size();
    return true;
  };
  if (!loop(cycle, true, region.outer)) return false;
  for (const std::vector<Index>& hole : holes) {
    region.holes.emplace_back();
    if (!loop(hole, false, region.holes.back())) return false;
  }
  const PlanarTriangulation t = triangulate(region);
  if (t.steiner_points != 0 || t.triangles.size() != points + 2 * holes.size() - 2) return false;
  for (const auto& tri : t.triangles) {
    std::array<Index, 3> out{};
    for (int e = 0; e < 3; ++e) out[e] = at.at({t.vertices[tri[e]].x(), t.vertices[tri[e]].y()});
    if (sign < 0) std::swap(out[1], out[2]);
    soup.triangles.push_back(out);
  }
  return true;
}

bool fill_polygon(TriangleSoup& soup, const std::vector<Index>& cycle, int k, int sign) {
  return fill_region(soup, cycle, {}, k, sign);
}

// A ring of `sides` points on the circle about `centre` of `radius` in the
// plane across axis q (the centre's coordinate q), starting on the axis r.
std::vector<Index> add_ring(TriangleSoup& soup, const Vec3& centre, int q, int r, double radius,
                            std::size_t sides) {
  const int t = 3 - q - r;
  std::vector<Index> ring;
  for (std::size_t n = 0; n < sides; ++n) {
    const double angle = 2.0 * M_PI * static_cast<double>(n) / static_cast<double>(sides);
    Vec3 p = centre;
    p[r] += radius * std::cos(angle);
    p[t] += radius * std::sin(angle);
    soup.vertices.push_back(p);
    ring.push_back(static_cast<Index>(soup.vertices.size() - 1));
  }
  return ring;
}

// The wall between two rings of the same points moved along an axis, its
// faces turned away from the rings' centre (`outward`) or toward it.
void add_tube(TriangleSoup& soup, const std::vector<Index>& from, const std::vector<Index>& to,
              const Vec3& centre, bool outward) {
  const std::size_t n = from.size();
  const Vec3& a = soup.vertices[from[0]];
  const Vec3 normal = (soup.vertices[from[1]] - a).cross(soup.vertices[to[0]] - a);
  const bool flip = (normal.dot(a - centre) > 0.0) != outward;
  for (std::size_t m = 0; m < n; ++m) {
    const std::size_t l = (m + 1) % n;
    std::array<Index, 3> one{from[m], from[l], to[m]}, two{from[l], to[l], to[m]};
    if (flip) {
      std::swap(one[1], one[2]);
      std::swap(two[1], two[2]);
    }
    soup.triangles.push_back(one);
    soup.triangles.push_back(two);
  }
}

// The part's triangles as copied into a piece: vertices added on first use.
struct Copier {
  const TriangleSoup& from;
  TriangleSoup& to;
  std::vector<Index> remap = std::vector<Index>(from.vertices.size(), kNone);
  Index operator()(Index v) {
    if (remap[v] == kNone) {
      remap[v] = static_cast<Index>(to.vertices.size());
      to.vertices.push_back(from.vertices[v]);
    }
    return remap[v];
  }
  void flipped(const Triangle& t) { to.triangles.push_back({(*this)(t[0]), (*this)(t[2]), (*this)(t[1])}); }
};

Index add_vertex(TriangleSoup& soup, const Vec3& p) {
  soup.vertices.push_back(p);
  return static_cast<Index>(soup.vertices.size() - 1);
}

// A plate: the triangles of the part on one side face of its bounding box
// (axis q, side s) and behind it, and the loop bounding them.
struct PlateFace {
  int q = 0;
  int s = 1;
  double e = 0.0;            // the face's plane: coordinate q
  std::vector<bool> member;  // by triangle
  std::size_t triangles = 0, features = 0, parallel = 0;
  std::size_t side = 0;     // the pour face's side lying on the face
  std::vector<Index> path;  // the loop off the pour face: corner `side` to the next corner
};

// The pour face and the part's triangles, indexed by directed edge.
struct Faces {
  const TriangleSoup& part;
  std::vector<bool> pour;
  std::map<std::pair<Index, Index>, std::size_t> by_edge;  // directed edge -> triangle
  std::size_t twin(std::size_t t, int e) const {
    const Triangle& tri = part.triangles[t];
    const auto it = by_edge.find({tri[(e + 1) % 3], tri[e]});
    return it == by_edge.end() ? part.triangles.size() : it->second;
  }
  /// The border of the triangles in `member`: each edge whose twin is not
  /// in it, u -> v; none when a vertex starts two of them (not one simple region).
  std::optional<std::map<Index, Index>> border(const std::vector<bool>& member) const {
    std::map<Index, Index> next;
    for (std::size_t t = 0; t < part.triangles.size(); ++t) {
      if (!member[t]) continue;
      const Triangle& tri = part.triangles[t];
      for (int e = 0; e < 3; ++e) {
        const std::size_t u = twin(t, e);
        if (u < member.size() && member[u]) continue;
        if (!next.emplace(tri[e], tri[(e + 1) % 3]).second) return std::nullopt;
      }
    }
    return next;
  }
};

// What a plate on the face (q, s) would take: the part's triangles on that
// side face of its bounding box and the regions behind it bounded by them
// alone; none when the part has no triangle there.
std::optional<PlateFace> plate_members(const Faces& f, const BoundingBox& box, int q, int s) {
  const TriangleSoup& part = f.part;
  const std::size_t count = part.triangles.size();
  PlateFace p;
  p.q = q;
  p.s = s;
  p.e = s > 0 ? box.hi[q] : box.lo[q];
  p.member.assign(count, false);
  const auto on_face = [&](std::size_t t) {
    const Triangle& tri = part.triangles[t];
    return !f.pour[t] && part.vertices[tri[0]][q] == p.e && part.vertices[tri[1]][q] == p.e &&
           part.vertices[tri[2]][q] == p.e;
  };
  for (std::size_t t = 0; t < count; ++t) p.member[t] = on_face(t);
  if (std::find(p.member.begin(), p.member.end(), true) == p.member.end()) return std::nullopt;
  // What lies behind the face: the regions of the rest bounded by its
  // triangles alone (a key's socket or bump), found by flooding across edges.
  std::vector<bool> seen(count, false);
  for (std::size_t seed = 0; seed < count; ++seed) {
    if (f.pour[seed] || p.member[seed] || seen[seed]) continue;
    std::vector<std::size_t> stack{seed}, found;
    seen[seed] = true;
    bool meets_pour = false;
    while (!stack.empty()) {
      const std::size_t t = stack.back();
      stack.pop_back();
      found.push_back(t);
      for (int e = 0; e < 3; ++e) {
        const std::size_t u = f.twin(t, e);
        if (u == count) return std::nullopt;
        if (f.pour[u]) meets_pour = true;
        if (f.pour[u] || on_face(u) || seen[u]) continue;
        seen[u] = true;
        stack.push_back(u);
      }
    }
    if (!meets_pour) {
      ++p.features;
      for (std::size_t t : found) p.member[t] = true;
    }
  }
  return p;
}

// The plate `p` (plate_members), if its triangles take every one in
// `blocking`, come off along s e_q and are bounded by one loop meeting the
// pour face along the pour face's side `side`.
std::optional<PlateFace> plate_on(const Faces& f, PlateFace p, const std::vector<std::size_t>& blocking,
                                  const std::vector<std::vector<Index>>& sides) {
  const TriangleSoup& part = f.part;
  const std::size_t count = part.triangles.size();
  const int q = p.q, s = p.s;
  const auto on_face = [&](std::size_t t) {
    const Triangle& tri = part.triangles[t];
    return !f.pour[t] && part.vertices[tri[0]][q] == p.e && part.vertices[tri[1]][q] == p.e &&
           part.vertices[tri[2]][q] == p.e;
  };
  for (std::size_t t : blocking) {
    if (!p.member[t]) return std::nullopt;
  }
  // It comes off the part: each of its faces faces s e_q or runs along it.
  for (std::size_t t = 0; t < count; ++t) {
    if (!p.member[t]) continue;
    ++p.triangles;
    const int sign = facing(part, part.triangles[t], q);
    if (sign * s < 0 || (on_face(t) && sign != s)) return std::nullopt;
    if (sign == 0) ++p.parallel;
  }
  // Its border: one loop, part of it on the pour face's side lying on the face.
  const std::optional<std::map<Index, Index>> border = f.border(p.member);
  if (!border) return std::nullopt;
  const std::map<Index, Index>& next = *border;
  std::optional<std::size_t> side;
  for (std::size_t n = 0; n < sides.size(); ++n) {
    if (part.vertices[sides[n].front()][q] == p.e && part.vertices[sides[n].back()][q] == p.e) side = n;
  }
  if (!side) return std::nullopt;
  p.side = *side;
  // The loop runs the pour face's side backwards, then from its first corner round to its last.
  const Index from = sides[*side].front(), to = sides[*side].back();
  Index u = from;
  p.path.push_back(u);
  while (u != to) {
    const auto it = next.find(u);
    if (it == next.end() || p.path.size() > next.size()) return std::nullopt;
    u = it->second;
    p.path.push_back(u);
  }
  if (p.path.size() - 1 + sides[*side].size() - 1 != next.size()) return std::nullopt;
  return p;
}

// The pour face across an axis direction and what the pull meets: the
// part's faces but the pour face's that face the pull (or whose facing
// cannot be decided), and those that run along it.
struct Pour {
  Faces faces;
  std::vector<Triangle> pour;
  std::vector<std::vector<Index>> sides;  // the pour face's border, corner to corner (a rectangle's)
  std::vector<std::size_t> blocking;
  std::size_t parallel = 0;
  double area = 0.0;  // the pour face's
};

// The pour face of `part` across `axis`, or why it has none that plaster
// poured level would reproduce (in `why`), and what pulling the part along
// `pull` meets. With `rectangle`, the face must cover the part's outline
// there (a box mould's parts: the case's rim is then the rectangle between
// the part's box and the case's); else it may be any one region (a
// cylinder mould's: the rim is cut around it).
std::optional<Pour> analyse(const TriangleSoup& part, const Axis& axis, const Axis& pull, bool rectangle,
                            const std::function<std::string(std::size_t)>& at, std::string& why) {
  const int k = axis.k;
  const BoundingBox box = bounding_box(part.vertices);
  const double extreme = axis.sign > 0 ? box.hi[k] : box.lo[k];
  const std::array<double, 2> lo = in_plane(box.lo, k), hi = in_plane(box.hi, k);
  const std::string dir = axis_name(axis);
  // The pour face: the triangles in the extreme plane. Every other triangle
  // must face away from the pull or along it, or lie on a plate.
  Pour out{Faces{part, std::vector<bool>(part.triangles.size(), false), {}}, {}, {}, {}, 0, 0.0};
  Faces& faces = out.faces;
  std::vector<Triangle>& pour = out.pour;
  for (std::size_t t = 0; t < part.triangles.size(); ++t) {
    const Triangle& tri = part.triangles[t];
    faces.pour[t] = part.vertices[tri[0]][k] == extreme && part.vertices[tri[1]][k] == extreme &&
                    part.vertices[tri[2]][k] == extreme;
    if (faces.pour[t]) pour.push_back(tri);
    for (int e = 0; e < 3; ++e) faces.by_edge[{tri[e], tri[(e + 1) % 3]}] = t;
  }
  if (pour.empty()) {
    why = fmt::format(
        "it has no flat face across {} to pour through (its outside there is "
        "curved or stepped)",
        dir);
    return std::nullopt;
  }
  std::size_t& parallel = out.parallel;
  std::vector<std::size_t>& blocking = out.blocking;
  for (std::size_t t = 0; t < part.triangles.size(); ++t) {
    if (faces.pour[t]) {
      if (facing(part, part.triangles[t], k) != axis.sign) {
        why = fmt::format("its face at {} in its {} plane does not face {}", at(t), dir, dir);
        return std::nullopt;
      }
      const Triangle& tri = part.triangles[t];
      out.area += 0.5 * (part.vertices[tri[1]] - part.vertices[tri[0]])
                            .cross(part.vertices[tri[2]] - part.vertices[tri[0]])
                            .norm();
      continue;
    }
    const int s = facing(part, part.triangles[t], pull.k);
    if (s * pull.sign > 0) {
      blocking.push_back(t);
    } else if (s == 0) {
      ++parallel;
    }
  }

  // The pour face's border: its edges used once, one loop along the
  // bounding rectangle through its four corners (then, the mesh being closed
  // and embedded, the face is the whole rectangle).
  const std::optional<std::map<Index, Index>> pour_border = faces.border(faces.pour);
  if (!pour_border) {
    why = fmt::format("its face across {} is not one simple region", dir);
    return std::nullopt;
  }
  const std::map<Index, Index>& next = *pour_border;  // border: u -> v
  if (!rectangle) return out;
  const auto not_rectangle = [&]() -> std::optional<Pour> {
    why = fmt::format(
        "its flat face across {} does not cover its whole outline there (the outline "
        "is not a rectangle), so plaster poured level would not reproduce it",
        dir);
    return std::nullopt;
  };
  std::optional<Index> start;
  for (const auto& [u, v] : next) {
    const std::array<double, 2> q = in_plane(part.vertices[u], k);
    if (q[0] != lo[0] && q[0] != hi[0] && q[1] != lo[1] && q[1] != hi[1]) return not_rectangle();
    if (!start && is_corner(q, lo, hi)) start = u;
  }
  if (!start) return not_rectangle();
  // Walk the loop from a corner: the runs between consecutive corners are the sides.
  std::vector<std::vector<Index>>& sides = out.sides;
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

  return out;
}

Attempt attempt(const TriangleSoup& part, const std::string& name, const Axis& axis,
                const CaseOptions& options, const std::function<std::string(const Vec3&)>& what_is_at) {
  const int k = axis.k;
  const BoundingBox box = bounding_box(part.vertices);
  const double extreme = axis.sign > 0 ? box.hi[k] : box.lo[k];
  const std::array<double, 2> lo = in_plane(box.lo, k), hi = in_plane(box.hi, k);
  const std::string dir = axis_name(axis);

  // Where a face is, for a refusal only.
  const auto at = [&](std::size_t t) { return where(part, t, what_is_at); };
  // Why a face that does not face away from the pull holds the part.
  const auto catches = [&](std::size_t t) {
    return fmt::format("its face at {} faces {}: pulled that way, the part would catch on the case there",
                       at(t), dir);
  };
  std::string why;
  std::optional<Pour> analysed = analyse(part, axis, axis, true, at, why);
  if (!analysed) return {std::nullopt, why};
  const Faces& faces = analysed->faces;
  const std::vector<Triangle>& pour = analysed->pour;
  const std::vector<std::vector<Index>>& sides = analysed->sides;
  const std::vector<std::size_t>& blocking = analysed->blocking;
  const std::size_t parallel = analysed->parallel;

  // What would catch, on a plate that comes off first: the first side face
  // of the bounding box whose plate takes it all.
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  std::optional<PlateFace> plate;
  if (!blocking.empty()) {
    std::vector<PlateFace> candidates;
    for (int q : {i, j}) {
      for (int s : {-1, 1}) {
        if (std::optional<PlateFace> p = plate_members(faces, box, q, s)) candidates.push_back(std::move(*p));
      }
    }
    for (const PlateFace& p : candidates) {
      if (!plate) plate = plate_on(faces, p, blocking, sides);
    }
    if (!plate) {
      // Name the first face no plate would take (a plate would take a base
      // key's socket, so naming it would send the reader the wrong way).
      for (std::size_t t : blocking) {
        const bool taken = std::any_of(candidates.begin(), candidates.end(),
                                       [t](const PlateFace& p) { return p.member[t]; });
        if (!taken) {
          return {std::nullopt, catches(t) + ", and no plate on a flat side of the part would take that face",
                  true};
        }
      }
      return {std::nullopt, catches(blocking.front()), true};
    }
  }

  // The case: the part's other triangles turned inside out, the rim in the
  // pour plane from the face's border out to the box, the walls and the
  // floor. A plate's side of the box lies on the part's face instead, and
  // the face's outline, filled out to the box, is where the plate meets it.
  CastingCase out;
  Copier vertex{part, out.soup};
  for (std::size_t t = 0; t < part.triangles.size(); ++t) {
    if (!faces.pour[t] && !(plate && plate->member[t])) vertex.flipped(part.triangles[t]);
  }
  const double w = options.wall;
  const double floor_at = axis.sign > 0 ? box.lo[k] - w : box.hi[k] + w;
  // The plate's pins: centred in the case's walls either side of its face
  // (beyond the part's box, so each hole has wall all round it and the main
  // piece's wall behind it), a third of the way from the floor to the
  // opening, so that the plate goes on one way round only.
  std::vector<CasePin> pins;
  const int across = plate ? (plate->q == i ? j : i) : 0;  // the face's other axis but k
  if (plate) {
    CasePin pin = case_pin(options);
    pin.buried = 0.0;  // it stands on the plate's face
    pin.axis[plate->q] = -plate->s;
    const double along = floor_at + (extreme - floor_at) / 3.0;
    if (!(std::abs(along - floor_at) > pin.hole_radius && std::abs(extreme - along) > pin.hole_radius)) {
      return {std::nullopt, fmt::format("its case is too shallow along {} for the plate's pins", dir)};
    }
    for (double centre : {box.lo[across] - w / 2.0, box.hi[across] + w / 2.0}) {
      pin.base = Vec3::Zero();
      pin.base[plate->q] = plate->e;
      pin.base[across] = centre;
      pin.base[k] = along;
      pins.push_back(pin);
    }
  }
  std::array<Index, 4> rim{}, floor{};  // by corner, in loop order
  for (std::size_t n = 0; n < 4; ++n) {
    Vec3 o = part.vertices[sides[n].front()];
    for (int a : {i, j}) {
      if (!(plate && plate->q == a && o[a] == plate->e)) o[a] += o[a] == box.hi[a] ? w : -w;
    }
    Vec3 f = o;
    f[k] = floor_at;
    rim[n] = add_vertex(out.soup, o);
    floor[n] = add_vertex(out.soup, f);
  }
  const auto fill_failed = [&] {
    return Attempt{std::nullopt, fmt::format("its face across {}{} does not bound a simple region",
                                             plate->s > 0 ? "+" : "-", "xyz"[plate->q])};
  };
  std::vector<Index> seam;  // the plate's face filled out to the box: its outline in the case
  for (std::size_t n = 0; n < 4; ++n) {
    const std::size_t m = (n + 1) % 4;
    const std::vector<Index>& side = sides[n];  // from corner n to corner m, along the loop
    if (plate && plate->side == n) {
      seam = {floor[n], rim[n]};
      for (Index v : plate->path) seam.push_back(vertex(v));
      seam.push_back(rim[m]);
      seam.push_back(floor[m]);
      // The seam faces the plate, with a hole for each pin, `clearance` wider and deeper.
      std::vector<std::vector<Index>> holes;
      holes.reserve(pins.size());
      for (const CasePin& pin : pins) {
        holes.push_back(add_ring(out.soup, pin.base, plate->q, across, pin.hole_radius, pin.sides));
      }
      if (!fill_region(out.soup, seam, holes, plate->q, plate->s)) return fill_failed();
      for (std::size_t h = 0; h < pins.size(); ++h) {
        const CasePin& pin = pins[h];
        const std::vector<Index> bottom = add_ring(out.soup, pin.base + pin.hole_depth * pin.axis, plate->q,
                                                   across, pin.hole_radius, pin.sides);
        add_tube(out.soup, holes[h], bottom, pin.base, false);
        if (!fill_polygon(out.soup, bottom, plate->q, plate->s)) return fill_failed();
      }
      continue;
    }
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
  out.opening = out.pull;
  out.lo = box.lo - Vec3::Constant(w);
  out.hi = box.hi + Vec3::Constant(w);
  (axis.sign > 0 ? out.hi : out.lo)[k] = extreme;
  out.pour_area = (hi[0] - lo[0]) * (hi[1] - lo[1]);
  std::string plate_text;
  if (plate) {
    const std::string face = std::string(plate->s > 0 ? "+" : "-") + "xyz"[plate->q];
    // The plate: the slab beyond the face, under the part's triangles on it.
    CasePlate cp;
    Copier copy{part, cp.soup};
    for (std::size_t t = 0; t < part.triangles.size(); ++t) {
      if (plate->member[t]) copy.flipped(part.triangles[t]);
    }
    // The seam's vertices in the plate: floor[n], rim[n], then the part's
    // loop from corner n to corner m, then rim[m], floor[m].
    const std::size_t last = seam.size() - 1;
    std::vector<Index> top(seam.size());
    for (std::size_t n = 0; n <= last; ++n) {
      top[n] = n >= 2 && n <= last - 2 ? copy(plate->path[n - 2])
                                       : add_vertex(cp.soup, out.soup.vertices[seam[n]]);
    }
    std::vector<Index> under(top.size());
    for (std::size_t n : {std::size_t{0}, std::size_t{1}, last - 1, last}) {
      Vec3 p = cp.soup.vertices[top[n]];
      p[plate->q] += plate->s * w;
      under[n] = add_vertex(cp.soup, p);
    }
    std::vector<Index> inner;  // the pour plane's run: rim[n], the pour face's side, rim[m]
    inner.push_back(top[1]);
    for (Index v : sides[plate->side]) inner.push_back(copy(v));
    inner.push_back(top[last - 1]);
    std::vector<Index> end = inner;
    end.push_back(under[last - 1]);
    end.push_back(under[1]);
    const int r = across;
    const int r_sign = cp.soup.vertices[top[0]][r] < box.lo[r] ? -1 : 1;
    // Its face toward the main piece, with the pins standing on it.
    std::vector<std::vector<Index>> feet, tips;
    feet.reserve(pins.size());
    tips.reserve(pins.size());
    for (const CasePin& pin : pins) {
      feet.push_back(add_ring(cp.soup, pin.base, plate->q, across, pin.radius, pin.sides));
      tips.push_back(
          add_ring(cp.soup, pin.base + pin.height * pin.axis, plate->q, across, pin.radius, pin.sides));
      add_tube(cp.soup, feet.back(), tips.back(), pin.base, true);
    }
    bool pins_filled = true;
    for (const std::vector<Index>& tip : tips)
      pins_filled = pins_filled && fill_polygon(cp.soup, tip, plate->q, -plate->s);
    const bool filled =
        pins_filled && fill_region(cp.soup, top, feet, plate->q, -plate->s) &&
        fill_polygon(cp.soup, end, k, axis.sign) &&
        fill_polygon(cp.soup, {top[0], top[1], under[1], under[0]}, r, r_sign) &&
        fill_polygon(cp.soup, {top[last], top[last - 1], under[last - 1], under[last]}, r, -r_sign) &&
        fill_polygon(cp.soup, {top[0], top[last], under[last], under[0]}, k, -axis.sign) &&
        fill_polygon(cp.soup, {under[0], under[1], under[last - 1], under[last]}, plate->q, plate->s);
    if (!filled) return fill_failed();
    cp.pull = Vec3::Zero();
    cp.pull[plate->q] = plate->s;
    cp.lo = out.lo;
    cp.hi = out.hi;
    (plate->s > 0 ? cp.lo : cp.hi)[plate->q] = plate->e;
    cp.features = plate->features;
    cp.face = "its face across " + face;
    cp.pins = pins;
    cp.release_proof = fmt::format(
        "the plate comes off first along {}: the {} faces of {} on it (its flat face across {} and {} "
        "feature{} behind it) face {} or run along it ({} do), by exact orientation signs, and its {} "
        "pins run along it out of their holes",
        face, plate->triangles, name, face, plate->features, plate->features == 1 ? "" : "s", face,
        plate->parallel, pins.size());
    plate_text = fmt::format(", once the plate across {} is off,", face);
    out.plates.push_back(std::move(cp));
  }
  out.release_proof = fmt::format(
      "{} leaves its case along {}: its flat face across {} ({:.6g} x {:.6g}) is the case's opening, and "
      "none of its other {} faces{} faces {} ({} run along it), by exact orientation signs",
      name, dir, dir, hi[0] - lo[0], hi[1] - lo[1],
      part.triangles.size() - pour.size() - (plate ? plate->triangles : 0), plate_text, dir, parallel);
  if (!out.plates.empty()) out.release_proof += "; " + out.plates.front().release_proof;
  return {std::move(out), {}};
}

// ---- A case carved in several pieces, by exact booleans ----

// Exact constructions on grids: a point on the 2^-30 grid plus a multiple
// of 2^-10 times a direction on the 2^-20 grid is again on the 2^-30 grid,
// and exact while coordinates stay below 2^22.
constexpr int kPointBits = 30, kDirectionBits = 20, kLengthBits = 10;
constexpr double kLargest = 4194304.0;  // 2^22

double snapped(double x, int bits) { return std::ldexp(std::round(std::ldexp(x, bits)), -bits); }

Vec3 snapped(const Vec3& p, int bits) {
  return {snapped(p.x(), bits), snapped(p.y(), bits), snapped(p.z(), bits)};
}

// A lid's frame, across the opening's axis k: coordinates u along `across`
// (d x e_k) and v along the lid's pull d, both along axes, so that the point
// (u, v, z) is exact; the case's box (its section umin..umax, vmin..vmax,
// its floor at `floor_at`), the part's far face at `far`, the opening's face
// at `extreme` and the lid's top `to` beyond it. The lid's two sides (right:
// toward angle 0 from `across` to d, left: toward a half turn) are rays
// from the axis: the split plane through it across d, or a split face of
// the part off that plane (a mould in more than 2 parts). Each leaves the
// box at its exit, where the box's walls are split, so that the lid's region
// and the box share their triangles.
struct LidFrame {
  using P2 = std::array<double, 2>;
  int k = 2;
  Vec3 across = Vec3::UnitX(), d = Vec3::UnitY();
  double umin = 0.0, umax = 0.0, vmin = 0.0, vmax = 0.0;
  double far = 0.0, extreme = 0.0, to = 0.0, floor_at = 0.0;
  std::array<P2, 2> ray{P2{1.0, 0.0}, P2{-1.0, 0.0}};  // unit directions: right, left
  std::array<bool, 2> split{true, true};               // whether that side is the split plane
  std::array<P2, 2> exit{};

  Vec3 at(const P2& p, double z) const {
    Vec3 out = p[0] * across + p[1] * d;
    out[k] = z;
    return out;
  }
  P2 of(const Vec3& p) const { return {p.dot(across), p.dot(d)}; }
  // How far p lies outside side s (0: right, 1: left), across its ray:
  // above 0 outside the lid's wedge.
  double outside(const Vec3& p, int s) const {
    const P2 q = of(p);
    return s == 0 ? q[0] * ray[0][1] - q[1] * ray[0][0] : q[1] * ray[1][0] - q[0] * ray[1][1];
  }
  // The outward normal of side s of the lid, out of the wedge.
  Vec3 side_normal(int s) const {
    return s == 0 ? Vec3(ray[0][1] * across - ray[0][0] * d) : Vec3(ray[1][0] * d - ray[1][1] * across);
  }
  // Where on the box's outline p lies, counter-clockwise from (umin, vmin).
  double perimeter(const P2& p) const {
    const double w = umax - umin, h = vmax - vmin;
    if (p[1] == vmin) return p[0] - umin;
    if (p[0] == umax) return w + (p[1] - vmin);
    if (p[1] == vmax) return w + h + (umax - p[0]);
    return 2.0 * w + h + (vmax - p[1]);
  }
  // The box's outline with the exits, counter-clockwise.
  std::vector<P2> outline() const {
    std::vector<P2> out{{umin, vmin}, {umax, vmin}, {umax, vmax}, {umin, vmax}, exit[0], exit[1]};
    std::sort(out.begin(), out.end(), [&](const P2& a, const P2& b) { return perimeter(a) < perimeter(b); });
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }
  // The lid's part of the outline: from the right side's exit counter-clockwise to the left's.
  std::vector<P2> lid_path() const {
    const double from = perimeter(exit[0]), all = 2.0 * (umax - umin + vmax - vmin);
    const auto after = [&](const P2& p) {
      const double s = perimeter(p) - from;
      return s < 0.0 ? s + all : s;
    };
    const double end = after(exit[1]);
    std::vector<P2> corners;
    for (const P2& c : {P2{umin, vmin}, P2{umax, vmin}, P2{umax, vmax}, P2{umin, vmax}}) {
      if (after(c) > 0.0 && after(c) < end) corners.push_back(c);
    }
    std::sort(corners.begin(), corners.end(), [&](const P2& a, const P2& b) { return after(a) < after(b); });
    std::vector<P2> out{exit[0]};
    out.insert(out.end(), corners.begin(), corners.end());
    out.push_back(exit[1]);
    return out;
  }
  // The outward normal of the box's side through outline points a and b.
  Vec3 wall_normal(const P2& a, const P2& b) const {
    if (a[0] == umax && b[0] == umax) return across;
    if (a[0] == umin && b[0] == umin) return -across;
    return a[1] == vmax && b[1] == vmax ? d : Vec3(-d);
  }
};

// A prism about the axis along z (a cylinder mould's): over the polygon of
// the axis, then chords of the circle of `radius` from angle `from` to `to`
// about it (`steps` to a half turn), from z `floor` up to `top`.
struct Sector {
  double radius = 0.0, from = 0.0, to = 0.0, floor = 0.0, top = 0.0;
  std::size_t steps = 8;
  std::size_t chords = 0;  // more than the fewest chords for `steps`, if above that
  // The least distance of the chords from the axis.
  double inscribed() const { return radius * std::cos(M_PI / (2.0 * static_cast<double>(steps))); }
  std::size_t fewest() const {
    return static_cast<std::size_t>(std::ceil((to - from) / (M_PI / static_cast<double>(steps))));
  }
  std::vector<Vec3> ring() const {
    std::vector<Vec3> out{Vec3(0.0, 0.0, floor)};
    const std::size_t n = std::max(chords, fewest());
    for (std::size_t i = 0; i <= n; ++i) {
      const double a = from + (to - from) * static_cast<double>(i) / static_cast<double>(n);
      out.emplace_back(radius * std::cos(a), radius * std::sin(a), floor);
    }
    return out;
  }
  CasePrism prism() const { return {ring(), Vec3(0.0, 0.0, top - floor)}; }
  // The angle of p about the axis, from `from` on (at least `from`).
  double turn(const Vec3& p) const {
    const double a = std::atan2(p.y(), p.x());
    return a < from ? a + 2.0 * M_PI : a;
  }
  // Whether p lies in it, `margin` inside it (outside, below 0).
  bool holds(const Vec3& p, double margin) const {
    if (!(p.z() >= floor + margin && p.z() <= top - margin)) return false;
    if (p.x() == 0.0 && p.y() == 0.0) return margin <= 0.0;  // the axis: the sector's apex
    const double a = turn(p);
    const double r = std::hypot(p.x(), p.y());
    return a >= from && a <= to && r * std::sin(std::min(a - from, to - a)) >= margin &&
           r <= inscribed() - margin;
  }
};

// A piece taken off before the part leaves the case: what lies in the case
// beyond the plane through o across d (and, for a side of the part's box,
// the sockets behind it), coming off along d.
struct Cut {
  std::string what;               // "its face across -z", "its split face at 120 degrees"
  Vec3 d, o, u, v;                // u x v = d exactly; u and v across d exactly
  std::optional<PlateFace> axis;  // on a side of the part's box: the part's triangles it takes
  std::size_t features = 0;
  std::size_t touching = 0, along = 0;  // the part's faces it touches, of which run along d
  std::vector<CasePin> pins;
  Vec3 corner, ru, rv, rd;  // its region: corner + a ru + b rv + c rd, a, b, c in [0, 1]
  // A lid: the region is that box less the prism over `hollow` along
  // `hollow_along` (the block's inside, `inner` the least distance of its
  // sides from the axis, `back` the block's radius).
  bool lid = false;
  int k = 2;  // a lid's axis (the opening's)
  std::vector<Vec3> hollow;
  Vec3 hollow_along = Vec3::Zero();
  double inner = 0.0, back = 0.0, inside = 0.0;
  std::vector<TriangleSoup> regions;  // a lid's region, built with it
  LidFrame frame;                     // a lid's
  double middle = 0.0;                // a lid's polygon's radius
  std::size_t steps = 8;              // its sides over a half turn
  // A piece that takes the core too: the prisms over these sectors.
  std::vector<Sector> core;
  bool in_core(const Vec3& p, double margin) const;
  /// A lid's: whether the part's triangle t lies on the back, the only
  /// faces of the part it touches: its corners all on the block's cylinder,
  /// one off the split plane, not all in one plane across the axis.
  bool back_triangle(const TriangleSoup& part, std::size_t t) const;
};

// A cylinder mould's axis: along z.
constexpr int kAxis = 2;

// The distance of p from the axis along e_k through the origin (the mould's axis).
double radial(const Vec3& p, int k) { return std::hypot(p[(k + 1) % 3], p[(k + 2) % 3]); }

// Whether p lies in one of the core's prisms, `margin` inside it (outside, below 0).
bool Cut::in_core(const Vec3& p, double margin) const {
  return std::any_of(core.begin(), core.end(), [&](const Sector& s) { return s.holds(p, margin); });
}

bool Cut::back_triangle(const TriangleSoup& part, std::size_t t) const {
  const Triangle& tri = part.triangles[t];
  bool off = false, level = true;
  for (int e = 0; e < 3; ++e) {
    const Vec3& p = part.vertices[tri[e]];
    if (radial(p, k) < back * (1.0 - 1e-9)) return false;
    off = off || exact_side(p, o, d) > 0;
    level = level && p[k] == part.vertices[tri[0]][k];
  }
  return off && !level;
}

// The sockets behind a plate's face: the part's triangles behind it turned
// inside out, closed by their rims in the face's plane.
std::optional<TriangleSoup> socket_fills(const Faces& f, const PlateFace& p) {
  const TriangleSoup& part = f.part;
  TriangleSoup fills;
  Copier copy{part, fills};
  std::vector<bool> feature(part.triangles.size(), false);
  for (std::size_t t = 0; t < part.triangles.size(); ++t) {
    const Triangle& tri = part.triangles[t];
    if (!p.member[t]) continue;
    if (part.vertices[tri[0]][p.q] == p.e && part.vertices[tri[1]][p.q] == p.e &&
        part.vertices[tri[2]][p.q] == p.e)
      continue;
    feature[t] = true;
    copy.flipped(tri);
  }
  std::optional<std::map<Index, Index>> border = f.border(feature);
  if (!border) return std::nullopt;
  std::map<Index, Index> next = std::move(*border);
  while (!next.empty()) {
    std::vector<Index> loop;
    Index u = next.begin()->first;
    while (true) {
      const auto it = next.find(u);
      if (it == next.end()) break;
      loop.push_back(copy(u));
      u = it->second;
      next.erase(it);
    }
    if (!fill_polygon(fills, loop, p.q, p.s)) return std::nullopt;
  }
  return fills;
}

std::string vector_text(const Vec3& d) {
  const Vec3 n = d.normalized();
  return fmt::format("({:.4g}, {:.4g}, {:.4g})", n.x(), n.y(), n.z());
}

// The pour face's outline, one loop, its vertices as `copy` copies them; none
// when it is not one loop.
std::optional<std::vector<Index>> pour_loop(const Faces& faces, Copier& copy) {
  const std::optional<std::map<Index, Index>> border = faces.border(faces.pour);
  if (!border || border->empty()) return std::nullopt;
  std::vector<Index> loop;
  Index u = border->begin()->first;
  do {
    loop.push_back(copy(u));
    const auto it = border->find(u);
    if (it == border->end() || loop.size() > border->size()) return std::nullopt;
    u = it->second;
  } while (u != border->begin()->first);
  if (loop.size() != border->size()) return std::nullopt;  // more than one loop
  return loop;
}

// The block's face across `opening` (its two triangles) replaced by the
// rim around the part's pour face, filled out to the face's corners, and
// then the pour face's own triangles (`with_part` false: the block less the
// part then takes the pour face's outline as it is, adding no point on the
// part's edges there) or the part's other triangles turned inside out (true:
// the block less the part itself, built face by face). False when the rim
// cannot be filled so.
bool open_through(TriangleSoup& block, const Axis& opening, const Faces& faces, bool with_part) {
  const int k = opening.k;
  double extreme = block.vertices.front()[k];
  for (const Vec3& p : block.vertices)
    extreme = opening.sign > 0 ? std::max(extreme, p[k]) : std::min(extreme, p[k]);
  std::vector<Index> corners;
  for (Index v = 0; v < block.vertices.size(); ++v) {
    if (block.vertices[v][k] == extreme) corners.push_back(v);
  }
  const auto on_face = [&](const Triangle& t) {
    return block.vertices[t[0]][k] == extreme && block.vertices[t[1]][k] == extreme &&
           block.vertices[t[2]][k] == extreme;
  };
  block.triangles.erase(std::remove_if(block.triangles.begin(), block.triangles.end(), on_face),
                        block.triangles.end());
  // The corners in turn about the face's centre.
  Vec3 centre = Vec3::Zero();
  for (Index v : corners) centre += block.vertices[v] / 4.0;
  const auto turn = [&](Index v) {
    const std::array<double, 2> q = in_plane(block.vertices[v] - centre, k);
    return std::atan2(q[1], q[0]);
  };
  std::sort(corners.begin(), corners.end(), [&](Index a, Index b) { return turn(a) < turn(b); });
  Copier copy{faces.part, block};
  for (std::size_t t = 0; t < faces.part.triangles.size(); ++t) {
    const Triangle& tri = faces.part.triangles[t];
    if (faces.pour[t] && !with_part) block.triangles.push_back({copy(tri[0]), copy(tri[1]), copy(tri[2])});
    if (!faces.pour[t] && with_part) copy.flipped(tri);
  }
  const std::optional<std::vector<Index>> hole = pour_loop(faces, copy);
  return hole && fill_region(block, corners, {*hole}, k, opening.sign);
}

// A triangle of `soup` turned so that its normal has a positive component along `outward`.
void facet(TriangleSoup& soup, Index a, Index b, Index c, const Vec3& outward) {
  const Vec3 n = (soup.vertices[b] - soup.vertices[a]).cross(soup.vertices[c] - soup.vertices[a]);
  if (n.dot(outward) < 0.0) std::swap(b, c);
  soup.triangles.push_back({a, b, c});
}

// The planar quadrilateral a b c d (in turn) as two triangles facing `outward`.
void quad(TriangleSoup& soup, Index a, Index b, Index c, Index d, const Vec3& outward) {
  facet(soup, a, b, c, outward);
  facet(soup, a, c, d, outward);
}

// The frame of a lid over the back of a part pulled along `pull` out of the
// case lo..hi open across `opening`, the part's far face at `far`; its sides
// the split plane's two halves until set_side() says otherwise.
LidFrame lid_frame(const Vec3& lo, const Vec3& hi, const Axis& opening, const Axis& pull, double far,
                   double w) {
  LidFrame f;
  f.k = opening.k;
  f.d = axis_vector(pull);
  f.across = f.d.cross(axis_vector({f.k, 1}));
  const int a = 3 - f.k - pull.k;
  const double sa = f.across[a], sq = f.d[pull.k];
  f.umin = std::min(sa * lo[a], sa * hi[a]);
  f.umax = std::max(sa * lo[a], sa * hi[a]);
  f.vmin = std::min(sq * lo[pull.k], sq * hi[pull.k]);
  f.vmax = std::max(sq * lo[pull.k], sq * hi[pull.k]);
  f.far = far;
  f.extreme = opening.sign > 0 ? hi[f.k] : lo[f.k];
  f.to = f.extreme + opening.sign * w;
  f.floor_at = opening.sign > 0 ? lo[f.k] : hi[f.k];
  for (int s = 0; s < 2; ++s) f.exit[s] = {s == 0 ? f.umax : f.umin, 0.0};
  return f;
}

// Sets side s of the lid to the ray from the axis through p (the split plane's
// half when `split`), and its exit from the box: the coordinate of the wall it
// leaves through exact, the other rounded.
void set_side(LidFrame& f, int s, const Vec3& p, bool split) {
  f.split[s] = split;
  if (split) {
    f.ray[s] = {s == 0 ? 1.0 : -1.0, 0.0};
    f.exit[s] = {s == 0 ? f.umax : f.umin, 0.0};
    return;
  }
  const LidFrame::P2 q = f.of(p);
  const double n = std::hypot(q[0], q[1]);
  const LidFrame::P2 r{q[0] / n, q[1] / n};
  f.ray[s] = r;
  const double tu = r[0] > 0.0 ? f.umax / r[0] : r[0] < 0.0 ? f.umin / r[0] : HUGE_VAL;
  const double tv = r[1] > 0.0 ? f.vmax / r[1] : r[1] < 0.0 ? f.vmin / r[1] : HUGE_VAL;
  f.exit[s] = tu <= tv ? LidFrame::P2{r[0] > 0.0 ? f.umax : f.umin, tu * r[1]}
                       : LidFrame::P2{tv * r[0], r[1] > 0.0 ? f.vmax : f.vmin};
}

// Adds a point to `soup` once, by position.
struct Points {
  TriangleSoup& soup;
  std::map<std::array<double, 3>, Index> made;
  Index operator()(const Vec3& p) {
    const auto [it, added] = made.emplace(std::array<double, 3>{p.x(), p.y(), p.z()}, 0);
    if (added) it->second = add_vertex(soup, p);
    return it->second;
  }
};

// The wall of the box of `f` between its outline's points a and b, from z0 to z1 along k.
void wall(TriangleSoup& soup, Points& point, const LidFrame& f, const LidFrame::P2& a, const LidFrame::P2& b,
          double z0, double z1) {
  quad(soup, point(f.at(a, z0)), point(f.at(b, z0)), point(f.at(b, z1)), point(f.at(a, z1)),
       f.wall_normal(a, b));
}

// The points of `f`'s outline points `ring` at z along k, as `point` adds them.
std::vector<Index> at_level(Points& point, const LidFrame& f, const std::vector<LidFrame::P2>& ring,
                            double z) {
  std::vector<Index> out;
  out.reserve(ring.size());
  for (const LidFrame::P2& p : ring) out.push_back(point(f.at(p, z)));
  return out;
}

// The case's box for a lid (LidFrame), open through the part's pour face:
// its walls split at the lid's exits and at the far face's plane, its floor
// (across k, away from the opening), and its face across the opening less
// the pour face, with the pour face's own triangles. None when that face
// cannot be filled without adding a point.
std::optional<TriangleSoup> lidded_block(const LidFrame& f, const Faces& faces, int opening_sign) {
  TriangleSoup soup;
  Points point{soup, {}};
  const std::vector<LidFrame::P2> ring = f.outline();
  const double zs[2][2] = {{std::min(f.floor_at, f.far), std::max(f.floor_at, f.far)},
                           {std::min(f.far, f.extreme), std::max(f.far, f.extreme)}};
  for (std::size_t i = 0; i < ring.size(); ++i) {
    for (const auto& z : zs) wall(soup, point, f, ring[i], ring[(i + 1) % ring.size()], z[0], z[1]);
  }
  if (!fill_polygon(soup, at_level(point, f, ring, f.floor_at), f.k, -opening_sign)) return std::nullopt;
  Copier copy{faces.part, soup};
  for (std::size_t t = 0; t < faces.part.triangles.size(); ++t) {
    if (!faces.pour[t]) continue;
    const Triangle& tri = faces.part.triangles[t];
    soup.triangles.push_back({copy(tri[0]), copy(tri[1]), copy(tri[2])});
  }
  std::optional<std::vector<Index>> hole = pour_loop(faces, copy);
  if (!hole || !fill_region(soup, at_level(point, f, ring, f.extreme), {*hole}, f.k, opening_sign)) {
    return std::nullopt;
  }
  return soup;
}

// Whether p lies on the plane of one of `given` (split faces through the
// axis, whose points were rounded from their angle: within 1e-9 relative).
bool on_given(const std::vector<CaseFace>& given, const Vec3& p) {
  return std::any_of(given.begin(), given.end(), [&](const CaseFace& f) {
    return std::abs((p - f.point).dot(f.normal)) <= 1e-9 * (1.0 + p.norm() + f.point.norm());
  });
}

// The border of a lid's back (the cut `c`): its edges used once, each
// vertex on the far face, on the opening's face, or on a side (the split
// plane, or a given split face off it); the part's vertex indices, the
// arcs by angle about the axis from `across` toward the pull, the sides by
// height from the far face.
struct BackBorder {
  using Run = std::vector<std::pair<double, Index>>;
  Run far_arc, open_arc;
  std::array<Run, 2> side;  // right, left
};

// The back's border, with the lid's sides set in `f` from it. None, with
// `why`, when the back is not one band from the far face to the opening's
// between two sides.
std::optional<BackBorder> back_border(const TriangleSoup& part, const Cut& c, LidFrame& f,
                                      const std::vector<CaseFace>& given, std::string& why) {
  const int k = f.k;
  std::map<std::pair<Index, Index>, int> uses;
  for (std::size_t t = 0; t < part.triangles.size(); ++t) {
    if (!c.back_triangle(part, t)) continue;
    const Triangle& tri = part.triangles[t];
    for (int e = 0; e < 3; ++e) {
      const Index u = tri[e], v = tri[(e + 1) % 3];
      ++uses[{std::min(u, v), std::max(u, v)}];
    }
  }
  const auto angle = [&](const Vec3& p) {
    const LidFrame::P2 q = f.of(p);
    return std::atan2(q[1], q[0]);
  };
  BackBorder b;
  std::array<int, 2> splits{0, 0};
  std::set<Index> seen;
  const double sign = f.extreme > f.far ? 1.0 : -1.0;
  for (const auto& [edge, n] : uses) {
    if (n != 1) continue;
    for (const Index v : {edge.first, edge.second}) {
      if (!seen.insert(v).second) continue;
      const Vec3& p = part.vertices[v];
      const bool split = exact_side(p, c.o, c.d) == 0;
      const bool given_face = !split && on_given(given, p);
      if (p[k] == f.far) b.far_arc.emplace_back(angle(p), v);
      if (p[k] == f.extreme) b.open_arc.emplace_back(angle(p), v);
      if (split || given_face) {
        const int s = split ? (f.of(p)[0] > 0.0 ? 0 : 1) : (angle(p) < 0.5 * M_PI ? 0 : 1);
        b.side[s].emplace_back(sign * (p[k] - f.far), v);
        splits[s] += split ? 1 : 0;
      }
      if (p[k] != f.far && p[k] != f.extreme && !split && !given_face) {
        why = fmt::format("its back's edge at {} lies off its split faces and flat faces", point_text(p));
        return std::nullopt;
      }
    }
  }
  for (BackBorder::Run* run : {&b.far_arc, &b.open_arc, &b.side[0], &b.side[1]}) {
    std::sort(run->begin(), run->end());
  }
  for (int s = 0; s < 2; ++s) {
    const std::size_t n = b.side[s].size();
    if (n < 2 || (splits[s] != 0 && static_cast<std::size_t>(splits[s]) != n)) {
      why = "its back is not one band between two sides, each on its split plane or on a split face";
      return std::nullopt;
    }
    set_side(f, s, part.vertices[b.side[s].front().second], splits[s] != 0);
  }
  if (b.far_arc.size() < 2 || b.open_arc.size() < 2 ||
      f.outside(part.vertices[b.side[1].front().second], 0) > 0.0) {
    why = "its back is not one band between two sides";
    return std::nullopt;
  }
  return b;
}

// The mesh of a lid's region (the cut `c`, its frame `f`, its back's
// border `b`): what lies in the case's box between its two sides, from the
// part's far face on (and beyond the opening, to f.to), outside the part's
// back: the back's own triangles turned inside out, walls straight on from
// its edge on the opening's face, each side's strip from the back out to its
// exit, the caps and the box's walls (split as the box's are, so that they
// share triangles). `seams`: the strips' triangles, by index.
std::optional<TriangleSoup> lid_region(const TriangleSoup& part, const Cut& c, const LidFrame& f,
                                       const BackBorder& b, std::vector<std::size_t>& seams,
                                       std::string& why) {
  const int k = f.k;
  TriangleSoup soup;
  Copier copy{part, soup};
  for (std::size_t t = 0; t < part.triangles.size(); ++t) {
    if (c.back_triangle(part, t)) copy.flipped(part.triangles[t]);
  }
  Points point{soup, {}};
  for (Index v = 0; v < soup.vertices.size(); ++v) {
    const Vec3& p = soup.vertices[v];
    point.made.emplace(std::array<double, 3>{p.x(), p.y(), p.z()}, v);
  }
  // The box's walls between the sides' exits, from the far face to the opening and on beyond it.
  const std::vector<LidFrame::P2> path = f.lid_path();
  const double levels[2][2] = {{std::min(f.far, f.extreme), std::max(f.far, f.extreme)},
                               {std::min(f.extreme, f.to), std::max(f.extreme, f.to)}};
  for (const auto& z : levels) {
    for (std::size_t i = 0; i + 1 < path.size(); ++i) wall(soup, point, f, path[i], path[i + 1], z[0], z[1]);
  }
  // The walls beyond the opening's face: the back's edge there moved on to `to`.
  std::vector<Index> lifted;
  for (const auto& [turn, v] : b.open_arc) {
    Vec3 p = part.vertices[v];
    p[k] = f.to;
    lifted.push_back(point(p));
  }
  for (std::size_t n = 0; n + 1 < b.open_arc.size(); ++n) {
    Vec3 inward = -0.5 * (part.vertices[b.open_arc[n].second] + part.vertices[b.open_arc[n + 1].second]);
    inward[k] = 0.0;
    quad(soup, copy(b.open_arc[n].second), copy(b.open_arc[n + 1].second), lifted[n + 1], lifted[n], inward);
  }
  // The caps: the box's section between the sides less the back's.
  std::vector<Index> low = at_level(point, f, path, f.far), high = at_level(point, f, path, f.to);
  for (auto it = b.far_arc.rbegin(); it != b.far_arc.rend(); ++it) low.push_back(copy(it->second));
  for (auto it = lifted.rbegin(); it != lifted.rend(); ++it) high.push_back(*it);
  const int up = f.to > f.far ? 1 : -1;
  if (!fill_polygon(soup, low, k, -up) || !fill_polygon(soup, high, k, up)) {
    why = "its lid's region could not be closed";
    return std::nullopt;
  }
  // The sides' strips: from the back's side edge out to the exit, facing out of the wedge.
  for (int s = 0; s < 2; ++s) {
    std::vector<Index> strip{point(f.at(f.exit[s], f.far)), point(f.at(f.exit[s], f.extreme)),
                             point(f.at(f.exit[s], f.to)), s == 0 ? lifted.front() : lifted.back()};
    for (auto it = b.side[s].rbegin(); it != b.side[s].rend(); ++it) strip.push_back(copy(it->second));
    const Vec3 out = f.side_normal(s);
    int axis = 0;
    for (int q = 1; q < 3; ++q) {
      if (std::abs(out[q]) > std::abs(out[axis])) axis = q;
    }
    const std::size_t first = soup.triangles.size();
    if (!fill_polygon(soup, strip, axis, out[axis] > 0.0 ? 1 : -1)) {
      why = "its lid's region could not be closed at a side";
      return std::nullopt;
    }
    for (std::size_t t = first; t < soup.triangles.size(); ++t) seams.push_back(t);
  }
  return soup;
}

// The lid over a cylinder block's back of `back` radius (about the axis k
// of the opening, through the origin): what lies in the case on the pull's
// side of the split plane through the axis, from the part's far face (across
// the opening) on, between the lid's two sides (the split plane, or the
// planes of `given` split faces off it, beyond the back), outside the back.
// For the exact case, the region's box less the prism over a polygon
// between the part's inside (every point of it but its back's, the sockets'
// and the cavity's) and its back, out along the sides. None, with `why`,
// when a face of the part reaches from its inside to its back off its split
// faces, the far face and the opening (the lid would then cut it), or a
// side's seam faces the way the lid comes off.
std::optional<Cut> lid_cut(const TriangleSoup& part, const Faces& faces, const Axis& axis,
                           const Axis& opening, double back, const std::vector<CaseFace>& given,
                           const BoundingBox& box, const Vec3& hi, const Vec3& lo, double w,
                           std::string& why) {
  const int k = opening.k;
  const double far = opening.sign > 0 ? box.lo[k] : box.hi[k];
  const double to = opening.sign > 0 ? hi[k] + w : lo[k] - w;
  Cut c;
  c.lid = true;
  c.k = k;
  c.back = back;
  c.what = "its curved back";
  c.d = axis_vector(axis);
  c.o = Vec3::Zero();
  c.o[k] = far;
  double inside = 0.0;
  for (const Vec3& p : part.vertices) {
    const double r = radial(p, k);
    if (r > back * (1.0 + 1e-9)) {
      why =
          fmt::format("its point {} lies outside the block's cylinder of radius {:.6g}", point_text(p), back);
      return std::nullopt;
    }
    if (r < back * (1.0 - 1e-9)) inside = std::max(inside, r);
  }
  for (std::size_t t = 0; t < part.triangles.size(); ++t) {
    const Triangle& tri = part.triangles[t];
    int on_back = 0;  // its corners on the block's cylinder
    bool split = true, far_face = true, side = true;
    for (int e = 0; e < 3; ++e) {
      const Vec3& p = part.vertices[tri[e]];
      if (radial(p, k) >= back * (1.0 - 1e-9)) ++on_back;
      split = split && exact_side(p, c.o, c.d) == 0;
      far_face = far_face && p[k] == far;
      side = side && on_given(given, p);
    }
    if (on_back > 0 && on_back < 3 && !split && !far_face && !side && !faces.pour[t]) {
      why = fmt::format(
          "its face at {} reaches from its inside to its back off its split faces and its flat "
          "faces, where no lid can be cut",
          where(part, t, {}));
      return std::nullopt;
    }
  }
  // The polygon: its corners on the circle halfway between the inside and
  // the back, a step at most a half turn over `sides`, its sides beyond the
  // inside by at least half that gap.
  const double middle = 0.5 * (inside + back);
  std::size_t sides = 8;
  while (middle * std::cos(M_PI / (2.0 * static_cast<double>(sides))) - inside <= 0.5 * (middle - inside)) {
    sides *= 2;
    if (sides > 4096 || !(middle > inside)) {
      why = "its back is too close to its inside for a lid";
      return std::nullopt;
    }
  }
  c.inside = inside;
  c.inner = middle * std::cos(M_PI / (2.0 * static_cast<double>(sides)));
  LidFrame f = lid_frame(lo, hi, opening, axis, far, w);
  const std::optional<BackBorder> border = back_border(part, c, f, given, why);
  if (!border) return std::nullopt;
  // The region's mesh: outside the part's own back, so that it cuts the
  // case where the back bounds it and adds no point on the part's faces.
  std::vector<std::size_t> seams;
  std::optional<TriangleSoup> region = lid_region(part, c, f, *border, seams, why);
  if (!region) return std::nullopt;
  const ValidationReport checked = validate(*region);
  if (!checked.valid()) {
    std::string defects;
    for (const std::string& d : describe_defects(checked)) defects += (defects.empty() ? "" : "; ") + d;
    why = "its lid's region is not a valid solid: " + defects;
    return std::nullopt;
  }
  // Its seams with the pieces beyond its sides face away from its way off, exactly.
  for (const std::size_t t : seams) {
    const Triangle& tri = region->triangles[t];
    // The region's triangles face out of it: into the piece beyond, which the lid leaves along d.
    if (exact_facing(region->vertices[tri[0]], region->vertices[tri[1]], region->vertices[tri[2]], c.d) > 0) {
      why = fmt::format("its lid's seam at {} faces the way the lid comes off",
                        point_text(region->vertices[tri[0]]));
      return std::nullopt;
    }
  }
  c.regions.push_back(std::move(*region));
  c.frame = f;
  c.middle = middle;
  c.steps = sides;
  // For the exact case: the box of the region (beyond the split plane) less the prism over the polygon,
  // out along a side off the split plane past the region's box, and round behind the axis.
  const Vec3 ek = axis_vector({k, 1}), across = f.across;
  const double reach = snapped(4.0 * (hi - lo).norm() + back, kLengthBits);
  const auto at = [&](double a, double b) { return Vec3(c.o + a * across + b * c.d); };
  const double from = f.split[0] ? 0.0 : std::atan2(f.ray[0][1], f.ray[0][0]);
  const double until = f.split[1] ? M_PI : std::atan2(f.ray[1][1], f.ray[1][0]);
  const auto steps =
      static_cast<std::size_t>(std::ceil((until - from) / (M_PI / static_cast<double>(sides)) - 1e-9));
  if (f.split[0]) {
    c.hollow.push_back(at(middle, -w));
    c.hollow.push_back(at(middle, 0.0));
  } else {
    c.hollow.push_back(at(2.0 * reach * f.ray[0][0], 2.0 * reach * f.ray[0][1]));
    c.hollow.push_back(at(middle * f.ray[0][0], middle * f.ray[0][1]));
  }
  for (std::size_t i = 1; i < steps; ++i) {
    const double angle = from + (until - from) * static_cast<double>(i) / static_cast<double>(steps);
    c.hollow.push_back(at(middle * std::cos(angle), middle * std::sin(angle)));
  }
  if (f.split[1]) {
    c.hollow.push_back(at(-middle, 0.0));
    c.hollow.push_back(at(-middle, -w));
  } else {
    c.hollow.push_back(at(middle * f.ray[1][0], middle * f.ray[1][1]));
    c.hollow.push_back(at(2.0 * reach * f.ray[1][0], 2.0 * reach * f.ray[1][1]));
  }
  if (!f.split[0] || !f.split[1]) {
    // Round behind the axis at twice the reach, a step at most a sixth of a turn.
    const double behind = 2.0 * M_PI + from - until;
    const auto around = static_cast<std::size_t>(std::ceil(behind / (M_PI / 3.0)));
    for (std::size_t i = 1; i < around; ++i) {
      const double angle = until + behind * static_cast<double>(i) / static_cast<double>(around);
      c.hollow.push_back(at(2.0 * reach * std::cos(angle), 2.0 * reach * std::sin(angle)));
    }
  }
  // The region's box: beyond the split plane, well past the case.
  c.corner = at(-reach, 0.0);
  c.corner[k] = std::min(far, to);
  c.ru = std::abs(to - far) * ek;
  c.rv = 2.0 * reach * across;
  c.rd = reach * c.d;
  for (Vec3& p : c.hollow) p[k] = far - opening.sign * w;
  c.hollow_along = (to - far + 2.0 * opening.sign * w) * ek;
  // Its pins lie across the pull, in the plane of the pin's rings.
  c.u = ek;
  c.v = across;
  return c;
}

// The prism over the convex polygon `ring` swept along `along` (across
// it), facing out.
TriangleSoup prism_over(const std::vector<Vec3>& ring, const Vec3& along) {
  TriangleSoup s;
  const auto n = static_cast<Index>(ring.size());
  s.vertices = ring;
  for (Index m = 0; m < n; ++m) s.vertices.push_back(ring[m] + along);
  for (Index m = 0; m < n; ++m) {
    const Index l = (m + 1) % n;
    s.triangles.push_back({m, l, n + m});
    s.triangles.push_back({l, n + l, n + m});
  }
  for (Index m = 1; m + 1 < n; ++m) {
    s.triangles.push_back({0, m + 1, m});
    s.triangles.push_back({n, n + m, n + m + 1});
  }
  if (signed_volume(s) < 0.0) {
    for (Triangle& t : s.triangles) std::swap(t[1], t[2]);
  }
  return s;
}

// How far behind a given face (a plane through `point` across `normal`)
// its piece's seam lies: `from` at least, and no point of the part within
// `gap` of it. A seam passing a hair from one of the part's points cuts
// slivers beside it that fold when a file rounds the points.
double seam_depth(const TriangleSoup& part, const Vec3& point, const Vec3& normal, double from, double gap) {
  std::vector<double> behind;
  behind.reserve(part.vertices.size());
  for (const Vec3& p : part.vertices) behind.push_back((point - p).dot(normal));
  std::sort(behind.begin(), behind.end());
  double depth = from;
  for (auto it = std::lower_bound(behind.begin(), behind.end(), depth - gap);
       it != behind.end() && *it < depth + gap; ++it) {
    depth = *it + gap;
  }
  return depth;
}

// A sector whose floor lies on the part's far face (at `far`): the edges
// fanning out from the axis across its floor cut the part's edges there,
// so they pass its points there by `gap` at least (a point a hair from one
// of the part's would fold when a file rounds them). Its chords are more
// than the fewest if that takes them clear; the inscribed circle stays.
void fan_clear(Sector& sector, const TriangleSoup& part, double far, double gap) {
  std::vector<std::pair<double, double>> on_floor;  // angle from `from`, distance from the axis
  for (const Vec3& p : part.vertices) {
    const double r = radial(p, kAxis);
    if (p.z() != far || !(r > 0.0) || r > sector.radius) continue;
    on_floor.emplace_back(sector.turn(p) - sector.from, r);
  }
  const auto clear = [&](std::size_t n) {
    const double step = (sector.to - sector.from) / static_cast<double>(n);
    return std::all_of(on_floor.begin(), on_floor.end(), [&](const std::pair<double, double>& q) {
      const double i = std::round(q.first / step);
      return i <= 0.0 || i >= static_cast<double>(n) || q.second * std::abs(q.first - i * step) >= gap;
    });
  };
  for (std::size_t n = sector.fewest(); n < sector.fewest() + 64; ++n) {
    if (clear(n)) {
      sector.chords = n;
      return;
    }
  }
}

// The prisms that take the vessel's slice between a cylinder part's split
// faces (the lid `lid` over its back; from angle a0 to a1 about the axis, up
// to `top`), so that the part lifts off the floor through the opening.
// Under a part with a bottom across the axis: one, of the lid's polygon's
// radius, from halfway up that bottom below the vessel (its floor lies in
// the part and marks nothing on the case's floor). Over a base part (the
// part's far face a ring round the cavity's edge): from that face up; where
// the base keys' sockets are in it, a narrower one up past their tops
// (round the cavity there, inside the sockets' rims: their bumps stay on
// the floor, which the part lifts off) under the full one.
std::optional<std::vector<Sector>> core_sectors(const TriangleSoup& part, const std::vector<CaseFace>& given,
                                                const Cut& lid, double a0, double a1, double top, double gap,
                                                std::string& why) {
  const LidFrame& f = lid.frame;
  const auto off_back = [&](const Vec3& p) { return radial(p, kAxis) < lid.back * (1.0 - 1e-9); };
  Sector full;
  full.radius = lid.middle;
  full.from = a0;
  full.to = a1;
  full.steps = lid.steps;
  full.top = top;
  double edge = std::numeric_limits<double>::infinity();  // the far face's least distance from the axis
  for (const Vec3& p : part.vertices) {
    if (p.z() == f.far) edge = std::min(edge, radial(p, kAxis));
  }
  if (!(edge > 1e-9 * lid.back)) {
    double above = f.to;
    for (const Vec3& p : part.vertices) {
      if (p.z() != f.far && radial(p, kAxis) < lid.inner) above = std::min(above, p.z());
    }
    full.floor = 0.5 * (f.far + above);
    return std::vector<Sector>{full};
  }
  full.floor = f.far;
  // The sockets' rims: the far face's points off the split faces between the cavity's edge and the back.
  double rim_lo = std::numeric_limits<double>::infinity(), rim_hi = 0.0;
  for (const Vec3& p : part.vertices) {
    const double r = radial(p, kAxis);
    if (p.z() == f.far && r > edge * (1.0 + 1e-9) && off_back(p) && !on_given(given, p)) {
      rim_lo = std::min(rim_lo, r);
      rim_hi = std::max(rim_hi, r);
    }
  }
  if (!(rim_hi > 0.0)) {
    fan_clear(full, part, f.far, gap);
    return std::vector<Sector>{full};
  }
  // The sockets' tops (no deeper than their rims are wide), the next point
  // of the part above them, and the narrower prism's top between the two.
  double tops = f.far, next = f.to;
  for (const Vec3& p : part.vertices) {
    const double r = radial(p, kAxis);
    if (p.z() > f.far && p.z() <= f.far + (rim_hi - rim_lo) && r >= rim_lo * (1.0 - 1e-9) &&
        r <= rim_hi * (1.0 + 1e-9) && !on_given(given, p)) {
      tops = std::max(tops, p.z());
    }
  }
  for (const Vec3& p : part.vertices) {
    if (p.z() > tops && off_back(p)) next = std::min(next, p.z());
  }
  const double between = 0.5 * (tops + next);
  // The cavity's widest up to the first of its points at or above that top
  // (its faces there run between its points at and below it).
  double wall_top = f.to;
  for (const Vec3& p : part.vertices) {
    if (p.z() >= between && radial(p, kAxis) < rim_lo && !on_given(given, p)) {
      wall_top = std::min(wall_top, p.z());
    }
  }
  double widest = edge;
  for (const Vec3& p : part.vertices) {
    const double r = radial(p, kAxis);
    if (on_given(given, p) || p.z() > wall_top || (p.z() <= tops && r >= rim_lo * (1.0 - 1e-9)) ||
        !off_back(p)) {
      continue;
    }
    widest = std::max(widest, r);
  }
  if (!(widest < rim_lo)) {
    why = fmt::format(
        "the vessel's wall reaches {:.6g} from the axis below z = {:.6g}, past the rims of the base keys' "
        "sockets at {:.6g}: no prism takes the vessel's slice there and leaves the keys' bumps on the floor",
        widest, wall_top, rim_lo);
    return std::nullopt;
  }
  Sector narrow = full;
  narrow.radius = 0.5 * (widest + rim_lo);
  narrow.top = between;
  while (narrow.inscribed() - widest <= 0.5 * (narrow.radius - widest)) {
    narrow.steps *= 2;
    if (narrow.steps > 4096) {
      why = "the vessel's wall comes too close to the base keys' sockets for a prism between them";
      return std::nullopt;
    }
  }
  fan_clear(narrow, part, f.far, gap);
  full.floor = between;
  return std::vector<Sector>{narrow, full};
}

// A lid over a cylinder block's back: the block's radius, and the way the
// lid comes off (across the split plane through the axis it is cut by).
struct Lid {
  double radius = 0.0;
  Axis way;
  // Whether the last piece beyond a slanted split face also takes the core
  // (what lies between the split faces near the axis: the vessel's slice),
  // so that the part then lifts off the floor through the opening.
  bool core = false;
};

// The case of `part` pulled along `axis` in several pieces: the main piece
// and, taken off before it in order, one per side of the part's box (with
// the sockets behind it), the lid over a cylinder block's back (`lid`) and
// one per given face that takes a face of the part the pull would catch on
// (under a lid, these before the sides of the part's box); each with two pins
// in holes of the main piece or of a piece taken off after it. The case is
// open across `opening` (the pull, but for a lidded case pulled across it),
// on a face of the part that covers its outline there when `rectangle`.
Attempt carved(const TriangleSoup& part, const std::string& name, const Axis& axis, const Axis& opening,
               bool rectangle, std::optional<Lid> lid, const CaseOptions& options,
               const std::vector<CaseFace>& given,
               const std::function<std::string(const Vec3&)>& what_is_at) {
  const int k = opening.k;
  const BoundingBox box = bounding_box(part.vertices);
  const double extreme = opening.sign > 0 ? box.hi[k] : box.lo[k];
  const std::string dir = axis_name(axis), open_dir = axis_name(opening);
  const auto at = [&](std::size_t t) { return where(part, t, what_is_at); };
  std::string why;
  const std::optional<Pour> analysed = analyse(part, opening, axis, rectangle, at, why);
  if (!analysed) return {std::nullopt, why};
  const Faces& faces = analysed->faces;
  const std::vector<std::size_t>& blocking = analysed->blocking;
  const double w = options.wall;
  Vec3 lo = box.lo - Vec3::Constant(w), hi = box.hi + Vec3::Constant(w);
  (opening.sign > 0 ? hi : lo)[k] = extreme;
  if (4.0 * std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff()) >= kLargest) {
    return {std::nullopt, "its case lies too far from the origin to be carved exactly"};
  }

  // The cuts: the sides of the part's box whose plate takes a face that
  // would catch, then the given faces that do.
  std::vector<Cut> cuts;
  const auto takes_blocking = [&](const std::function<bool(std::size_t)>& inside) {
    return std::any_of(blocking.begin(), blocking.end(), inside);
  };
  for (int q = 0; q < 3; ++q) {
    for (int s : {-1, 1}) {
      if (q == axis.k || (q == k && s == opening.sign)) continue;
      std::optional<PlateFace> p = plate_members(faces, box, q, s);
      if (!p || !takes_blocking([&](std::size_t t) { return bool(p->member[t]); })) continue;
      Cut c;
      c.what = "its face across " + axis_name({q, s});
      c.d = axis_vector({q, s});
      c.o = Vec3::Zero();
      c.o[q] = p->e;
      c.u = Vec3::Zero();
      c.u[(q + 1) % 3] = 1.0;
      c.v = Vec3::Zero();
      c.v[(q + 2) % 3] = s;
      c.features = p->features;
      c.axis = std::move(p);
      cuts.push_back(std::move(c));
    }
  }
  // Which side of a cut's plane each vertex lies on, exactly.
  const auto sides_of = [&](const Cut& c, const Triangle& tri) {
    std::array<int, 3> out{};
    for (int e = 0; e < 3; ++e) out[e] = exact_side(part.vertices[tri[e]], c.o, c.d);
    return out;
  };
  // Whether the part's triangle t lies in a core's prism (its faces round the vessel's slice).
  const auto cored = [&](const Cut& c, std::size_t t) {
    const Triangle& tri = part.triangles[t];
    return !c.core.empty() &&
           std::all_of(tri.begin(), tri.end(), [&](Index v) { return c.in_core(part.vertices[v], 0.0); });
  };
  const auto inside = [&](const Cut& c, std::size_t t) {
    if (c.lid) return c.back_triangle(part, t);
    if (c.axis) return bool(c.axis->member[t]);
    const std::array<int, 3> side = sides_of(c, part.triangles[t]);
    return (*std::min_element(side.begin(), side.end()) >= 0 &&
            *std::max_element(side.begin(), side.end()) > 0) ||
           cored(c, t);
  };
  const auto touches = [&](const Cut& c, std::size_t t) {
    if (c.lid) return c.back_triangle(part, t);
    if (c.axis) return bool(c.axis->member[t]);
    const std::array<int, 3> side = sides_of(c, part.triangles[t]);
    return *std::max_element(side.begin(), side.end()) > 0 || cored(c, t);
  };
  if (lid) {
    std::optional<Cut> c = lid_cut(part, faces, lid->way, opening, lid->radius, given, box, hi, lo, w, why);
    if (!c) return {std::nullopt, why};
    cuts.push_back(std::move(*c));
  }
  // The seams of pieces beyond two faces mirrored about a line of the
  // part's edges (the middle side's split faces, about its bisector) would
  // meet on that line: each seam after the first lies deeper by a step, so
  // that they meet off it.
  std::size_t given_seams = 0;
  for (const CaseFace& f : given) {
    // Vertical planes across no axis; the sides of the box are found above.
    if (f.normal.z() != 0.0 || f.normal.x() == 0.0 || f.normal.y() == 0.0) continue;
    Cut c;
    c.what = f.name;
    c.d = Vec3(snapped(f.normal.x(), kDirectionBits), snapped(f.normal.y(), kDirectionBits), 0.0);
    const double step = static_cast<double>(given_seams++) * w / 250.0;
    c.o = snapped(
        f.point - seam_depth(part, f.point, f.normal, f.depth + w / 4.0 + step, w / 1000.0) * f.normal,
        kPointBits);
    c.u = Vec3(-c.d.y(), c.d.x(), 0.0);
    c.v = Vec3(0.0, 0.0, 1.0);
    c.features = f.features;
    // Under a lid that leaves the vessel's slice to them, every such face has its piece.
    if (takes_blocking([&](std::size_t t) { return inside(c, t); }) || (lid && lid->core)) {
      cuts.push_back(std::move(c));
    }
  }
  // Under a lid, the pieces beyond slanted split faces come off before the
  // plates on the part's box (the plate under it, over a base part): they
  // keep the floor beyond their seams, where their pins stand.
  if (lid && std::any_of(cuts.begin(), cuts.end(), [](const Cut& c) { return !c.axis && !c.lid; })) {
    std::stable_partition(cuts.begin(), cuts.end(), [](const Cut& c) { return !c.axis; });
  }
  if (lid && lid->core) {
    // The core goes with the last piece beyond a slanted split face: its
    // prism over the sector between the lid's sides, 25 degrees more each
    // way, into the pieces beyond them (their half-spaces hold those rays
    // from the axis; its sides cross their seams steeply, leaving no thin
    // sliver), of the lid's polygon's radius, up past the opening.
    constexpr double kOver = 25.0 * M_PI / 180.0;
    const auto first = std::find_if(cuts.begin(), cuts.end(), [](const Cut& c) { return c.lid; });
    const auto last =
        std::find_if(cuts.rbegin(), cuts.rend(), [](const Cut& c) { return !c.lid && !c.axis; });
    if (first == cuts.end() || last == cuts.rend() || k != 2 || opening.sign < 0) {
      return {std::nullopt, "no piece beyond a slanted split face takes the vessel's slice from below"};
    }
    const LidFrame& f = first->frame;
    const auto world = [&](int s) { return Vec3(f.ray[s][0] * f.across + f.ray[s][1] * f.d); };
    const Vec3 from = world(0), until = world(1);
    double a0 = std::atan2(from.y(), from.x()) - kOver, a1 = std::atan2(until.y(), until.x()) + kOver;
    if (a1 < a0) a1 += 2.0 * M_PI;
    std::optional<std::vector<Sector>> core =
        core_sectors(part, given, *first, a0, a1, hi[k] + w, w / 1000.0, why);
    if (!core) return {std::nullopt, why};
    last->core = std::move(*core);
  }
  for (std::size_t t : blocking) {
    if (std::none_of(cuts.begin(), cuts.end(), [&](const Cut& c) { return inside(c, t); })) {
      return {std::nullopt,
              fmt::format("its face at {} faces {} and no piece taken off first would take it", at(t), dir)};
    }
  }

  // The proof: every face of the part a piece touches faces the way that
  // piece comes off or runs along it; every face the main piece touches
  // faces away from the pull or runs along it (the blocking ones all lie
  // inside a piece, so none does).
  std::size_t main_faces = 0;
  for (std::size_t t = 0; t < part.triangles.size(); ++t) {
    if (faces.pour[t]) continue;
    const Triangle& tri = part.triangles[t];
    bool in_one = false;
    for (Cut& c : cuts) {
      // A face inside a piece taken off before has that piece across it.
      if (in_one) break;
      if (!touches(c, t)) continue;
      const int f = exact_facing(part.vertices[tri[0]], part.vertices[tri[1]], part.vertices[tri[2]], c.d);
      if (f < 0) {
        return {std::nullopt,
                fmt::format("its face at {} faces away from the way the piece beyond {} comes off {}: that "
                            "piece would catch on it",
                            at(t), c.what, vector_text(c.d))};
      }
      ++c.touching;
      if (f == 0) ++c.along;
      in_one = in_one || inside(c, t);
    }
    if (!in_one) ++main_faces;
  }

  // The pins: two per piece, in the case's walls (centred in a wall that
  // runs along the piece's way off), where the hole has main piece all
  // round it and the pin's foot is in its own piece.
  const CasePin sized = case_pin(options);
  const double radius = sized.radius, height = sized.height, buried = sized.buried;
  const double hole_radius = sized.hole_radius;
  const std::size_t sides = sized.sides;
  const double margin = case_pin_margin(options);
  const auto in_case = [&](const Vec3& p) {
    return (p.array() >= lo.array() + margin).all() && (p.array() <= hi.array() - margin).all();
  };
  // Whether p lies in the region of c or within the margin of it (a lid's:
  // between its sides, from its far face to its top, beyond its polygon; a
  // piece's with the vessel's slice: in that too).
  const auto beyond = [&](const Cut& c, const Vec3& p) {
    if (!c.lid) return (p - c.o).dot(c.d) / c.d.norm() > -margin || c.in_core(p, -margin);
    return c.frame.outside(p, 0) < margin && c.frame.outside(p, 1) < margin && p[k] > c.corner[k] - margin &&
           p[k] < c.corner[k] + c.ru[k] + margin && radial(p, k) > c.inner - margin;
  };
  // Whether a lid's pin foot at p lies in the lid, clear of its edges (of
  // its sides too at the foot's end's centre, `deep`: a pin across a side's
  // slanted seam lies partly beyond it, in its hole in the piece there).
  const auto in_lid = [&](const Cut& c, const Vec3& p, bool deep) {
    return p[k] >= c.corner[k] + margin && p[k] <= c.corner[k] + c.ru[k] - margin &&
           radial(p, k) >= c.back + margin &&
           (!deep || (c.frame.outside(p, 0) <= -margin && c.frame.outside(p, 1) <= -margin));
  };
  // Whether p lies clear of the part's box: in the case's walls.
  const auto clear_of_part = [&](const Vec3& p) {
    return !((p.array() > box.lo.array() - margin).all() && (p.array() < box.hi.array() + margin).all());
  };
  std::vector<std::vector<TriangleSoup>> pins(cuts.size()), holes(cuts.size()), regions(cuts.size());
  for (std::size_t i = 0; i < cuts.size(); ++i) {
    Cut& c = cuts[i];
    const Vec3 e1 = c.u.normalized(), e2 = c.v.normalized(), n = c.d.normalized();
    // The samples of a cylinder about the axis through p along n, from `from` to `to` along n.
    const auto samples = [&](const Vec3& p, double r, double from, double to) {
      std::vector<Vec3> out;
      for (double along : {from, to}) {
        out.push_back(p + along * n);
        for (int m = 0; m < 16; ++m) {
          const double angle = M_PI * m / 8.0;
          out.push_back(p + along * n + r * (std::cos(angle) * e1 + std::sin(angle) * e2));
        }
      }
      return out;
    };
    // Whether a pin from p fits: its hole in the main piece (or, not
    // `strict`, in pieces taken off after this one: the pin leaves it first),
    // its foot in its own piece.
    const auto fits = [&](const Vec3& p, bool strict) {
      for (const Vec3& q : samples(p, hole_radius + margin, 0.0, -(height + options.clearance + margin))) {
        if (!in_case(q) || !clear_of_part(q)) return false;
        for (std::size_t j = 0; j < (strict ? cuts.size() : i); ++j) {
          if (j != i && beyond(cuts[j], q)) return false;
        }
      }
      const std::vector<Vec3> foot = samples(p, radius + margin, 0.0, buried);
      for (std::size_t m = 0; m < foot.size(); ++m) {
        const Vec3& q = foot[m];
        if (!in_case(q) || !clear_of_part(q) || (c.lid && !in_lid(c, q, m == foot.size() / 2))) return false;
        for (std::size_t j = 0; j < i; ++j) {
          if (beyond(cuts[j], q)) return false;
        }
      }
      return true;
    };
    // Along a line in the middle of each wall that runs along the piece's way
    // off: through its plane (a lid's split plane), or, for a lid, where
    // each side off the split plane crosses that line; and, `across` (when
    // those give no two), in the middle of a wall across the way off of a
    // piece with an upright slanted seam, where the seam crosses it.
    const auto found_where = [&](bool strict, bool across) {
      std::vector<Vec3> found;
      for (int a = 0; a < 3; ++a) {
        for (int sigma : {-1, 1}) {
          if (a == k && sigma == opening.sign) continue;
          Vec3 p0 = c.o;
          p0[a] = sigma > 0 ? box.hi[a] + w / 2.0 : box.lo[a] - w / 2.0;
          std::vector<Vec3> starts;
          Vec3 line = n.cross(axis_vector({a, 1}));
          if (c.d[a] == 0.0) {
            starts.push_back(p0);
            for (int s = 0; c.lid && s < 2; ++s) {
              const double u = p0.dot(c.frame.across), ru = c.frame.ray[s][0];
              if (c.frame.split[s] || !(u * ru > 0.0)) continue;
              starts.push_back(p0 + (u / ru) * c.frame.ray[s][1] * c.frame.d);
            }
          } else if (across && !c.lid && a != k && c.d[k] == 0.0 && c.d[3 - a - k] != 0.0) {
            const int b = 3 - a - k;
            p0[b] = c.o[b] - c.d[a] * (p0[a] - c.o[a]) / c.d[b];
            starts.push_back(p0);
            line = axis_vector({k, 1});
          }
          for (const Vec3& start : starts) {
            double t0 = -std::numeric_limits<double>::infinity(), t1 = -t0;
            for (int b = 0; b < 3; ++b) {
              if (line[b] == 0.0) continue;
              const double ta = (lo[b] - start[b]) / line[b], tb = (hi[b] - start[b]) / line[b];
              t0 = std::max(t0, std::min(ta, tb));
              t1 = std::min(t1, std::max(ta, tb));
            }
            if (!(t0 < t1)) continue;
            for (double fraction : {1.0 / 6.0, 1.0 / 3.0, 0.5, 2.0 / 3.0, 5.0 / 6.0}) {
              const Vec3 p = start + (t0 + fraction * (t1 - t0)) * line;
              if (fits(p, strict)) found.push_back(p);
            }
          }
        }
      }
      return found;
    };
    std::vector<Vec3> found = found_where(true, false);
    if (found.size() < 2) found = found_where(true, true);
    if (found.size() < 2) found = found_where(false, true);
    if (found.size() < 2) {
      return {std::nullopt,
              fmt::format("its case has no room in its walls for the pins of the piece beyond {}", c.what)};
    }
    const auto [best_a, best_b] = farthest_pair(found);
    const double pin_length = snapped(buried + height, kLengthBits);
    const double hole_length = snapped(buried + height + options.clearance, kLengthBits);
    for (std::size_t b : {best_a, best_b}) {
      const Vec3 foot = found[b] + buried * n;
      CasePin pin = sized;
      pin.base = found[b];
      pin.axis = -n;
      c.pins.push_back(pin);
      pins[i].push_back(pin_prism(foot, e1, e2, -c.d, radius, pin_length, sides));
      holes[i].push_back(pin_prism(foot, e1, e2, -c.d, hole_radius, hole_length, sides));
    }
    // The region: beyond the plane, well past the case on every other side.
    const double reach = snapped(4.0 * (hi - lo).norm() + (c.o - lo).norm(), kLengthBits);
    if (c.lid) {
      regions[i] = std::move(c.regions);
    } else if (c.axis) {
      Vec3 rlo = lo - Vec3::Constant(w), rhi = hi + Vec3::Constant(w);
      const int q = c.axis->q;
      (c.axis->s > 0 ? rlo : rhi)[q] = c.axis->e;
      regions[i].push_back(block_of(rlo, Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ(),
                                    {0.0, rhi.x() - rlo.x()}, {0.0, rhi.y() - rlo.y()},
                                    {0.0, rhi.z() - rlo.z()}));
      // As a box with edges along the axes, right-handed (the axes in cyclic order).
      const Vec3 size = rhi - rlo;
      c.corner = rlo;
      c.ru = Vec3::Zero();
      c.rv = Vec3::Zero();
      c.rd = Vec3::Zero();
      c.rd[q] = size[q];
      c.ru[(q + 1) % 3] = size[(q + 1) % 3];
      c.rv[(q + 2) % 3] = size[(q + 2) % 3];
      if (c.features > 0) {
        std::optional<TriangleSoup> fills = socket_fills(faces, *c.axis);
        if (!fills) return {std::nullopt, fmt::format("the sockets behind {} do not bound regions", c.what)};
        regions[i].push_back(std::move(*fills));
      }
    } else {
      regions[i].push_back(block_of(c.o, c.u, c.v, c.d, {-reach, reach}, {-reach, reach}, {0.0, reach}));
      for (const Sector& sector : c.core) {
        const CasePrism p = sector.prism();
        regions[i].push_back(prism_over(p.ring, p.along));
      }
      c.corner = c.o - reach * c.u - reach * c.v;
      c.ru = 2.0 * reach * c.u;
      c.rv = 2.0 * reach * c.v;
      c.rd = reach * c.d;
    }
  }

  TriangleSoup block = block_of(lo, Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ(), {0.0, hi.x() - lo.x()},
                                {0.0, hi.y() - lo.y()}, {0.0, hi.z() - lo.z()});
  const auto no_rim = [&] {
    return Attempt{std::nullopt, fmt::format("its face across {} does not bound a simple region", open_dir)};
  };
  if (lid) {
    const auto c = std::find_if(cuts.begin(), cuts.end(), [](const Cut& x) { return x.lid; });
    std::optional<TriangleSoup> lidded = lidded_block(c->frame, faces, opening.sign);
    if (!lidded) return no_rim();
    block = std::move(*lidded);
  } else if (!rectangle && !open_through(block, opening, faces, cuts.empty())) {
    return no_rim();
  }
  // Nothing to cut: the case is the block less the part, built face by face.
  std::optional<std::vector<TriangleSoup>> pieces =
      cuts.empty() && !rectangle ? std::optional<std::vector<TriangleSoup>>({std::move(block)})
                                 : carve_pieces(block, part, regions, pins, holes, &why);
  if (!pieces) return {std::nullopt, "carving its case failed: " + why};
  const bool by_booleans = !cuts.empty() || rectangle;
  for (std::size_t i = 0; i < pieces->size(); ++i) {
    std::optional<ValidationReport> collapsed;
    if (by_booleans) collapsed = without_hairs((*pieces)[i], options.tolerance);
    const ValidationReport report = collapsed ? std::move(*collapsed) : validate((*pieces)[i]);
    if (!report.valid()) {
      std::string defects;
      for (const std::string& d : describe_defects(report)) defects += (defects.empty() ? "" : "; ") + d;
      return {std::nullopt,
              fmt::format("its carved case's {} is not a valid solid: {}",
                          i == 0 ? std::string("main piece") : "piece beyond " + cuts[i - 1].what, defects)};
    }
  }

  CastingCase out;
  out.carved = !cuts.empty() || rectangle;
  out.soup = std::move(pieces->front());
  out.pull = axis_vector(axis);
  out.opening = axis_vector(opening);
  out.lo = lo;
  out.hi = hi;
  const std::array<double, 2> plo = in_plane(box.lo, k), phi = in_plane(box.hi, k);
  out.pour_area = rectangle ? (phi[0] - plo[0]) * (phi[1] - plo[1]) : analysed->area;
  const std::string opened =
      rectangle ? fmt::format("({:.6g} x {:.6g})", phi[0] - plo[0], phi[1] - plo[1])
                : fmt::format("({:.6g} in area, the case's rim cut round it)", analysed->area);
  const std::string after = cuts.empty() ? std::string()
                                         : fmt::format(" once the case's {} other piece{} off", cuts.size(),
                                                       cuts.size() == 1 ? " is" : "s are");
  out.release_proof = fmt::format(
      "{} leaves its case along {}{}: its flat face across {} {} is the case's opening, and none of the {} "
      "faces of {} against the main piece faces {}, by exact orientation signs",
      name, dir, after, open_dir, opened, main_faces, name, dir);
  for (std::size_t i = 0; i < cuts.size(); ++i) {
    const Cut& c = cuts[i];
    CasePlate plate;
    plate.soup = std::move((*pieces)[i + 1]);
    plate.pull = c.d.normalized();
    const BoundingBox b = bounding_box(plate.soup.vertices);
    plate.lo = b.lo;
    plate.hi = b.hi;
    plate.features = c.features;
    plate.pins = c.pins;
    plate.face = c.what;
    plate.corner = c.corner;
    plate.u = c.ru;
    plate.v = c.rv;
    plate.d = c.rd;
    if (c.axis) {
      plate.face_axis = c.axis->q;
      plate.face_at = c.axis->e;
    }
    plate.hollow = c.hollow;
    plate.hollow_along = c.hollow_along;
    for (const Sector& sector : c.core) plate.cores.push_back(sector.prism());
    if (c.lid) {
      const int slanted = (c.frame.split[0] ? 0 : 1) + (c.frame.split[1] ? 0 : 1);
      const std::string seams =
          slanted == 0 ? "the split plane across that way"
          : slanted == 1
              ? "the split plane across that way and the plane of its other split face beyond its back, "
                "whose triangles face away from that way by exact signs,"
              : "the planes of its two split faces beyond its back, whose triangles face away from that way "
                "by exact signs,";
      plate.release_proof = fmt::format(
          "piece {} (the lid over {}) comes off{} along {}: it touches {} only on the {} faces of its back "
          "(every other face lies within {:.6g} of the axis, or on its split faces or its flat faces), "
          "which face that way or run along it ({} do), by exact signs; its seams with the pieces left are "
          "{} and the plane of the part's far face along it, and its {} pins run exactly along it out of "
          "their holes",
          i + 1, name, i == 0 ? " first" : " next", vector_text(c.d), name, c.touching, c.inside, c.along,
          seams, c.pins.size());
      out.release_proof += "; " + plate.release_proof;
      out.plates.push_back(std::move(plate));
      continue;
    }
    plate.release_proof = fmt::format(
        "piece {} (beyond {}) comes off{} along {}: the {} faces of {} it touches face that way or run "
        "along it ({} do), by exact signs; its seam with the pieces left is flat across that way, and its "
        "{} pins run exactly along it out of their holes",
        i + 1, c.what, i == 0 ? " first" : " next", vector_text(c.d), c.touching, name, c.along,
        c.pins.size());
    out.release_proof += "; " + plate.release_proof;
    out.plates.push_back(std::move(plate));
  }
  return {std::move(out), {}};
}

// ---- The draft: the part's free faces along the pull, leaned ----

// The part with its free faces along the pull (flat, on a side of the
// mould's outside, across an axis q other than the pull's) leaned by the
// draft: each point of such a face moved into the part along q by
// tan(draft) times its depth behind the pour face, so that the face lies in
// the plane through its edge on the pour face leaning in by the draft. That
// is the part less the prism beyond that plane (CaseDraft, as the STEP case
// cuts it) when every face of the part meeting the face is flat across q
// (it slides in its own plane) and every other point lies inside the plane
// by more than the tolerance (nothing folds): else the face stays as it is.
struct Drafted {
  TriangleSoup part;
  std::vector<CaseDraft> drafts;
  std::vector<std::string> undrafted;
  double meeting_area = 0.0;  ///< of the faces meeting a leaned face that may be curved (leaned)
};

// Nothing folded: every triangle of the leaned part faces as it did (a
// safeguard; the conditions for leaning keep each point on its side of the
// leaned faces). Else nothing leans, each face saying why.
void unfolded(const TriangleSoup& part, Drafted& d) {
  const std::vector<Vec3>& moved = d.part.vertices;
  for (const Triangle& tri : part.triangles) {
    const Vec3 before =
        (part.vertices[tri[1]] - part.vertices[tri[0]]).cross(part.vertices[tri[2]] - part.vertices[tri[0]]);
    const Vec3 after = (moved[tri[1]] - moved[tri[0]]).cross(moved[tri[2]] - moved[tri[0]]);
    if (!(before.dot(after) > 0.0)) {
      for (const CaseDraft& f : d.drafts) {
        d.undrafted.push_back(fmt::format("{} does not lean: a face of the part would fold", f.face));
      }
      d.drafts.clear();
      d.part = part;
      d.meeting_area = 0.0;
      return;
    }
  }
}

Drafted drafted(const TriangleSoup& part, const Axis& axis, const CaseOptions& options,
                const std::function<std::string(const Vec3&)>& what_is_at) {
  Drafted out{part, {}, {}};
  if (options.draft_deg == 0.0 || !options.outside) return out;
  const int k = axis.k;
  const BoundingBox box = bounding_box(part.vertices);
  const double pour = axis.sign > 0 ? box.hi[k] : box.lo[k];
  const double depth = box.hi[k] - box.lo[k];
  const double tangent = std::tan(options.draft_deg * M_PI / 180.0);
  const double w = options.wall;
  // How far into the part a point's face moves: by its depth behind the pour face.
  const auto inset = [&](const Vec3& p) { return tangent * std::abs(pour - p[k]); };
  std::vector<Vec3>& moved = out.part.vertices;
  for (const int q : {(k + 1) % 3, (k + 2) % 3}) {
    const int j = 3 - k - q;
    for (const int s : {-1, 1}) {
      const double at = s > 0 ? box.hi[q] : box.lo[q];
      if (at != (s > 0 ? options.outside->hi[q] : options.outside->lo[q])) continue;
      const std::string name = fmt::format("its face across {}{}", s > 0 ? "+" : "-", "xyz"[q]);
      const auto on = [&](Index v) { return part.vertices[v][q] == at; };
      const auto touching = [&](const Triangle& tri) {
        return static_cast<int>(on(tri[0])) + on(tri[1]) + on(tri[2]);
      };
      if (std::none_of(part.triangles.begin(), part.triangles.end(),
                       [&](const Triangle& tri) { return touching(tri) == 3; })) {
        continue;  // no flat face there
      }
      std::string why;
      for (std::size_t t = 0; t < part.triangles.size() && why.empty(); ++t) {
        const Triangle& tri = part.triangles[t];
        if (touching(tri) == 0 || touching(tri) == 3) continue;
        // It meets the face: it must slide in its own plane, flat across q.
        if (facing(part, tri, q) != 0) {
          why = fmt::format("its face at {} meets it and is not flat across {}", where(part, t, what_is_at),
                            "xyz"[q]);
        }
      }
      for (std::size_t v = 0; v < part.vertices.size() && why.empty(); ++v) {
        const Vec3& p = part.vertices[v];
        if (p[q] != at && s * (p[q] - at) + inset(p) > -options.tolerance) {
          why = fmt::format("its point at {}{} lies within {:.3g} of where it would lean to", point_text(p),
                            what_is_at ? what_is_at(p) : std::string(), options.tolerance);
        }
      }
      if (!why.empty()) {
        out.undrafted.push_back(fmt::format("{} does not lean: {}", name, why));
        continue;
      }
      for (std::size_t v = 0; v < part.vertices.size(); ++v) {
        if (part.vertices[v][q] == at) moved[v][q] = at - s * inset(part.vertices[v]);
      }
      // The faces meeting it that may be curved: those not in a plane across
      // an axis (a mould part's faces in such planes are its exact flat
      // ones: the block's sides, top and bottom, the cuts, split planes on
      // the axes).
      const auto in_axis_plane = [&](const Triangle& tri) {
        for (int a = 0; a < 3; ++a) {
          const double x = part.vertices[tri[0]][a];
          if (part.vertices[tri[1]][a] == x && part.vertices[tri[2]][a] == x) return true;
        }
        return false;
      };
      for (const Triangle& tri : part.triangles) {
        if ((touching(tri) == 1 || touching(tri) == 2) && !in_axis_plane(tri)) {
          out.meeting_area +=
              0.5 * (moved[tri[1]] - moved[tri[0]]).cross(moved[tri[2]] - moved[tri[0]]).norm();
        }
      }
      // Its prism, in the plane across j: the edge on the pour face, the
      // point a wall behind the part's far side on the leaned plane, and two
      // points a wall outside the face; swept past the part both ways.
      const double far = pour - axis.sign * (depth + w);
      const auto point = [&](double along_q, double along_k) {
        Vec3 p = Vec3::Zero();
        p[q] = along_q;
        p[k] = along_k;
        p[j] = box.lo[j] - w;
        return p;
      };
      CaseDraft d;
      d.face = name;
      d.section = {point(at, pour), point(at - s * tangent * (depth + w), far), point(at + s * w, far),
                   point(at + s * w, pour)};
      d.along[j] = box.hi[j] - box.lo[j] + 2.0 * w;
      out.drafts.push_back(std::move(d));
    }
  }
  unfolded(part, out);
  return out;
}

// A cylinder mould's base part (poured through its flat face across the
// axis, `axis`) with its wall on the block's cylinder leaned into a cone:
// each point of the wall moved toward the axis along its radius by
// tan(draft) times its height above the pour face, so that the wall lies on
// the cone through its edge on the pour face narrowing by the draft. That is
// the part less the ring beyond the cone (CaseDraft::about_axis) when every
// face meeting the wall is level (it slides in its own plane) and every
// other point lies inside the cone by more than the tolerance.
Drafted cone_drafted(const TriangleSoup& part, const Axis& axis, double radius, const CaseOptions& options,
                     const std::function<std::string(const Vec3&)>& what_is_at) {
  Drafted out{part, {}, {}};
  if (options.draft_deg == 0.0 || axis.k != 2) return out;
  const BoundingBox box = bounding_box(part.vertices);
  const double pour = axis.sign > 0 ? box.hi.z() : box.lo.z();
  const double depth = box.hi.z() - box.lo.z();
  const double tangent = std::tan(options.draft_deg * M_PI / 180.0);
  const double w = options.wall;
  const auto inset = [&](const Vec3& p) { return tangent * std::abs(pour - p.z()); };
  const std::string name = "its cylinder";
  std::vector<char> on(part.vertices.size(), 0);
  for (std::size_t v = 0; v < on.size(); ++v) {
    on[v] = radial(part.vertices[v], 2) >= radius * (1.0 - 1e-9) ? 1 : 0;
  }
  const auto touching = [&](const Triangle& tri) { return on[tri[0]] + on[tri[1]] + on[tri[2]]; };
  if (std::none_of(part.triangles.begin(), part.triangles.end(),
                   [&](const Triangle& tri) { return touching(tri) == 3; })) {
    return out;  // no wall on the cylinder
  }
  std::string why;
  if (!(radius - tangent * (depth + w) > 0.0)) {
    why = fmt::format("leaned by {} degrees over its height, it would pass the axis", options.draft_deg);
  }
  for (std::size_t t = 0; t < part.triangles.size() && why.empty(); ++t) {
    const Triangle& tri = part.triangles[t];
    if (touching(tri) == 0 || touching(tri) == 3) continue;
    const double z = part.vertices[tri[0]].z();
    if (part.vertices[tri[1]].z() != z || part.vertices[tri[2]].z() != z) {
      why = fmt::format("its face at {} meets it and is not level", where(part, t, what_is_at));
    }
  }
  for (std::size_t v = 0; v < part.vertices.size() && why.empty(); ++v) {
    const Vec3& p = part.vertices[v];
    if (on[v] == 0 && radial(p, 2) + inset(p) > radius - options.tolerance) {
      why = fmt::format("its point at {}{} lies within {:.3g} of where it would lean to", point_text(p),
                        what_is_at ? what_is_at(p) : std::string(), options.tolerance);
    }
  }
  if (!why.empty()) {
    out.undrafted.push_back(fmt::format("{} does not lean: {}", name, why));
    return out;
  }
  for (std::size_t v = 0; v < part.vertices.size(); ++v) {
    const Vec3& p = part.vertices[v];
    const double by = inset(p);
    if (on[v] == 0 || by == 0.0) continue;
    const double keep = 1.0 - by / radial(p, 2);
    out.part.vertices[v].x() = p.x() * keep;
    out.part.vertices[v].y() = p.y() * keep;
  }
  // The wall (its faces not level) is inscribed in the exact cylinder, now
  // in the exact cone: its own area bounds how far the wedge's volume may
  // lie from the exact one.
  for (const Triangle& tri : part.triangles) {
    const double z = part.vertices[tri[0]].z();
    if (touching(tri) != 3 || (part.vertices[tri[1]].z() == z && part.vertices[tri[2]].z() == z)) continue;
    const std::vector<Vec3>& m = out.part.vertices;
    out.meeting_area += 0.5 * (m[tri[1]] - m[tri[0]]).cross(m[tri[2]] - m[tri[0]]).norm();
  }
  // The ring's section in the half-plane y = 0: the edge on the pour face,
  // the point a wall beyond the part's far side on the cone, and two points
  // a wall outside the cylinder.
  const double far = pour - axis.sign * (depth + w);
  CaseDraft d;
  d.face = name;
  d.section = {Vec3(radius, 0.0, pour), Vec3(radius - tangent * (depth + w), 0.0, far),
               Vec3(radius + w, 0.0, far), Vec3(radius + w, 0.0, pour)};
  d.about_axis = true;
  out.drafts.push_back(std::move(d));
  unfolded(part, out);
  return out;
}

// The case that `build` makes around the part with its free faces leaned
// (`d`), or none when no face leans or the leaned part has no case that way
// (each face then named in d.undrafted).
template <typename Build>
std::optional<CastingCase> leaned(const TriangleSoup& part, Drafted& d, const Build& build,
                                  const CaseOptions& options) {
  if (d.drafts.empty()) return std::nullopt;
  Attempt a = build(d.part);
  if (!a.built) {
    for (const CaseDraft& f : d.drafts) {
      d.undrafted.push_back(
          fmt::format("{} does not lean: leaned, the part has no case that way ({})", f.face, a.why_not));
    }
    return std::nullopt;
  }
  a.built->draft_volume = signed_volume(part) - signed_volume(d.part);
  a.built->draft_volume_error = options.tolerance * d.meeting_area;
  a.built->drafts = std::move(d.drafts);
  a.built->undrafted = std::move(d.undrafted);
  return std::move(a.built);
}

// The case of a part of a cylinder mould (CaseOptions::cylinder_radius),
// carved: a side part's (its split faces one plane through the axis) poured
// through its flat top or bottom, its back under a lid that comes off first
// along the split face's normal, and the part then pulled that way; a base
// part's poured through a flat face across the axis that it leaves by.
CastingCase cylinder_case(const TriangleSoup& part, const std::string& name, const std::vector<Axis>& axes,
                          const CaseOptions& options,
                          const std::function<std::string(const Vec3&)>& what_is_at,
                          const std::vector<CaseFace>& faces) {
  const double radius = *options.cylinder_radius;
  if (!(radius > 0.0) || !std::isfinite(radius)) {
    throw GeometryError("case",
                        fmt::format("{}: its block's radius {} is not a length above 0", name, radius));
  }
  const std::string undrafted =
      "no face leans: this part's back is the block's cylinder, and its bottom stands on the table or on "
      "the base part";
  std::string reasons;
  const auto refused = [&](const Axis& pull, const Axis& opening, const std::string& why) {
    reasons += fmt::format("{}poured through {} and pulled along {}, {}", reasons.empty() ? "" : "; ",
                           axis_name(opening), axis_name(pull), why);
  };
  if (faces.empty()) {
    for (const Axis& axis : axes) {
      if (axis.k != 2) continue;  // across the axis: a curved side cannot be poured level
      const auto build = [&](const TriangleSoup& p) {
        return carved(p, name, axis, axis, false, std::nullopt, options, {}, what_is_at);
      };
      Drafted d = cone_drafted(part, axis, radius, options, what_is_at);
      if (std::optional<CastingCase> c = leaned(part, d, build, options)) return std::move(*c);
      Attempt a = build(part);
      if (a.built) {
        a.built->undrafted = std::move(d.undrafted);
        return std::move(*a.built);
      }
      refused(axis, axis, a.why_not);
    }
    throw GeometryError("case", fmt::format("no casting case releases {}: {}", name, reasons));
  }
  // The pull: across x or y, with the part's back (its points on the
  // cylinder) on its side of the plane through the axis across it (exactly;
  // the keys' bumps may cross it), a split face on that plane when one is. The lid comes off that way over
  // the back; the split faces off the plane (a mould in more than 2 parts) each have a piece of their own,
  // taken off across them before the part leaves the main piece.
  const auto on_plane = [](const CaseFace& f, const Axis& a) {
    return std::abs(f.normal[a.k] + a.sign) <= 1e-12 && std::abs(f.normal[1 - a.k]) <= 1e-12 &&
           f.normal.z() == 0.0 && f.point.norm() <= 1e-9;
  };
  std::vector<Axis> pulls;
  for (int q = 0; q < 2; ++q) {
    for (int sign : {1, -1}) {
      const Axis a{q, sign};
      if (std::any_of(part.vertices.begin(), part.vertices.end(), [&](const Vec3& p) {
            return sign * p[q] < 0.0 && radial(p, 2) >= radius * (1.0 - 1e-9);
          })) {
        continue;
      }
      const bool split =
          std::any_of(faces.begin(), faces.end(), [&](const CaseFace& f) { return on_plane(f, a); });
      pulls.insert(split ? pulls.begin() : pulls.end(), a);
    }
  }
  if (pulls.empty()) {
    throw GeometryError(
        "case",
        fmt::format("no casting case is made for {}: it lies on both sides of every plane through the "
                    "axis across x or y, so no lid over its curved back comes off across one",
                    name));
  }
  for (const Axis& pull : pulls) {
    std::vector<CaseFace> given;
    for (const CaseFace& f : faces) {
      if (!on_plane(f, pull)) given.push_back(f);
    }
    // With no split face on the lid's plane (the middle side of 3), the
    // piece beyond its last split face takes the vessel's slice too, and the
    // part lifts off the floor (over a base part, off its keys) through the
    // opening.
    const bool lifted = given.size() == faces.size();
    for (int sign : {1, -1}) {
      const Axis opening{2, sign};
      Attempt a = carved(part, name, lifted ? opening : pull, opening, false, Lid{radius, pull, lifted},
                         options, given, what_is_at);
      if (a.built) {
        a.built->undrafted = {undrafted};
        return std::move(*a.built);
      }
      refused(pull, opening, a.why_not);
    }
  }
  throw GeometryError("case", fmt::format("no casting case with a lid releases {}: {}", name, reasons));
}

}  // namespace

CasePin case_pin(const CaseOptions& options) {
  const double w = options.wall;
  CasePin pin;
  pin.radius = w / 4.0;
  pin.height = w / 2.0;
  pin.buried = w / 4.0;
  pin.hole_radius = pin.radius + options.clearance;
  pin.hole_depth = pin.height + options.clearance;
  pin.sides = pin_sides(pin.hole_radius, options.tolerance);
  return pin;
}

double case_pin_margin(const CaseOptions& options) { return options.wall / 16.0; }

std::optional<ValidationReport> without_hairs(TriangleSoup& piece, double tolerance) {
  // Edges shorter than this share of the tolerance: a cut that passes a
  // hair from one of the part's vertices crosses its edges points apart
  // that float32 files round to one (faces folded), and nothing a printer
  // makes is that fine.
  constexpr double kHairShare = 0.01;
  TriangleSoup collapsed = piece;
  if (collapse_short_edges(collapsed, kHairShare * tolerance) == 0) return std::nullopt;
  ValidationReport report = validate(collapsed);
  if (!report.valid()) return std::nullopt;
  piece = std::move(collapsed);
  return report;
}

// The sides of a pin's and its hole's polygons: a multiple of 4 (8 to 512)
// keeping the hole's circle of `radius` within `tolerance` of its polygon.
std::size_t pin_sides(double radius, double tolerance) {
  const double ratio = 1.0 - tolerance / radius;  // cos(pi / sides) at least this
  const double count = ratio <= -1.0 ? 8.0 : std::ceil(M_PI / std::acos(ratio) / 4.0) * 4.0;
  return static_cast<std::size_t>(std::clamp(count, 8.0, 512.0));
}

// The solid o + a u + b v + c d over the ranges a, b, c (u, v, d
// right-handed), closed and outward.
TriangleSoup block_of(const Vec3& o, const Vec3& u, const Vec3& v, const Vec3& d,
                      const std::array<double, 2>& a, const std::array<double, 2>& b,
                      const std::array<double, 2>& c) {
  TriangleSoup s;
  for (int n = 0; n < 8; ++n)
    s.vertices.push_back(o + a[n & 1] * u + b[(n >> 1) & 1] * v + c[(n >> 2) & 1] * d);
  s.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return s;
}

// The prism over the ring of `sides` points about `centre` of `radius`
// across d (in the plane of e1, e2), running `length` along d: its walls run
// exactly along d (the ring on the point grid, length on the length grid).
TriangleSoup pin_prism(const Vec3& centre, const Vec3& e1, const Vec3& e2, const Vec3& d, double radius,
                       double length, std::size_t sides) {
  std::vector<Vec3> ring;
  ring.reserve(sides);
  for (std::size_t m = 0; m < sides; ++m) {
    const double angle = 2.0 * M_PI * static_cast<double>(m) / static_cast<double>(sides);
    ring.push_back(snapped(centre + radius * (std::cos(angle) * e1 + std::sin(angle) * e2), kPointBits));
  }
  return prism_over(ring, length * d);
}

std::vector<CaseFace> split_faces(const MouldPart& part) {
  std::vector<CaseFace> out;
  if (part.kind != MouldPartKind::Side) return out;
  for (const bool from : {true, false}) {
    const double angle = from ? part.from_angle : part.to_angle;
    CaseFace f;
    f.name = fmt::format("its split face at {:.4g} degrees", std::fmod(angle * 180.0 / M_PI, 360.0));
    f.normal =
        from ? Vec3(std::sin(angle), -std::cos(angle), 0.0) : Vec3(-std::sin(angle), std::cos(angle), 0.0);
    for (const KeyFeature& k : part.keys) {
      if (k.on_base || k.bump == from) continue;  // sockets on the `from` plane, bumps on the `to` plane
      ++f.features;
      if (!k.bump) f.depth = std::max(f.depth, k.radius);
    }
    out.push_back(f);
  }
  return out;
}

TriangleSoup standing(const TriangleSoup& soup, const Vec3& up, const Vec3& corner) {
  // A right-handed frame of axis vectors with z along `up`: coordinates in
  // it are the old ones permuted and negated, so nothing rounds.
  const Vec3 ex = std::abs(up.z()) == 1.0 ? Vec3(1.0, 0.0, 0.0) : Vec3(0.0, 0.0, 1.0);
  const Vec3 ey = up.cross(ex);
  TriangleSoup out = soup;
  for (Vec3& p : out.vertices) p = Vec3(p.dot(ex), p.dot(ey), p.dot(up));
  const Vec3 lo = bounding_box(out.vertices).lo;
  for (Vec3& p : out.vertices) p = p - lo + corner;
  return out;
}

TriangleSoup standing(const CastingCase& c, const Vec3& corner) { return standing(c.soup, c.pull, corner); }

TriangleSoup standing(const CasePlate& p, const Vec3& corner) {
  // On its outer side: the side of the case's box its pull points most toward.
  Eigen::Index q = 0;
  p.pull.cwiseAbs().maxCoeff(&q);
  Vec3 up = Vec3::Zero();
  up[q] = p.pull[q] > 0.0 ? -1.0 : 1.0;
  return standing(p.soup, up, corner);
}

CastingCase build_casting_case(const TriangleSoup& part, const std::string& name, const Vec3& outward,
                               const CaseOptions& options,
                               const std::function<std::string(const Vec3&)>& what_is_at,
                               const std::vector<CaseFace>& faces) {
  if (!(options.wall > 0.0) || !std::isfinite(options.wall)) {
    throw RangeError("wall", options.wall,
                     fmt::format("case.wall = {} must be a length above 0", options.wall),
                     ErrorLocation{"case.wall"});
  }
  if (!(options.clearance >= 0.0) || !(options.clearance < options.wall / 4.0)) {
    throw RangeError(
        "clearance", options.clearance,
        fmt::format("case.clearance = {} must be at least 0 and below a quarter of case.wall ({}): "
                    "a plate's pins are a quarter of the wall in radius, and their holes must "
                    "keep wall all round",
                    options.clearance, options.wall / 4.0),
        ErrorLocation{"case.clearance"});
  }
  if (!(options.tolerance > 0.0) || !std::isfinite(options.tolerance)) {
    throw RangeError("tolerance", options.tolerance,
                     fmt::format("the case's tolerance = {} must be above 0", options.tolerance));
  }
  if (!(options.draft_deg >= 0.0 && options.draft_deg <= 10.0)) {
    throw RangeError(
        "draft_deg", options.draft_deg,
        fmt::format("case.draft_deg = {} must be an angle from 0 to 10 degrees", options.draft_deg),
        ErrorLocation{"case.draft_deg"});
  }
  if (part.triangles.empty()) throw GeometryError("case", name + " has no triangles to make a case of");
  std::vector<Axis> axes;
  for (int k = 0; k < 3; ++k) {
    for (int sign : {1, -1}) axes.push_back({k, sign});
  }
  std::stable_sort(axes.begin(), axes.end(), [&](const Axis& a, const Axis& b) {
    return outward[a.k] * a.sign > outward[b.k] * b.sign;
  });
  if (options.cylinder_radius) return cylinder_case(part, name, axes, options, what_is_at, faces);
  std::string first_reason;
  std::vector<Axis> caught;  // the directions with a flat face to pour through, where faces catch
  for (const Axis& axis : axes) {
    Attempt a = attempt(part, name, axis, options, what_is_at);
    if (a.built) {
      Drafted d = drafted(part, axis, options, what_is_at);
      const auto build = [&](const TriangleSoup& p) { return attempt(p, name, axis, options, what_is_at); };
      if (std::optional<CastingCase> c = leaned(part, d, build, options)) return std::move(*c);
      a.built->undrafted = std::move(d.undrafted);
      return std::move(*a.built);
    }
    if (first_reason.empty()) first_reason = fmt::format("pulled along {}, {}", axis_name(axis), a.why_not);
    if (a.catches) caught.push_back(axis);
  }
  // Then in several pieces, taken off one after the other.
  std::string carved_reason;
  for (const Axis& axis : caught) {
    // Leaned first: carving is costly, and a part carved one way leaned mostly is too.
    Drafted d = drafted(part, axis, options, what_is_at);
    const auto build = [&](const TriangleSoup& p) {
      return carved(p, name, axis, axis, true, std::nullopt, options, faces, what_is_at);
    };
    if (std::optional<CastingCase> c = leaned(part, d, build, options)) return std::move(*c);
    Attempt a = build(part);
    if (a.built) {
      a.built->undrafted = std::move(d.undrafted);
      return std::move(*a.built);
    }
    if (carved_reason.empty()) {
      carved_reason = fmt::format("; in several pieces pulled along {}, {}", axis_name(axis), a.why_not);
    }
  }
  throw GeometryError("case", fmt::format("no casting case of one piece, or of one piece and a plate, "
                                          "releases {}: {}; no other axis direction has a flat face to "
                                          "pour through that releases it either{}",
                                          name, first_reason, carved_reason));
}

}  // namespace fabmesh
