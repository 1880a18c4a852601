#include "geometry/mould/master_sectors.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <stdexcept>
#include <utility>

#include "geometry/core/errors.h"
#include "geometry/mesh/revolve.h"
#include "geometry/section/region.h"
#include "geometry/section/triangulate.h"
#include "geometry/toolpath/boundary_index.h"

namespace fabmesh {
namespace {

using Index = std::uint32_t;
using Direction = std::array<double, 2>;

/// The unit direction at num / den quarter turns from x: exact at whole
/// quarter turns, where the cut planes are.
Direction quarter_direction(long num, long den) {
  if (num % den == 0) {
    const Vec2 d = quadrant_direction(static_cast<int>(num / den));
    return {d.x(), d.y()};
  }
  const double theta = 0.5 * M_PI * static_cast<double>(num) / static_cast<double>(den);
  return {std::cos(theta), std::sin(theta)};
}

/// The largest radius at which the loop's edges cross height z (0 when none does).
double radius_at(const std::vector<Vec2>& loop, double z) {
  double r = 0.0;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Vec2 &a = loop[i], &b = loop[(i + 1) % loop.size()];
    if ((a.y() - z) * (b.y() - z) > 0.0 || a.y() == b.y()) continue;
    r = std::max(r, a.x() + (z - a.y()) / (b.y() - a.y()) * (b.x() - a.x()));
  }
  return r;
}

/// Distance between segment ab and the rectangle [r0, r1] x [z0, z1]: 0
/// when an end lies in it, else the least distance to its four sides.
double rectangle_distance(const Vec2& a, const Vec2& b, double r0, double r1, double z0, double z1) {
  auto inside = [&](const Vec2& p) { return p.x() >= r0 && p.x() <= r1 && p.y() >= z0 && p.y() <= z1; };
  if (inside(a) || inside(b)) return 0.0;
  const Vec2 corners[4] = {{r0, z0}, {r1, z0}, {r1, z1}, {r0, z1}};
  double d = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 4; ++k) d = std::min(d, segment_distance(a, b, corners[k], corners[(k + 1) % 4]));
  return d;
}

/// The polygon of `sides` points on the circle of `radius` about `centre`, counter-clockwise.
std::vector<Vec2> circle(const Vec2& centre, double radius, int sides) {
  std::vector<Vec2> points;
  for (int k = 0; k < sides; ++k) {
    const double phi = 2.0 * M_PI * k / sides;
    points.emplace_back(centre.x() + radius * std::cos(phi), centre.y() + radius * std::sin(phi));
  }
  return points;
}

/// Appends triangle abc of `soup`, turned so that its normal points along `want`.
void add_facing(TriangleSoup& soup, Index a, Index b, Index c, const Vec3& want) {
  const Vec3 n = (soup.vertices[b] - soup.vertices[a]).cross(soup.vertices[c] - soup.vertices[a]);
  if (n.dot(want) >= 0.0) {
    soup.triangles.push_back({a, b, c});
  } else {
    soup.triangles.push_back({a, c, b});
  }
}

class SectorBuilder {
 public:
  SectorBuilder(const std::vector<Vec2>& loop, const SectorOptions& o, TriangleSoup& soup)
      : loop_(loop), o_(o), soup_(soup) {}

  /// The cap of the loop's vertices at sample j, in direction d, facing
  /// `outward` (d x z for the sector's first cap, its opposite for the
  /// last), with a pin standing out of it or a hole sunk into it at `pin`.
  void cap(const LoopGrid& grid, std::size_t j, const Direction& d, bool first, const Vec2& pin,
           bool is_pin) {
    const Vec3 outward = first ? Vec3(d[1], -d[0], 0.0) : Vec3(-d[1], d[0], 0.0);
    const double radius = is_pin ? o_.pin_radius : o_.hole_radius;
    const std::vector<Vec2> ring2 = circle(pin, radius, o_.pin_sides);
    std::map<std::pair<double, double>, Index> at;
    Region2 region;
    region.outer = loop_;
    for (std::size_t i = 0; i < loop_.size(); ++i)
      at.emplace(std::make_pair(loop_[i].x(), loop_[i].y()), grid.at(i, j));
    std::vector<Index> ring;
    for (const Vec2& p : ring2) {
      ring.push_back(static_cast<Index>(soup_.vertices.size()));
      soup_.vertices.push_back(revolved_point(p, d));
      if (!at.emplace(std::make_pair(p.x(), p.y()), ring.back()).second)
        throw std::logic_error("master sectors: a pin's point on the section's outline");
    }
    region.holes.push_back(std::vector<Vec2>(ring2.rbegin(), ring2.rend()));
    const PlanarTriangulation t = triangulate(region);
    if (t.steiner_points != 0 || t.triangles.size() != loop_.size() + ring2.size())
      throw std::logic_error("master sectors: a cap's triangulation added points");
    for (const auto& tri : t.triangles) {
      std::array<Index, 3> c{};
      for (int e = 0; e < 3; ++e) c[e] = at.at({t.vertices[tri[e]].x(), t.vertices[tri[e]].y()});
      // Counter-clockwise in (radius, height) faces d x z: the first cap's outside.
      if (!first) std::swap(c[1], c[2]);
      soup_.triangles.push_back(c);
    }
    // The pin out along `outward`, or the hole in against it; its far end a fan.
    const Vec3 centre = revolved_point(pin, d);
    const Vec3 shift = outward * (is_pin ? o_.pin_length : -o_.hole_depth);
    std::vector<Index> far;
    for (const Index v : ring) {
      far.push_back(static_cast<Index>(soup_.vertices.size()));
      soup_.vertices.push_back(soup_.vertices[v] + shift);
    }
    const std::size_t n = ring.size();
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t l = (k + 1) % n;
      Vec3 radial = 0.5 * (soup_.vertices[ring[k]] + soup_.vertices[ring[l]]) - centre;
      if (!is_pin) radial = -radial;  // a hole's wall faces its axis
      add_facing(soup_, ring[k], ring[l], far[l], radial);
      add_facing(soup_, ring[k], far[l], far[k], radial);
    }
    for (std::size_t k = 1; k + 1 < n; ++k) add_facing(soup_, far[0], far[k], far[k + 1], outward);
  }

 private:
  const std::vector<Vec2>& loop_;
  const SectorOptions& o_;
  TriangleSoup& soup_;
};

}  // namespace

