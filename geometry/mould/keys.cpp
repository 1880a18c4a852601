#include "geometry/mould/keys.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/core/errors.h"
#include "geometry/mesh/revolve.h"

namespace fabmesh {
namespace {

std::string at(const Vec2& p) { return fmt::format("(r {:.6g}, z {:.6g})", p.x(), p.y()); }

// The point of segment ab nearest to p.
Vec2 nearest_on_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return a + t * ab;
}

// Distance from p to a polyline (closed: polygon) and the nearest point on it.
double polyline_distance(const Vec2& p, const std::vector<Vec2>& pts, bool closed, Vec2* nearest) {
  double d = std::numeric_limits<double>::infinity();
  const std::size_t n = pts.size(), edges = closed ? n : n - 1;
  for (std::size_t i = 0; i < edges; ++i) {
    const Vec2 q = nearest_on_segment(p, pts[i], pts[(i + 1) % n]);
    if ((p - q).norm() < d) {
      d = (p - q).norm();
      *nearest = q;
    }
  }
  return d;
}

// Crossing-number test; the callers also require a positive distance to the boundary.
bool inside(const Vec2& p, const std::vector<Vec2>& loop) {
  bool in = false;
  for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++) {
    const Vec2 &a = loop[i], &b = loop[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y())) {
      in = !in;
    }
  }
  return in;
}

// `keys` centres midway between the cavity and the block, spread evenly up the side section's height
// after keeping `edge` (socket radius + margin + sagitta) from its bottom and top.
std::vector<Vec2> default_centres(const MouldSection& s, int keys, double edge) {
  const double r = 0.5 * (s.cavity_radius + s.block_radius);
  const double lo = (s.has_cut ? s.z_cut : s.z_bottom) + edge, hi = s.z_top - edge;
  std::vector<Vec2> out;
  out.reserve(static_cast<std::size_t>(std::max(keys, 0)));
  for (int i = 0; i < keys; ++i) out.emplace_back(r, lo + (i + 0.5) * (hi - lo) / keys);
  return out;
}

// One key per side part on the base cut, at the part's bisector, midway across the plaster of the cut
// (between the cavity's widest point on the cut and the block); every socket keeps `need` from the
// cavity above and below the cut, from the block and from the split planes.
void place_base_keys(KeyLayout& k, const MouldSection& s, const MouldOptions& o, double need) {
  const double inner = std::max(s.side_cavity.back().x(), s.base_cavity.front().x()) + s.max_deviation;
  const double r = 0.5 * (inner + s.block_radius);
  const Vec2 c(r, s.z_cut);
  Vec2 near_side, near_base;
  const double to_side = polyline_distance(c, s.side_cavity, false, &near_side) - s.max_deviation;
  const double to_base = polyline_distance(c, s.base_cavity, false, &near_base) - s.max_deviation;
  const double to_block = s.block_radius - r;
  const double to_split = r * std::sin(M_PI / o.parts);
  const double clearance = std::min({to_side, to_base, to_block, to_split});
  if (clearance < need) {
    const std::string what =
        clearance == to_block ? "the block"
        : clearance == to_split
            ? "the split planes"
            : fmt::format("the cavity near {}", at(clearance == to_side ? near_side : near_base));
    throw GeometryError(
        "key_radius",
        fmt::format("the base part's keys (one per side part on the base cut z = {:.6g}, at radius {:.6g} "
                    "midway across the plaster): a socket (radius {:.6g} = key_radius {} + key_clearance {}) "
                    "comes within {:.6g} of {}; keys need {:.6g} (key_margin + mesh sagitta) of plaster "
                    "around them: use a smaller key_radius, a thicker wall, or keys: 0",
                    s.z_cut, r, k.socket_radius, o.key_radius, o.key_clearance, clearance - k.socket_radius,
                    what, need - k.socket_radius));
  }
  for (int part = 0; part < o.parts; ++part) {
    const double angle = 2.0 * M_PI * (part + 0.5) / o.parts;
    k.base_centres.emplace_back(r * std::cos(angle), r * std::sin(angle));
    k.base_clearances.push_back(clearance - k.socket_radius);
  }
}

}  // namespace

