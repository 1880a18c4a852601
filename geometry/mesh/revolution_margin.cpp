#include "geometry/mesh/revolution_margin.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>

#include "geometry/mesh/revolve.h"

namespace fabmesh {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Rounding allowances, relative to the largest coordinate S of the section.
// Every bound below is computed in double from coordinates of magnitude <= S
// with a handful of operations, so its rounding error is a small multiple of
// 2^-53 S (< 1e-15 S); 1e-12 S leaves a wide margin. The vertices of angular
// step j are rounded products x cos(theta_j), x sin(theta_j): they differ
// from the exact rotation of step 0's by less than 1e-13 S.
constexpr double kBoundSlack = 1e-12;
constexpr double kRotationSlack = 1e-13;

/// A corner of a revolved face: its position and which mesh vertex it is
/// (loop vertex, angular step or the pole marker).
struct Corner {
  Vec3 p;
  std::pair<std::size_t, std::size_t> key;
};
using Face = std::array<Corner, 3>;

/// Separation of the convex hulls of two small point sets: the largest gap
/// along a set of axes that contains the direction of their closest points
/// (vertex-vertex, vertex-edge, vertex-face and edge-edge), so it equals their
/// distance up to rounding; any axis gives a lower bound. Less `slack`; >= 0.
double separation(const std::vector<Vec3>& a, const std::vector<Vec3>& b, double slack) {
  std::vector<Vec3> axes;
  auto edges = [](const std::vector<Vec3>& s) {
    std::vector<std::pair<Vec3, Vec3>> e;
    for (std::size_t i = 0; i < s.size(); ++i) {
      for (std::size_t j = i + 1; j < s.size(); ++j) e.emplace_back(s[i], s[j]);
    }
    return e;
  };
  const auto ea = edges(a), eb = edges(b);
  for (const Vec3& p : a) {
    for (const Vec3& q : b) axes.push_back(q - p);
  }
  for (const auto& [p0, p1] : ea) {
    for (const auto& [q0, q1] : eb) axes.push_back((p1 - p0).cross(q1 - q0));
  }
  auto point_edge = [&](const std::vector<Vec3>& points, const std::vector<std::pair<Vec3, Vec3>>& es) {
    for (const Vec3& p : points) {
      for (const auto& [q0, q1] : es) {
        const Vec3 d = q1 - q0;
        const double dd = d.squaredNorm();
        if (dd > 0.0) axes.push_back((p - q0) - d * ((p - q0).dot(d) / dd));
      }
    }
  };
  point_edge(a, eb);
  point_edge(b, ea);
  for (const std::vector<Vec3>* s : {&a, &b}) {
    if (s->size() != 3) continue;
    const Vec3 n = ((*s)[1] - (*s)[0]).cross((*s)[2] - (*s)[0]);
    axes.push_back(n);
    for (const auto& [q0, q1] : edges(*s)) axes.push_back(n.cross(q1 - q0));
  }
  double best = 0.0;
  for (const Vec3& w : axes) {
    const double length = w.norm();
    if (!(length > 0.0) || !std::isfinite(length)) continue;
    double lo_a = kInf, hi_a = -kInf, lo_b = kInf, hi_b = -kInf;
    for (const Vec3& p : a) {
      lo_a = std::min(lo_a, w.dot(p));
      hi_a = std::max(hi_a, w.dot(p));
    }
    for (const Vec3& q : b) {
      lo_b = std::min(lo_b, w.dot(q));
      hi_b = std::max(hi_b, w.dot(q));
    }
    best = std::max(best, std::max(lo_b - hi_a, lo_a - hi_b) / length);
  }
  return std::max(0.0, best - slack);
}

std::vector<Vec3> points(std::initializer_list<const Corner*> corners) {
  std::vector<Vec3> out;
  for (const Corner* c : corners) out.push_back(c->p);
  return out;
}

/// The distance within which moving both faces could make them intersect
/// (the deciding features of their class, see the header), less `slack`.
double pair_bound(const Face& f, const Face& g, double slack) {
  std::array<int, 3> in_g{-1, -1, -1};  // for each corner of f, its corner in g
  int shared = 0;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (f[i].key == g[j].key) in_g[i] = j;
    }
    shared += in_g[i] >= 0;
  }
  const auto all = [](const Face& t) { return points({&t[0], &t[1], &t[2]}); };
  if (shared == 0) return separation(all(f), all(g), slack);
  if (shared == 1) {
    const int i = in_g[0] >= 0 ? 0 : in_g[1] >= 0 ? 1 : 2;
    const int j = in_g[i];
    const double opposite_f = separation(points({&f[(i + 1) % 3], &f[(i + 2) % 3]}), all(g), slack);
    const double opposite_g = separation(points({&g[(j + 1) % 3], &g[(j + 2) % 3]}), all(f), slack);
    return std::min(opposite_f, opposite_g);
  }
  if (shared == 2) {
    const int apex_f = in_g[0] < 0 ? 0 : in_g[1] < 0 ? 1 : 2;
    const Corner& u = f[(apex_f + 1) % 3];
    const Corner& v = f[(apex_f + 2) % 3];
    const Corner& a = f[apex_f];
    const Corner& b = g[3 - in_g[(apex_f + 1) % 3] - in_g[(apex_f + 2) % 3]];
    return std::min({separation(points({&b}), all(f), slack), separation(points({&a}), all(g), slack),
                     separation(points({&u, &b}), points({&v, &a}), slack),
                     separation(points({&u, &a}), points({&v, &b}), slack)});
  }
  return 0.0;  // the same face twice: never made by revolve
}

