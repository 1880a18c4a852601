#include "geometry/mould/mould_part.h"

#include <fmt/format.h>

#include <cmath>
#include <map>

#include "geometry/core/budget.h"
#include "geometry/core/errors.h"
#include "geometry/mesh/halfedge_mesh.h"
#include "geometry/mesh/sweep.h"
#include "geometry/section/simple_polygon.h"
#include "geometry/section/triangulate.h"

namespace fabmesh {
namespace {

constexpr double kTwoPi = 2.0 * M_PI;

// The box's outline point in direction d: on the side |x| = W or |y| = W that the ray meets.
Vec2 box_point(const Vec2& d, double w) {
  if (std::abs(d.x()) >= std::abs(d.y())) return {std::copysign(w, d.x()), w * d.y() / std::abs(d.x())};
  return {w * d.x() / std::abs(d.y()), std::copysign(w, d.y())};
}

// The section as it lies in the half-plane at one sample: a box's outline vertices at the outline's radius.
std::vector<Vec2> section_at(const SweepSection& s, BlockShape block, const Vec2& outline) {
  std::vector<Vec2> loop = s.loop;
  if (block != BlockShape::Box) return loop;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    if (s.on_outline[i]) loop[i].x() = outline.norm();
  }
  return loop;
}

std::vector<Vec2> circle(const Vec2& c, double radius, int n) {
  std::vector<Vec2> pts;
  for (int k = 0; k < n; ++k) {
    const double a = kTwoPi * k / n;
    pts.push_back(c + radius * Vec2(std::cos(a), std::sin(a)));
  }
  return pts;
}

// Triangulates the section at one end with a hole per key (radius `key_r`),
// appends the cap (end cap: reversed, normal +e_theta) and returns each key's
// base circle as soup indices (counter-clockwise in (r, z)).
std::vector<std::vector<std::uint32_t>> append_cap(TriangleSoup& soup, const std::vector<Vec2>& loop,
                                                   const std::vector<std::uint32_t>& ring, const Vec2& dir,
                                                   const KeyLayout& keys, double key_r, bool end_cap) {
  std::map<std::pair<double, double>, std::uint32_t> index;
  for (std::size_t i = 0; i < loop.size(); ++i) index[{loop[i].x(), loop[i].y()}] = ring[i];
  Region2 region;
  region.outer = loop;
  region.area = 0.5 * signed_area2(loop);
  std::vector<std::vector<std::uint32_t>> circles;
  for (const Vec2& c : keys.centres) {
    std::vector<Vec2> pts = circle(c, key_r, keys.segments);
    std::vector<std::uint32_t> idx;
    for (const Vec2& p : pts) {
      idx.push_back(static_cast<std::uint32_t>(soup.vertices.size()));
      index[{p.x(), p.y()}] = idx.back();
      soup.vertices.emplace_back(p.x() * dir.x(), p.x() * dir.y(), p.y());
    }
    circles.push_back(std::move(idx));
    region.area -= 0.5 * signed_area2(pts);
    region.holes.emplace_back(pts.rbegin(), pts.rend());  // holes run clockwise
  }
  if (const auto c = find_crossing(region_loops(region))) {
    throw std::logic_error(
        fmt::format("mould cap: the key circles meet the section near ({}, {})", c->where.x(), c->where.y()));
  }
  const PlanarTriangulation t = triangulate(region);
  if (t.steiner_points != 0) throw std::logic_error("mould cap: the triangulation added points");
  std::vector<std::uint32_t> to_soup(t.vertices.size());
  for (std::size_t i = 0; i < t.vertices.size(); ++i) {
    const auto it = index.find({t.vertices[i].x(), t.vertices[i].y()});
    if (it == index.end())
      throw std::logic_error("mould cap: a triangulation vertex is not a section vertex");
    to_soup[i] = it->second;
  }
  for (const auto& f : t.triangles) {
    const std::uint32_t a = to_soup[f[0]], b = to_soup[f[1]], c = to_soup[f[2]];
    soup.triangles.push_back(end_cap ? std::array<std::uint32_t, 3>{a, c, b}
                                     : std::array<std::uint32_t, 3>{a, b, c});
  }
  return circles;
}

void add_features(MouldPart& part, const std::vector<std::vector<std::uint32_t>>& circles,
                  const KeyLayout& keys, const Vec2& dir, bool bump) {
  const double radius = bump ? keys.radius : keys.socket_radius;
  for (std::size_t i = 0; i < circles.size(); ++i) {
    Hemisphere h;
    const Vec2& c = keys.centres[i];
    h.centre = Vec3(c.x() * dir.x(), c.x() * dir.y(), c.y());
    h.u = Vec3(dir.x(), dir.y(), 0.0);
    h.w = Vec3(0.0, 0.0, 1.0);
    h.axis = Vec3(-dir.y(), dir.x(), 0.0);  // +e_theta: out of the part at its end, into it at its start
    h.radius = radius;
    const std::size_t first_new = part.soup.vertices.size();
    append_hemisphere(part.soup, circles[i], h, bump);
    KeyFeature f;
    f.key = i;
    f.bump = bump;
    f.centre = h.centre;
    f.axis = h.axis;
    f.radius = radius;
    f.vertices = circles[i];
    for (std::size_t v = first_new; v < part.soup.vertices.size(); ++v)
      f.vertices.push_back(static_cast<std::uint32_t>(v));
    part.keys.push_back(std::move(f));
  }
}

void check_budget(std::size_t triangles, std::size_t budget, const std::string& name) {
  require_within_budget(
      triangles, budget, [&] { return fmt::format("mould part {} needs {} triangles", name, triangles); },
      "raise max_triangles or the tolerance");
}

std::size_t key_triangles(const KeyLayout& keys) {
  const auto n = static_cast<std::size_t>(keys.segments);
  const auto rings = static_cast<std::size_t>(hemisphere_rings(keys.segments));
  return keys.centres.size() * (2 * n * (rings - 1) + n + 2 * n);  // hemisphere + cap triangles around it
}

}  // namespace

