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

using VertexIndex = std::map<std::pair<double, double>, std::uint32_t>;

// Triangulates `region` (CGAL, no points added) into `soup`: every vertex of
// the triangulation is one of the soup's, found by its plane coordinates in
// `index`; `reversed` flips the triangles. `what` names the face in errors.
void append_triangulation(TriangleSoup& soup, const Region2& region, const VertexIndex& index, bool reversed,
                          const char* what) {
  if (const auto c = find_crossing(region_loops(region))) {
    throw std::logic_error(
        fmt::format("{}: the key circles meet the face near ({}, {})", what, c->where.x(), c->where.y()));
  }
  const PlanarTriangulation t = triangulate(region);
  if (t.steiner_points != 0) throw std::logic_error(fmt::format("{}: the triangulation added points", what));
  std::vector<std::uint32_t> to_soup(t.vertices.size());
  for (std::size_t i = 0; i < t.vertices.size(); ++i) {
    const auto it = index.find({t.vertices[i].x(), t.vertices[i].y()});
    if (it == index.end())
      throw std::logic_error(fmt::format("{}: a triangulation vertex is not a face vertex", what));
    to_soup[i] = it->second;
  }
  for (const auto& f : t.triangles) {
    const std::uint32_t a = to_soup[f[0]], b = to_soup[f[1]], c = to_soup[f[2]];
    soup.triangles.push_back(reversed ? std::array<std::uint32_t, 3>{a, c, b}
                                      : std::array<std::uint32_t, 3>{a, b, c});
  }
}

// Triangulates the section at one end with a hole per key (radius `key_r`),
// appends the cap (end cap: reversed, normal +e_theta) and returns each key's
// base circle as soup indices (counter-clockwise in (r, z)).
std::vector<std::vector<std::uint32_t>> append_cap(TriangleSoup& soup, const std::vector<Vec2>& loop,
                                                   const std::vector<std::uint32_t>& ring, const Vec2& dir,
                                                   const KeyLayout& keys, double key_r, bool end_cap) {
  VertexIndex index;
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
  append_triangulation(soup, region, index, end_cap, "mould cap");
  return circles;
}

// A key's hemisphere over its circle (already in the part's soup), recorded as a feature.
void add_feature(MouldPart& part, const std::vector<std::uint32_t>& circle, const Hemisphere& h,
                 std::size_t key, bool bump, bool on_base) {
  const std::size_t first_new = part.soup.vertices.size();
  append_hemisphere(part.soup, circle, h, bump);
  KeyFeature f;
  f.key = key;
  f.bump = bump;
  f.on_base = on_base;
  f.centre = h.centre;
  f.axis = h.axis;
  f.radius = h.radius;
  f.vertices = circle;
  for (std::size_t v = first_new; v < part.soup.vertices.size(); ++v)
    f.vertices.push_back(static_cast<std::uint32_t>(v));
  part.keys.push_back(std::move(f));
}

void add_features(MouldPart& part, const std::vector<std::vector<std::uint32_t>>& circles,
                  const KeyLayout& keys, const Vec2& dir, bool bump) {
  for (std::size_t i = 0; i < circles.size(); ++i) {
    Hemisphere h;
    const Vec2& c = keys.centres[i];
    h.centre = Vec3(c.x() * dir.x(), c.x() * dir.y(), c.y());
    h.u = Vec3(dir.x(), dir.y(), 0.0);
    h.w = Vec3(0.0, 0.0, 1.0);
    h.axis = Vec3(-dir.y(), dir.x(), 0.0);  // +e_theta: out of the part at its end, into it at its start
    h.radius = bump ? keys.radius : keys.socket_radius;
    add_feature(part, circles[i], h, i, bump, false);
  }
}