Vec2 quadrant_direction(int quadrant) {
  switch (((quadrant % 4) + 4) % 4) {
    case 0:
      return {1.0, 0.0};
    case 1:
      return {0.0, 1.0};
    case 2:
      return {-1.0, 0.0};
    default:
      return {0.0, -1.0};
  }
}

Vec2 place_joint_pin(const std::vector<Vec2>& loop, const SectorOptions& o, const std::string& name) {
  double z0 = std::numeric_limits<double>::infinity(), z1 = -z0;
  for (const Vec2& p : loop) {
    z0 = std::min(z0, p.y());
    z1 = std::max(z1, p.y());
  }
  // The hole's points at (x, y, z) in a cap's frame (x along the cap from the
  // axis, y into the sector) have radius sqrt(x^2 + y^2) in [x, sqrt(x^2 + depth^2)]:
  // its footprint in (radius, height) lies in the rectangle tested.
  for (const double height : {0.5, 0.4, 0.6, 0.3, 0.7}) {
    const double z = z0 + height * (z1 - z0);
    const double r_max = radius_at(loop, z);
    for (const double along : {0.5, 0.4, 0.6, 0.3, 0.7}) {
      const double r = along * r_max;
      const double lo = r - o.hole_radius;
      const double hi = std::hypot(r + o.hole_radius, o.hole_depth);
      if (lo < o.pin_radius) continue;  // off the axis, and for quarters off the other cut plane
      double wall = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < loop.size(); ++i) {
        wall = std::min(wall, rectangle_distance(loop[i], loop[(i + 1) % loop.size()], lo, hi,
                                                 z - o.hole_radius, z + o.hole_radius));
      }
      if (wall >= o.pin_radius) return {r, z};
    }
  }
  throw GeometryError(
      "print.pin_diameter",
      fmt::format("the master's {} has no place on its cut faces for the pin of an axial joint: its hole "
                  "(radius {:.6g}, {:.6g} deep) needs {:.6g} (the pin's radius) of material all round; use a "
                  "smaller pin_diameter",
                  name, o.hole_radius, o.hole_depth, o.pin_radius));
}

std::vector<MasterSector> cut_sectors(const std::vector<Vec2>& loop, const Vec2& pin,
                                      const SectorOptions& o) {
  if (o.sectors != 2 && o.sectors != 4) throw std::logic_error("master sectors: 2 or 4 sectors");
  const int quadrants = 4 / o.sectors;
  const long steps = std::max<long>(1, (o.segments * quadrants + 3) / 4);
  std::vector<MasterSector> sectors;
  for (int k = 0; k < o.sectors; ++k) {
    MasterSector s;
    s.index = k;
    s.from_quadrant = k * quadrants;
    s.to_quadrant = (k + 1) * quadrants;
    std::vector<Direction> d;
    for (long j = 0; j <= steps; ++j)
      d.push_back(quarter_direction(s.from_quadrant * steps + quadrants * j, steps));
    const LoopGrid grid =
        append_loop_grid(loop, static_cast<std::size_t>(steps) + 1, s.soup.vertices,
                         [&](std::size_t i, std::size_t j) { return revolved_point(loop[i], d[j]); });
    for_each_grid_face(grid, static_cast<std::size_t>(steps), [&](Index a, Index b, Index c) {
      s.soup.triangles.push_back({a, b, c});
    });
    SectorBuilder build(loop, o, s.soup);
    build.cap(grid, 0, d.front(), true, pin, false);  // the joint before: its hole
    build.cap(grid, static_cast<std::size_t>(steps), d.back(), false, pin, true);  // the joint after: its pin
    sectors.push_back(std::move(s));
  }
  return sectors;
}

}  // namespace fabmesh