KeyLayout place_keys(const MouldSection& s, const MouldOptions& o, double sagitta) {
  KeyLayout k;
  k.radius = o.key_radius;
  k.socket_radius = o.key_radius + o.key_clearance;
  const double margin = o.key_margin > 0.0 ? o.key_margin : 0.5 * o.key_radius;
  const double need = k.socket_radius + margin + sagitta;
  k.centres = o.key_positions.empty() ? default_centres(s, o.keys, need) : o.key_positions;
  if (k.centres.empty()) return k;
  // Circle sagitta <= tolerance / 2 keeps every hemisphere face within the tolerance (keys.h).
  k.segments = std::max(8, angular_segments(k.socket_radius, 0.5 * o.tolerance));
  for (std::size_t i = 0; i < k.centres.size(); ++i) {
    const Vec2& c = k.centres[i];
    const std::string where = fmt::format("keys[{}]", i);
    if (!std::isfinite(c.x()) || !std::isfinite(c.y())) {
      throw GeometryError(where, fmt::format("{} at {} is not a finite point", where, at(c)));
    }
    if (!inside(c, s.side.loop)) {
      throw GeometryError(
          where, fmt::format("{} at {} is not inside the side parts' section (plaster between "
                             "the cavity and the block, r in [0, {:.6g}], z in [{:.6g}, {:.6g}])",
                             where, at(c), s.block_radius, s.has_cut ? s.z_cut : s.z_bottom, s.z_top));
    }
    Vec2 near_cavity, near_any;
    const double to_cavity = polyline_distance(c, s.side_cavity, false, &near_cavity) - s.max_deviation;
    const double to_any = polyline_distance(c, s.side.loop, true, &near_any);
    const double clearance = std::min(to_cavity, to_any);
    if (clearance < need) {
      const bool cavity = to_cavity <= to_any;
      throw GeometryError(
          where,
          fmt::format("{} at {}: its socket (radius {:.6g} = key_radius {} + key_clearance {}) comes within "
                      "{:.6g} of the {} near {}; keys need key_margin {:.6g} (+ mesh sagitta {:.3g}) of "
                      "plaster around them",
                      where, at(c), k.socket_radius, o.key_radius, o.key_clearance,
                      clearance - k.socket_radius,
                      cavity ? "cavity" : (s.has_cut ? "block's or the base cut's edge" : "block's edge"),
                      at(cavity ? near_cavity : near_any), margin, sagitta));
    }
    for (std::size_t j = 0; j < i; ++j) {
      const double gap = (c - k.centres[j]).norm() - 2.0 * k.socket_radius;
      if (gap < margin) {
        throw GeometryError(where,
                            fmt::format("{} at {}: its socket comes within {:.6g} (negative: overlaps) "
                                        "of the socket of keys[{}] at {}; keys need key_margin {:.6g} "
                                        "between them (use fewer keys or a smaller key_radius)",
                                        where, at(c), gap, j, at(k.centres[j]), margin));
      }
    }
    k.clearances.push_back(clearance - k.socket_radius);
  }
  if (s.has_cut) place_base_keys(k, s, o, need);
  return k;
}

int hemisphere_rings(int segments) { return std::max(2, (segments + 3) / 4); }

void append_hemisphere(TriangleSoup& soup, const std::vector<std::uint32_t>& base_ring, const Hemisphere& h,
                       bool flip) {
  const int n = static_cast<int>(base_ring.size());
  const int rings = hemisphere_rings(n);
  std::vector<std::vector<std::uint32_t>> ring{base_ring};
  for (int i = 1; i < rings; ++i) {
    const double beta = 0.5 * M_PI * (1.0 - static_cast<double>(i) / rings);  // polar angle from the axis
    std::vector<std::uint32_t> idx;
    for (int k = 0; k < n; ++k) {
      const double a = 2.0 * M_PI * k / n;
      idx.push_back(static_cast<std::uint32_t>(soup.vertices.size()));
      soup.vertices.push_back(
          h.centre +
          h.radius * (std::sin(beta) * (std::cos(a) * h.u + std::sin(a) * h.w) + std::cos(beta) * h.axis));
    }
    ring.push_back(std::move(idx));
  }
  const auto apex = static_cast<std::uint32_t>(soup.vertices.size());
  soup.vertices.push_back(h.centre + h.radius * h.axis);
  auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    soup.triangles.push_back(flip ? std::array<std::uint32_t, 3>{a, c, b}
                                  : std::array<std::uint32_t, 3>{a, b, c});
  };
  for (int i = 0; i + 1 < rings; ++i) {
    for (int k = 0; k < n; ++k) {
      const int k1 = (k + 1) % n;
      add(ring[i][k], ring[i][k1], ring[i + 1][k1]);
      add(ring[i][k], ring[i + 1][k1], ring[i + 1][k]);
    }
  }
  for (int k = 0; k < n; ++k) add(ring[rings - 1][k], ring[rings - 1][(k + 1) % n], apex);
}

}  // namespace fabmesh