SplitPlane split_plane(int k, int parts) {
  SplitPlane p;
  k %= parts;
  p.angle = kTwoPi * k / parts;
  if ((4 * k) % parts == 0) {
    const Vec2 quarter[4] = {{1.0, 0.0}, {0.0, 1.0}, {-1.0, 0.0}, {0.0, -1.0}};
    p.direction = quarter[(4 * k / parts) % 4];
  } else {
    p.direction = Vec2(std::cos(p.angle), std::sin(p.angle));
  }
  return p;
}

AngularSamples angular_samples(const SplitPlane& from, const SplitPlane& to, bool closed, BlockShape block,
                               double block_radius, double max_step) {
  const double end = closed ? from.angle + kTwoPi : (to.angle > from.angle ? to.angle : to.angle + kTwoPi);
  std::vector<double> breaks{from.angle};
  if (block == BlockShape::Box) {
    for (int q = -4; q < 12; ++q) {
      const double corner = M_PI / 4.0 + q * M_PI / 2.0;
      if (corner > from.angle && corner < end) breaks.push_back(corner);
    }
  }
  breaks.push_back(end);
  AngularSamples s;
  auto push = [&](double angle, const Vec2& dir, const Vec2& outline) {
    s.angles.push_back(angle);
    s.directions.push_back(dir);
    s.outline.push_back(outline);
  };
  auto outline_of = [&](const Vec2& d) {
    return block == BlockShape::Box ? box_point(d, block_radius) : Vec2(block_radius * d);
  };
  for (std::size_t b = 0; b + 1 < breaks.size(); ++b) {
    const double t0 = breaks[b], t1 = breaks[b + 1];
    const int steps = std::max(1, static_cast<int>(std::ceil((t1 - t0) / max_step - 1e-9)));
    for (int j = 0; j < steps; ++j) {
      if (b == 0 && j == 0) {
        push(from.angle, from.direction, outline_of(from.direction));
      } else if (j == 0) {  // a box corner: exactly (+-W, +-W)
        const Vec2 d(std::cos(t0), std::sin(t0));
        push(t0, d, Vec2(std::copysign(block_radius, d.x()), std::copysign(block_radius, d.y())));
      } else {
        const double a = t0 + (t1 - t0) * j / steps;
        const Vec2 d(std::cos(a), std::sin(a));
        push(a, d, outline_of(d));
      }
    }
  }
  if (!closed) push(end, to.direction, outline_of(to.direction));
  return s;
}

MouldPart build_side_part(const MouldSection& section, const KeyLayout& keys, const MouldOptions& options,
                          const SplitPlane& from, const SplitPlane& to, double max_step,
                          std::size_t max_triangles) {
  MouldPart part;
  part.kind = MouldPartKind::Side;
  part.from_angle = from.angle;
  part.to_angle = to.angle > from.angle ? to.angle : to.angle + kTwoPi;
  const AngularSamples samples =
      angular_samples(from, to, false, options.block, section.block_radius, max_step);
  part.angular_steps = samples.angles.size() - 1;
  const std::size_t estimate = swept_triangle_count(section.side, samples.angles.size(), false) +
                               2 * section.side.loop.size() + 2 * key_triangles(keys);
  check_budget(estimate, max_triangles, "side");

  SweepPath path;
  path.directions = samples.directions;
  path.outline = samples.outline;
  SweptSurface swept = sweep_section(section.side, path);
  part.soup = std::move(swept.soup);
  const std::vector<Vec2> start = section_at(section.side, options.block, samples.outline.front());
  const std::vector<Vec2> end = section_at(section.side, options.block, samples.outline.back());
  const auto sockets =
      append_cap(part.soup, start, swept.first, from.direction, keys, keys.socket_radius, false);
  const auto bumps = append_cap(part.soup, end, swept.last, to.direction, keys, keys.radius, true);
  add_features(part, sockets, keys, from.direction, false);
  add_features(part, bumps, keys, to.direction, true);
  return part;
}

MouldPart build_base_part(const MouldSection& section, const MouldOptions& options, double max_step,
                          std::size_t max_triangles) {
  MouldPart part;
  part.name = "base";
  part.kind = MouldPartKind::Base;
  part.to_angle = kTwoPi;
  const SplitPlane zero = split_plane(0, 1);
  const AngularSamples samples =
      angular_samples(zero, zero, true, options.block, section.block_radius, max_step);
  part.angular_steps = samples.angles.size();
  check_budget(swept_triangle_count(section.base, samples.angles.size(), true), max_triangles, "base");
  SweepPath path;
  path.directions = samples.directions;
  path.outline = samples.outline;
  path.closed = true;
  part.soup = sweep_section(section.base, path).soup;
  return part;
}

}  // namespace fabmesh