// A base key's hemisphere: its circle in the plane z = `z` about (x, y) = `c`,
// its axis up (out of the base's top, into a side part's bottom). The base
// circle runs centre + radius (cos a u + sin a w) with u x w = -axis, as the
// split planes' keys do, so the same stitching holds.
Hemisphere flat_hemisphere(const Vec2& c, double z, double radius) {
  Hemisphere h;
  h.centre = Vec3(c.x(), c.y(), z);
  h.u = Vec3(0.0, 1.0, 0.0);
  h.w = Vec3(1.0, 0.0, 0.0);
  h.axis = Vec3(0.0, 0.0, 1.0);
  h.radius = radius;
  return h;
}

// The flat face of the base cut between the open edge's two rings, `outer`
// on the block's outline and `inner` on the cavity, sample by sample: the
// whole annulus (closed) or a side part's sector; a hole per key circle of
// `key_r` about each of `centres` (none when empty). Normal up (the base's
// top) or down (a side part's bottom). Returns each key's circle as soup
// indices, in flat_hemisphere's order.
std::vector<std::vector<std::uint32_t>> append_flat_face(TriangleSoup& soup,
                                                         const std::vector<std::uint32_t>& outer,
                                                         const std::vector<std::uint32_t>& inner, bool closed,
                                                         const std::vector<Vec2>& centres, double key_r,
                                                         int segments, bool up) {
  VertexIndex index;
  const double z = soup.vertices[outer.front()].z();
  auto xy = [&](std::uint32_t v) {
    Vec2 p(soup.vertices[v].x(), soup.vertices[v].y());
    index[{p.x(), p.y()}] = v;
    return p;
  };
  Region2 region;
  for (const std::uint32_t v : outer) region.outer.push_back(xy(v));
  std::vector<Vec2> in;
  for (auto v = inner.rbegin(); v != inner.rend(); ++v) in.push_back(xy(*v));
  if (closed) {
    region.holes.push_back(in);  // clockwise: the cavity's ring walked back
  } else {
    region.outer.insert(region.outer.end(), in.begin(), in.end());
  }
  region.area = 0.5 * signed_area2(region.outer);
  if (closed) region.area += 0.5 * signed_area2(in);
  std::vector<std::vector<std::uint32_t>> circles;
  for (const Vec2& c : centres) {
    const Hemisphere h = flat_hemisphere(c, z, key_r);
    std::vector<Vec2> pts;
    std::vector<std::uint32_t> idx;
    for (int k = 0; k < segments; ++k) {
      const double a = kTwoPi * k / segments;
      const Vec3 p = h.centre + key_r * (std::cos(a) * h.u + std::sin(a) * h.w);
      idx.push_back(static_cast<std::uint32_t>(soup.vertices.size()));
      soup.vertices.emplace_back(p.x(), p.y(), z);
      pts.push_back(xy(idx.back()));
    }
    circles.push_back(std::move(idx));
    region.area += 0.5 * signed_area2(pts);  // clockwise (u x w = -z): a hole as it is
    region.holes.push_back(std::move(pts));
  }
  append_triangulation(soup, region, index, !up, "mould base cut");
  return circles;
}

// The base keys whose centres lie within a part's angular range.
std::vector<std::size_t> base_keys_within(const KeyLayout& keys, double from, double to) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < keys.base_centres.size(); ++i) {
    double a = std::atan2(keys.base_centres[i].y(), keys.base_centres[i].x());
    while (a < from) a += kTwoPi;
    if (a < to) out.push_back(i);
  }
  return out;
}

void check_budget(std::size_t triangles, std::size_t budget, const std::string& name) {
  require_within_budget(
      triangles, budget, [&] { return fmt::format("mould part {} needs {} triangles", name, triangles); },
      "raise max_triangles or the tolerance");
}

