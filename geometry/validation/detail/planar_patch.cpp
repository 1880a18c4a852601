// The certificate of a plane group (planar_patch.h), every step exact:
// orientations with CGAL's Epick (exact predicates on the doubles), winding
// numbers by signed crossings (Sunday's rule: exact comparisons and
// orientations), border edges against each other through a hierarchy of
// their boxes and CGAL's exact segment test.

#include "geometry/validation/detail/planar_patch.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <unordered_map>
#include <utility>

#include "geometry/validation/detail/triangle_bvh.h"

namespace fabmesh::detail {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_2;

constexpr std::size_t kMaxLoopWork = 20'000'000;  ///< loops x border edges for the nesting test

/// One plane group: its faces and how to see them in 2D.
struct Group {
  int axis = 0;
  double level = 0.0;
  std::vector<std::uint32_t> faces;
};

/// A border edge (of one face of the group), directed as its face runs it.
struct Border {
  std::uint32_t from, to;
};

class Certifier {
 public:
  Certifier(const TriangleSoup& soup, const Group& group) : soup_(soup), group_(group) {}

  bool certify() { return oriented() && edges() && vertices() && borders_apart() && loops_nest(); }

 private:
  Point at(std::uint32_t v) const {
    const Vec3& p = soup_.vertices[v];
    return {p[(group_.axis + 1) % 3], p[(group_.axis + 2) % 3]};
  }
  int orient(std::uint32_t a, std::uint32_t b, std::uint32_t c) const {
    return static_cast<int>(CGAL::orientation(at(a), at(b), at(c)));
  }
  /// Signed crossing of edge a -> b around point p (Sunday's rule).
  int crossing(const Point& a, const Point& b, const Point& p) const {
    if (a.y() <= p.y()) {
      if (b.y() > p.y() && CGAL::orientation(a, b, p) == CGAL::LEFT_TURN) return 1;
    } else if (b.y() <= p.y() && CGAL::orientation(a, b, p) == CGAL::RIGHT_TURN) {
      return -1;
    }
    return 0;
  }

  /// Every face non-degenerate, all of one orientation (sign_).
  bool oriented() {
    for (const std::uint32_t f : group_.faces) {
      const auto& t = soup_.triangles[f];
      const int o = orient(t[0], t[1], t[2]);
      if (o == 0 || (sign_ != 0 && o != sign_)) return false;
      sign_ = o;
    }
    return true;
  }

  /// Every edge has one or two faces, two in opposite directions; the
  /// one-face edges are the border.
  bool edges() {
    struct Side {
      std::uint64_t key;
      std::uint32_t from, to;
    };
    std::vector<Side> sides;
    sides.reserve(3 * group_.faces.size());
    for (const std::uint32_t f : group_.faces) {
      const auto& t = soup_.triangles[f];
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = t[k];
        const std::uint32_t b = t[(k + 1) % 3];
        sides.push_back({(std::uint64_t{std::min(a, b)} << 32) | std::max(a, b), a, b});
      }
    }
    std::sort(sides.begin(), sides.end(), [](const Side& x, const Side& y) { return x.key < y.key; });
    for (std::size_t i = 0; i < sides.size();) {
      std::size_t j = i;
      while (j < sides.size() && sides[j].key == sides[i].key) ++j;
      if (j - i > 2 || (j - i == 2 && sides[i].from == sides[i + 1].from)) return false;
      if (j - i == 1) borders_.push_back({sides[i].from, sides[i].to});
      i = j;
    }
    return true;
  }

  /// Around each vertex the faces form one fan covering its directions once
  /// (no border edge) or one open fan that does not wrap (one border edge out, one in).
  bool vertices() {
    std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> around;
    for (const std::uint32_t f : group_.faces) {
      for (const std::uint32_t v : soup_.triangles[f]) around[v].push_back(f);
    }
    std::unordered_map<std::uint32_t, std::array<int, 2>> border_at;  // out, in
    for (const Border& e : borders_) {
      ++border_at[e.from][0];
      ++border_at[e.to][1];
      out_[e.from] = e.to;
    }
    for (const auto& [v, faces] : around) {
      const auto b = border_at.find(v);
      const bool ok = b == border_at.end()
                          ? winds_once(v, faces)
                          : b->second[0] == 1 && b->second[1] == 1 && does_not_wrap(v, faces);
      if (!ok) return false;
    }
    return true;
  }

