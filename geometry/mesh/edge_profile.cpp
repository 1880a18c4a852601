#include "geometry/mesh/edge_profile.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <utility>

#include "geometry/core/budget.h"
#include "geometry/core/error_checks.h"
#include "geometry/core/errors.h"
#include "geometry/section/region.h"
#include "geometry/section/simple_polygon.h"
#include "geometry/section/triangulate.h"

namespace fabmesh {

const char* to_string(EdgeProfileKind kind) {
  switch (kind) {
    case EdgeProfileKind::Square:
      return "square";
    case EdgeProfileKind::Eased:
      return "eased";
    case EdgeProfileKind::HalfBullnose:
      return "half_bullnose";
    case EdgeProfileKind::Bullnose:
      return "bullnose";
    case EdgeProfileKind::Bevel:
      return "bevel";
  }
  return "square";
}

ProfileEdges profile_edges(const EdgeProfile& p) {
  switch (p.kind) {
    case EdgeProfileKind::Square:
      return {};
    case EdgeProfileKind::Eased:
    case EdgeProfileKind::Bullnose:
      return {p.radius, p.radius, false};
    case EdgeProfileKind::HalfBullnose:
      return {p.radius, 0.0, false};
    case EdgeProfileKind::Bevel:
      return {p.radius, 0.0, true};
  }
  return {};
}

double max_profile_radius(EdgeProfileKind kind, double thickness) {
  const bool both = kind == EdgeProfileKind::Eased || kind == EdgeProfileKind::Bullnose;
  return both ? 0.5 * thickness : thickness;
}

namespace {

// The inset of a round of radius r at height u above where it starts (u in [0, r]).
double round_inset(double r, double u) { return r - std::sqrt(std::max(0.0, r * r - u * u)); }

}  // namespace

double profile_inset(const EdgeProfile& profile, double t, double z) {
  const ProfileEdges e = profile_edges(profile);
  z = std::clamp(z, 0.0, t);
  if (e.top > 0.0 && z > t - e.top) {
    const double u = z - (t - e.top);
    return e.chamfer ? u : round_inset(e.top, u);
  }
  if (e.bottom > 0.0 && z < e.bottom) return round_inset(e.bottom, e.bottom - z);
  return 0.0;
}

std::vector<ProfileLevel> profile_levels(const EdgeProfile& profile, double t, double tolerance,
                                         double* sagitta) {
  require_positive("thickness", t);
  require_positive("tolerance", tolerance);
  const ProfileEdges e = profile_edges(profile);
  double worst = 0.0;
  // Quarter circles of radius r in n equal steps of angle: chords within the tolerance.
  const auto steps = [&](double r) {
    const double h = tolerance >= r ? 0.5 * M_PI : 2.0 * std::acos(1.0 - tolerance / r);
    const int n = std::max(2, static_cast<int>(std::ceil(0.5 * M_PI / h)));
    worst = std::max(worst, r * (1.0 - std::cos(0.25 * M_PI / n)));
    return n;
  };
  std::vector<ProfileLevel> levels;
  const auto add = [&levels](double z, double d) {
    if (!levels.empty() && z <= levels.back().z) return;  // a corner shared by two parts
    levels.push_back({z, d});
  };
  if (e.bottom > 0.0) {
    const double r = e.bottom;
    const int n = steps(r);
    for (int k = 0; k <= n; ++k) {
      const double phi = 0.5 * M_PI * k / n;
      add(k == n ? r : r - r * std::cos(phi), k == n ? 0.0 : r - r * std::sin(phi));
    }
  } else {
    add(0.0, 0.0);
  }
  if (e.top > 0.0) {
    const double r = e.top;
    add(t - r, 0.0);
    if (e.chamfer) {
      add(t, r);
    } else {
      const int n = steps(r);
      for (int k = 1; k <= n; ++k) {
        const double theta = 0.5 * M_PI * k / n;
        add(k == n ? t : t - r + r * std::sin(theta), k == n ? r : r - r * std::cos(theta));
      }
    }
  } else {
    add(t, 0.0);
  }
  if (sagitta != nullptr) *sagitta = worst;
  return levels;
}

ProfileMoments profile_moments(const EdgeProfile& profile, double /*thickness*/) {
  const ProfileEdges e = profile_edges(profile);
  ProfileMoments m;
  const auto round = [&m](double r) {
    m.area += r * r * (1.0 - 0.25 * M_PI);
    m.square += r * r * r * (5.0 / 3.0 - 0.5 * M_PI);
  };
  if (e.chamfer) {
    m.area += 0.5 * e.top * e.top;
    m.square += e.top * e.top * e.top / 3.0;
  } else if (e.top > 0.0) {
    round(e.top);
  }
  if (e.bottom > 0.0) round(e.bottom);
  return m;
}

namespace {

Vec2 left_normal(const Vec2& u) { return {-u.y(), u.x()}; }
Vec2 rotated(const Vec2& v, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

// Where the eroded plan's boundary runs past vertex v of the plan, as a
// function of the inset d: one point (a mitre, or where an exposed edge's
// offset meets its unprofiled neighbour), or an arc of radius d about v
// from direction `from` clockwise through `sweep` radians in `pieces`
// chords (a reflex corner, or the rounded end of an exposed run).
struct CornerRule {
  enum class Kind { Fixed, Point, Arc } kind = Kind::Fixed;
  Vec2 v{0.0, 0.0};
  Vec2 along{0.0, 0.0};  ///< Point: the point is v + d * along
  Vec2 from{0.0, 0.0};   ///< Arc
  double sweep = 0.0;
  int pieces = 0;
  std::size_t count() const { return kind == Kind::Arc ? static_cast<std::size_t>(pieces) + 1 : 1; }
  void emit(double d, std::vector<Vec2>& ring) const {
    if (kind == Kind::Fixed) {
      ring.push_back(v);
    } else if (kind == Kind::Point) {
      ring.push_back(v + d * along);
    } else {
      for (int k = 0; k <= pieces; ++k) ring.push_back(v + d * rotated(from, -sweep * k / pieces));
    }
  }
};

// The clockwise angle from unit vector a to unit vector b, in [0, 2 pi).
double clockwise(const Vec2& a, const Vec2& b) {
  double angle = -std::atan2(cross2(a, b), a.dot(b));
  if (angle < 0.0) angle += 2.0 * M_PI;
  return angle;
}

CornerRule corner_rule(const Vec2& prev, const Vec2& v, const Vec2& next, bool a_exposed, bool b_exposed,
                       double d_max, double tolerance) {
  CornerRule rule;
  rule.v = v;
  if (!a_exposed && !b_exposed) return rule;
  const Vec2 ua = (v - prev).normalized(), ub = (next - v).normalized();
  const Vec2 na = left_normal(ua), nb = left_normal(ub);
  const double c = cross2(ua, ub);
  const auto arc = [&](const Vec2& from, const Vec2& to) {
    rule.kind = CornerRule::Kind::Arc;
    rule.from = from;
    rule.sweep = clockwise(from, to);
    const double step = tolerance >= d_max ? 0.5 * M_PI : 2.0 * std::acos(1.0 - tolerance / d_max);
    rule.pieces = std::max(1, static_cast<int>(std::ceil(rule.sweep / step)));
  };
  const auto point = [&](const Vec2& along) {
    rule.kind = CornerRule::Kind::Point;
    rule.along = along;
  };
  if (a_exposed && b_exposed) {
    // Both offset: their lines meet at the mitre of a convex (or straight)
    // corner; round a reflex one every point within d of v is taken.
    if (c >= 0.0)
      point((na + nb) / (1.0 + na.dot(nb)));
    else
      arc(na, nb);
  } else if (a_exposed) {
    // Edge a's offset meets edge b where b turns back over a (90 degrees or
    // more); otherwise the points nearest a are round its end v.
    if (c > 0.0 && ua.dot(ub) <= 0.0)
      point(ub / c);
    else
      arc(na, ub);
  } else {
    if (c > 0.0 && ua.dot(ub) <= 0.0)
      point(-ua / c);
    else
      arc(-ua, nb);
  }
  return rule;
}

// Mesh vertex ids of a ring's points: consecutive equal points (an arc
// shrunk to its centre where the inset is 0) share one.
std::vector<std::uint32_t> ring_ids(const std::vector<Vec2>& ring, double z, TriangleSoup& mesh) {
  std::vector<std::uint32_t> ids(ring.size());
  for (std::size_t k = 0; k < ring.size(); ++k) {
    if (k > 0 && ring[k] == ring[k - 1]) {
      ids[k] = ids[k - 1];
      continue;
    }
    ids[k] = static_cast<std::uint32_t>(mesh.vertices.size());
    mesh.vertices.emplace_back(ring[k].x(), ring[k].y(), z);
  }
  for (std::size_t k = ring.size(); k-- > 1 && ring[k] == ring.front();) ids[k] = ids.front();
  return ids;
}

std::vector<Vec2> distinct(const std::vector<Vec2>& ring) {
  std::vector<Vec2> out;
  for (const Vec2& p : ring) {
    if (out.empty() || p != out.back()) out.push_back(p);
  }
  while (out.size() > 1 && out.back() == out.front()) out.pop_back();
  return out;
}

// The wall between two loops of ids (lower, upper) running with the solid
// on their left: two triangles per step, less those a shared id flattens.
void wall(const std::vector<std::uint32_t>& lo, const std::vector<std::uint32_t>& up, TriangleSoup& mesh) {
  const std::size_t n = lo.size();
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t l = (k + 1) % n;
    const std::array<std::uint32_t, 3> first{lo[k], lo[l], up[l]}, second{lo[k], up[l], up[k]};
    for (const auto& t : {first, second}) {
      if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) mesh.triangles.push_back(t);
    }
  }
}

}  // namespace