std::size_t key_triangles(const KeyLayout& keys, std::size_t count) {
  const auto n = static_cast<std::size_t>(keys.segments);
  const auto rings = static_cast<std::size_t>(hemisphere_rings(keys.segments));
  return count * (2 * n * (rings - 1) + n + 2 * n);  // hemisphere + cap triangles around it
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
  const std::vector<std::size_t> base_keys = base_keys_within(keys, part.from_angle, part.to_angle);
  SweepSection side = section.side;
  if (!keys.base_centres.empty()) side.open_edge = side.loop.size() - 1;  // its bottom: from the cavity out
  const std::size_t estimate = swept_triangle_count(side, samples.angles.size(), false) +
                               2 * side.loop.size() + 2 * key_triangles(keys, keys.centres.size()) +
                               2 * samples.angles.size() + key_triangles(keys, base_keys.size());
  check_budget(estimate, max_triangles, "side");

  SweepPath path;
  path.directions = samples.directions;
  path.outline = samples.outline;
  SweptSurface swept = sweep_section(side, path);
  part.soup = std::move(swept.soup);
  if (!keys.base_centres.empty()) {
    std::vector<Vec2> centres;
    centres.reserve(base_keys.size());
    for (const std::size_t i : base_keys) centres.push_back(keys.base_centres[i]);
    const auto circles = append_flat_face(part.soup, swept.open_to, swept.open_from, false, centres,
                                          keys.socket_radius, keys.segments, false);
    for (std::size_t i = 0; i < circles.size(); ++i) {
      add_feature(part, circles[i], flat_hemisphere(centres[i], section.z_cut, keys.socket_radius),
                  base_keys[i], false, true);
    }
  }
  const std::vector<Vec2> start = section_at(section.side, options.block, samples.outline.front());
  const std::vector<Vec2> end = section_at(section.side, options.block, samples.outline.back());
  const auto sockets =
      append_cap(part.soup, start, swept.first, from.direction, keys, keys.socket_radius, false);
  const auto bumps = append_cap(part.soup, end, swept.last, to.direction, keys, keys.radius, true);
  add_features(part, sockets, keys, from.direction, false);
  add_features(part, bumps, keys, to.direction, true);
  return part;
}

MouldPart build_base_part(const MouldSection& section, const KeyLayout& keys, const MouldOptions& options,
                          double max_step, std::size_t max_triangles) {
  MouldPart part;
  part.name = "base";
  part.kind = MouldPartKind::Base;
  part.to_angle = kTwoPi;
  const SplitPlane zero = split_plane(0, 1);
  const AngularSamples samples =
      angular_samples(zero, zero, true, options.block, section.block_radius, max_step);
  part.angular_steps = samples.angles.size();
  SweepSection base = section.base;
  if (!keys.base_centres.empty()) {
    base.open_edge = 2;  // its top: from the block in to the cavity (mould_section.h)
    if (base.loop[3].x() == 0.0) {
      // The cut runs along a flat floor to the axis: the top's disc keeps its fan about the axis out to
      // halfway to the keys, and the flat face with the keys is the annulus beyond.
      double reach = section.block_radius;
      for (const Vec2& c : keys.base_centres) reach = std::min(reach, c.norm() - keys.radius);
      base.loop.insert(base.loop.begin() + 3, Vec2(0.5 * reach, section.z_cut));
      base.on_outline.insert(base.on_outline.begin() + 3, 0);
    }
  }
  check_budget(swept_triangle_count(base, samples.angles.size(), true) + 2 * samples.angles.size() +
                   key_triangles(keys, keys.base_centres.size()),
               max_triangles, "base");
  SweepPath path;
  path.directions = samples.directions;
  path.outline = samples.outline;
  path.closed = true;
  SweptSurface swept = sweep_section(base, path);
  part.soup = std::move(swept.soup);
  if (!keys.base_centres.empty()) {
    const auto circles = append_flat_face(part.soup, swept.open_from, swept.open_to, true, keys.base_centres,
                                          keys.radius, keys.segments, true);
    for (std::size_t i = 0; i < circles.size(); ++i) {
      add_feature(part, circles[i], flat_hemisphere(keys.base_centres[i], section.z_cut, keys.radius), i,
                  true, true);
    }
  }
  return part;
}

}  // namespace fabmesh