/// The least altitude of a face, less `slack`. Three points moved by less
/// than half of it stay non-collinear: if they were collinear, one would lie
/// on the segment of the other two, so its original would be within twice
/// the move of the opposite side.
double least_altitude(const Face& f, double slack) {
  const double doubled_area = (f[1].p - f[0].p).cross(f[2].p - f[0].p).norm();
  const double longest =
      std::max({(f[1].p - f[0].p).norm(), (f[2].p - f[1].p).norm(), (f[0].p - f[2].p).norm()});
  if (!(longest > 0.0)) return 0.0;
  return std::max(0.0, doubled_area / longest * (1.0 - 1e-12) - slack);
}

/// Distance between two section edges (a lower bound, less `slack`): their
/// separation in the plane z = 0 (0 when they may touch).
double segment_distance(const Vec2& p0, const Vec2& p1, const Vec2& q0, const Vec2& q1, double slack) {
  auto lift = [](const Vec2& p) { return Vec3(p.x(), p.y(), 0.0); };
  return separation({lift(p0), lift(p1)}, {lift(q0), lift(q1)}, slack);
}

struct Edge2 {
  std::size_t loop, index;
  Vec2 p, q;
  double lo, hi;  // extent in height
};

/// The least distance between two section edges (not along the axis) that
/// share no section vertex, when it is below `cap`; else `cap`.
double section_clearance(const std::vector<std::vector<Vec2>>& loops, double cap, double slack) {
  std::vector<Edge2> edges;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const auto& loop = loops[l];
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Vec2& p = loop[i];
      const Vec2& q = loop[(i + 1) % loop.size()];
      if (p.x() == 0.0 && q.x() == 0.0) continue;  // an axis edge makes no faces
      edges.push_back({l, i, p, q, std::min(p.y(), q.y()), std::max(p.y(), q.y())});
    }
  }
  std::sort(edges.begin(), edges.end(), [](const Edge2& a, const Edge2& b) { return a.lo < b.lo; });
  double best = cap;
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const Edge2& e = edges[i];
    for (std::size_t j = i + 1; j < edges.size() && edges[j].lo <= e.hi + best; ++j) {
      const Edge2& f = edges[j];
      if (e.loop == f.loop) {
        const std::size_t n = loops[e.loop].size();
        const std::size_t gap = (e.index + n - f.index) % n;
        if (gap == 1 || gap == n - 1) continue;  // neighbours: bounded with the faces
      }
      const double x_gap = std::max(std::min(e.p.x(), e.q.x()) - std::max(f.p.x(), f.q.x()),
                                    std::min(f.p.x(), f.q.x()) - std::max(e.p.x(), e.q.x()));
      if (x_gap >= best) continue;
      best = std::min(best, segment_distance(e.p, e.q, f.p, f.q, slack));
    }
  }
  return best;
}

}  // namespace