ProfiledSlab build_profiled_slab(const ProfiledPlan& plan, const EdgeProfile& profile, double thickness,
                                 double tolerance, std::size_t max_triangles) {
  const std::size_t n = plan.outer.size();
  if (n < 3 || plan.exposed.size() != n)
    throw std::invalid_argument("build_profiled_slab: a loop of 3 or more points and a flag per edge");
  ProfiledSlab out;
  const std::vector<ProfileLevel> levels = profile_levels(profile, thickness, tolerance, &out.sagitta);
  double d_max = 0.0;
  for (const ProfileLevel& l : levels) d_max = std::max(d_max, l.inset);
  std::vector<CornerRule> rules;
  std::size_t ring_size = 0;
  for (std::size_t i = 0; i < n; ++i) {
    rules.push_back(corner_rule(plan.outer[(i + n - 1) % n], plan.outer[i], plan.outer[(i + 1) % n],
                                plan.exposed[(i + n - 1) % n], plan.exposed[i], d_max, tolerance));
    ring_size += rules.back().count();
  }
  const std::size_t hole_points = [&] {
    std::size_t s = 0;
    for (const auto& h : plan.holes) s += h.size();
    return s;
  }();
  // Walls (two per ring step and hole edge) and about two faces' worth per outline point.
  const std::size_t estimate =
      2 * (levels.size() - 1) * ring_size + 2 * hole_points + 2 * (ring_size + hole_points);
  require_within_budget(
      estimate, max_triangles,
      [&] { return fmt::format("the profiled slab needs about {} triangles", estimate); },
      "raise max_triangles or the tolerance");
  TriangleSoup& mesh = out.mesh;
  std::vector<std::vector<std::uint32_t>> rings;
  std::vector<Vec2> top, bottom;
  for (std::size_t j = 0; j < levels.size(); ++j) {
    std::vector<Vec2> ring;
    ring.reserve(ring_size);
    for (const CornerRule& r : rules) r.emit(levels[j].inset, ring);
    if (levels[j].inset > 0.0) {
      // The eroded plan must stay one simple loop clear of the cut-outs.
      std::vector<std::vector<Vec2>> loops{distinct(ring)};
      loops.insert(loops.end(), plan.holes.begin(), plan.holes.end());
      const std::optional<EdgeCrossing> crossing = find_crossing(loops);
      if (crossing || signed_area2(loops[0]) <= 0.0) {
        const Vec2 at = crossing ? crossing->where : loops[0].front();
        throw GeometryError(
            ErrorLocation{"edges.radius", {}, {at.x(), at.y()}},
            fmt::format(
                "{}: the {} profile does not fit: {} in from the exposed edges at height {:.6g} its "
                "face {} near ({:.6g}, {:.6g}); take a smaller radius or move the cut-out",
                plan.name, to_string(profile.kind), fmt::format("{:.6g}", levels[j].inset), levels[j].z,
                crossing && crossing->second >= loops[0].size() ? "meets a cut-out" : "crosses itself",
                at.x(), at.y()));
      }
    }
    if (j == 0) bottom = distinct(ring);
    if (j + 1 == levels.size()) top = distinct(ring);
    rings.push_back(ring_ids(ring, levels[j].z, mesh));
  }
  out.levels = rings.size();
  for (std::size_t j = 0; j + 1 < rings.size(); ++j) wall(rings[j], rings[j + 1], mesh);
  // The holes: vertical walls from the bottom to the top.
  std::vector<std::vector<std::uint32_t>> hole_bottom, hole_top;
  for (const auto& h : plan.holes) {
    hole_bottom.push_back(ring_ids(h, 0.0, mesh));
    hole_top.push_back(ring_ids(h, thickness, mesh));
    wall(hole_bottom.back(), hole_top.back(), mesh);
  }
  // Top and bottom: the rings' constrained Delaunay triangulations with the
  // holes, their points found again by value (no point is added).
  const auto face = [&](const std::vector<Vec2>& outer, const std::vector<std::uint32_t>& outer_ids,
                        const std::vector<std::vector<std::uint32_t>>& holes_ids, bool up) {
    std::map<std::pair<double, double>, std::uint32_t> id_of;
    for (const std::uint32_t id : outer_ids)
      id_of.emplace(std::make_pair(mesh.vertices[id].x(), mesh.vertices[id].y()), id);
    for (const auto& ids : holes_ids) {
      for (const std::uint32_t id : ids)
        id_of.emplace(std::make_pair(mesh.vertices[id].x(), mesh.vertices[id].y()), id);
    }
    Region2 region;
    region.outer = outer;
    region.holes = plan.holes;
    const PlanarTriangulation t = triangulate(region);
    std::vector<std::uint32_t> ids(t.vertices.size());
    for (std::size_t k = 0; k < t.vertices.size(); ++k) {
      const auto found = id_of.find({t.vertices[k].x(), t.vertices[k].y()});
      if (found == id_of.end())
        throw std::logic_error("build_profiled_slab: the face's triangulation added a point");
      ids[k] = found->second;
    }
    for (const auto& tri : t.triangles) {
      if (up)
        mesh.triangles.push_back({ids[tri[0]], ids[tri[1]], ids[tri[2]]});
      else
        mesh.triangles.push_back({ids[tri[0]], ids[tri[2]], ids[tri[1]]});
    }
  };
  face(bottom, rings.front(), hole_bottom, false);
  face(top, rings.back(), hole_top, true);
  return out;
}

}  // namespace fabmesh