  /// Face f's corners starting at v: (v, a, b) in the face's order.
  std::pair<std::uint32_t, std::uint32_t> far_edge(std::uint32_t f, std::uint32_t v) const {
    const auto& t = soup_.triangles[f];
    const int k = t[0] == v ? 0 : t[1] == v ? 1 : 2;
    return {t[(k + 1) % 3], t[(k + 2) % 3]};
  }

  bool winds_once(std::uint32_t v, const std::vector<std::uint32_t>& faces) const {
    int winding = 0;
    const Point p = at(v);
    for (const std::uint32_t f : faces) {
      const auto [a, b] = far_edge(f, v);
      winding += crossing(at(a), at(b), p);
    }
    return winding == sign_;
  }

  bool does_not_wrap(std::uint32_t v, const std::vector<std::uint32_t>& faces) const {
    const std::uint32_t c = out_.at(v);
    for (const std::uint32_t f : faces) {
      auto [a, b] = far_edge(f, v);
      if (a == c) continue;  // the face whose border edge is v -> c: its sector starts (or ends) at c
      if (sign_ < 0) std::swap(a, b);  // the sector, counter-clockwise from a to b
      if (orient(v, a, c) >= 0 && orient(v, c, b) >= 0) return false;
    }
    return true;
  }

  /// No two border edges meet, but consecutive ones at their shared vertex.
  bool borders_apart() const {
    TriangleSoup segments;  // each border edge as a triangle (from, to, to), over its own vertices
    std::unordered_map<std::uint32_t, std::uint32_t> local;
    const auto index = [&](std::uint32_t v) {
      const auto [it, added] = local.emplace(v, static_cast<std::uint32_t>(segments.vertices.size()));
      if (added) segments.vertices.push_back(soup_.vertices[v]);
      return it->second;
    };
    for (const Border& e : borders_) {
      const std::uint32_t a = index(e.from);
      const std::uint32_t b = index(e.to);
      segments.triangles.push_back({a, b, b});
    }
    const TriangleBvh bvh(segments, {}, false);
    TriangleBvh::TaskCursor cursor(bvh, 64);
    std::vector<TriangleBvh::Task> tasks;
    bool apart = true;
    while (apart && cursor.next(1024, tasks)) {
      for (const auto& task : tasks) {
        bvh.run(task, [&](std::size_t i, std::size_t j) {
          if (apart && meet(borders_[bvh.face(i)], borders_[bvh.face(j)])) apart = false;
        });
      }
    }
    return apart;
  }

  bool meet(const Border& e, const Border& g) const {
    std::uint32_t shared = 0;
    std::uint32_t p = 0;
    std::uint32_t q = 0;
    if (e.from == g.from || e.from == g.to) {
      shared = e.from;
    } else if (e.to == g.from || e.to == g.to) {
      shared = e.to;
    } else {
      return CGAL::do_intersect(Kernel::Segment_2(at(e.from), at(e.to)),
                                Kernel::Segment_2(at(g.from), at(g.to)));
    }
    p = e.from == shared ? e.to : e.from;
    q = g.from == shared ? g.to : g.from;
    if (p == q) return true;  // the same edge twice
    if (orient(shared, p, q) != 0) return false;
    // Collinear: they overlap beyond the shared vertex when p and q lie on one side of it.
    const Point s = at(shared), a = at(p), b = at(q);
    const auto side = [](double x, double o) { return x < o ? -1 : x > o ? 1 : 0; };
    const int ax = side(a.x(), s.x()), bx = side(b.x(), s.x());
    return ax != 0 ? ax == bx : side(a.y(), s.y()) == side(b.y(), s.y());
  }