double revolution_margin(const std::vector<std::vector<Vec2>>& loops, int segments) {
  if (segments < 3) return 0.0;
  const auto m = static_cast<std::size_t>(segments);
  double scale = 0.0, r_max = 0.0, r_min = kInf;
  for (const auto& loop : loops) {
    for (const Vec2& p : loop) {
      scale = std::max({scale, std::abs(p.x()), std::abs(p.y())});
      r_max = std::max(r_max, p.x());
      if (p.x() > 0.0) r_min = std::min(r_min, p.x());
    }
  }
  if (!std::isfinite(scale) || !(r_min < kInf)) return 0.0;
  const double slack = kBoundSlack * scale;
  const double half_step = M_PI / static_cast<double>(m);

  // Two or more angular steps apart (only when there are four or more steps).
  double wedge = kInf;
  if (m >= 4) {
    const double angle = std::min(2.0 * half_step, M_PI / 2.0);
    wedge = std::cos(half_step) * r_min * std::sin(angle) * (1.0 - 1e-12) - slack;
  }

  // At most one step apart, from the same or neighbouring section edges.
  double local = kInf;
  for (const auto& loop : loops) {
    const std::size_t n = loop.size();
    auto on_axis = [&](std::size_t i) { return loop[i % n].x() == 0.0; };
    auto corner = [&](std::size_t i, long step) -> Corner {
      const Vec2& p = loop[i % n];
      if (on_axis(i)) return {Vec3(0.0, 0.0, p.y()), {i % n, m}};
      const std::size_t j =
          static_cast<std::size_t>((step % static_cast<long>(m) + static_cast<long>(m))) % m;
      return {revolved_point(p, revolve_direction(j, segments)), {i % n, j}};
    };
    // revolve's faces of loop edge e at angular step j.
    auto faces = [&](std::size_t e, long j) {
      std::vector<Face> out;
      for_each_edge_face(
          on_axis(e), on_axis(e + 1), j, [&](bool is_b, long step) { return corner(is_b ? e + 1 : e, step); },
          [&](const Corner& c0, const Corner& c1, const Corner& c2) {
            out.push_back({c0, c1, c2});
          });
      return out;
    };
    auto bound_pairs = [&](const std::vector<Face>& fs, const std::vector<Face>& gs, bool same) {
      for (std::size_t x = 0; x < fs.size(); ++x) {
        for (std::size_t y = same ? x + 1 : 0; y < gs.size(); ++y)
          local = std::min(local, pair_bound(fs[x], gs[y], slack));
      }
    };
    for (std::size_t e = 0; e < n; ++e) {
      if (on_axis(e) && on_axis(e + 1)) continue;
      const std::vector<Face> here = faces(e, 0);
      for (const Face& f : here) local = std::min(local, least_altitude(f, slack));
      bound_pairs(here, here, true);
      bound_pairs(here, faces(e, 1), false);
      if (on_axis(e + 1) && on_axis(e + 2)) continue;  // the next edge runs along the axis
      if (on_axis(e) && on_axis(e + 2)) return 0.0;    // a vertex between two poles
      for (const long k : {-1L, 0L, 1L}) bound_pairs(here, faces(e + 1, k), false);
    }
  }

  // From section edges sharing no section vertex: their 2D distance less two sagittas.
  const double sagitta = r_max * 2.0 * std::pow(std::sin(half_step / 2.0), 2) * (1.0 + 1e-12) + slack;
  const double cap = std::min(local, wedge);
  const double apart = section_clearance(loops, cap + 2.0 * sagitta, slack) - 2.0 * sagitta;
  const double least = std::min(cap, apart);
  const double margin = 0.5 * least - kRotationSlack * scale;
  return margin > 0.0 && std::isfinite(margin) ? margin : 0.0;
}

}  // namespace fabmesh