  /// The border loops (each border vertex has one edge out) nest so that
  /// the faces cover every point at most once: just outside each loop the
  /// winding numbers of all loops sum to 0.
  bool loops_nest() const {
    std::vector<std::vector<std::uint32_t>> loops;
    std::unordered_map<std::uint32_t, char> seen;
    for (const Border& e : borders_) {
      if (seen.count(e.from)) continue;
      std::vector<std::uint32_t> loop;
      for (std::uint32_t v = e.from; !seen.count(v); v = out_.at(v)) {
        seen[v] = 1;
        loop.push_back(v);
      }
      loops.push_back(std::move(loop));
    }
    if (loops.size() * borders_.size() > kMaxLoopWork) return false;
    for (std::size_t l = 0; l < loops.size(); ++l) {
      const Point p = at(loops[l].front());
      int winding = 0;
      for (std::size_t m = 0; m < loops.size(); ++m) {
        if (m == l) continue;
        const auto& loop = loops[m];
        for (std::size_t i = 0; i < loop.size(); ++i)
          winding += crossing(at(loop[i]), at(loop[(i + 1) % loop.size()]), p);
      }
      const bool ccw = counter_clockwise(loops[l]);
      const int outside =
          sign_ > 0 ? (ccw ? 0 : -1) : (ccw ? 1 : 0);  // its own winding on its faces' far side
      if (winding + outside != 0) return false;
    }
    return true;
  }

  /// Whether a simple loop runs counter-clockwise: the turn at its lowest
  /// (then leftmost) vertex.
  bool counter_clockwise(const std::vector<std::uint32_t>& loop) const {
    std::size_t low = 0;
    for (std::size_t i = 1; i < loop.size(); ++i) {
      const Point a = at(loop[i]), b = at(loop[low]);
      if (a.y() < b.y() || (a.y() == b.y() && a.x() < b.x())) low = i;
    }
    const std::size_t n = loop.size();
    return orient(loop[(low + n - 1) % n], loop[low], loop[(low + 1) % n]) > 0;
  }

  const TriangleSoup& soup_;
  const Group& group_;
  int sign_ = 0;
  std::vector<Border> borders_;
  std::unordered_map<std::uint32_t, std::uint32_t> out_;  ///< border vertex -> the end of its edge out
};

/// The faces in an axis plane, grouped by the plane, groups in order of (axis, level).
std::vector<Group> plane_groups(const TriangleSoup& soup, const std::vector<char>& skip) {
  struct Entry {
    int axis;
    double level;
    std::uint32_t face;
  };
  std::vector<Entry> entries;
  for (std::uint32_t f = 0; f < soup.triangles.size(); ++f) {
    if (!skip.empty() && skip[f]) continue;
    const auto& t = soup.triangles[f];
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
    for (int k = 0; k < 3; ++k) {
      const double c = soup.vertices[t[0]][k];
      if (soup.vertices[t[1]][k] == c && soup.vertices[t[2]][k] == c) {
        entries.push_back({k, c + 0.0, f});
        break;
      }
    }
  }
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return a.axis != b.axis ? a.axis < b.axis : a.level != b.level ? a.level < b.level : a.face < b.face;
  });
  std::vector<Group> groups;
  for (const Entry& e : entries) {
    if (groups.empty() || groups.back().axis != e.axis || groups.back().level != e.level)
      groups.push_back({e.axis, e.level, {}});
    groups.back().faces.push_back(e.face);
  }
  return groups;
}

}  // namespace

PlanarPatches certify_planar_patches(const TriangleSoup& soup, const std::vector<char>& skip,
                                     std::size_t min_faces) {
  PlanarPatches out;
  out.patch.assign(soup.triangles.size(), kNoPatch);
  for (const Group& group : plane_groups(soup, skip)) {
    if (group.faces.size() < min_faces || !Certifier(soup, group).certify()) continue;
    const auto id = static_cast<std::uint32_t>(out.axis.size());
    out.axis.push_back(group.axis);
    out.level.push_back(group.level);
    for (const std::uint32_t f : group.faces) out.patch[f] = id;
  }
  return out;
}

}  // namespace fabmesh::detail
