#include "geometry/mould/mould_section.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geometry/core/error_checks.h"
#include "geometry/sampling/sample_curve.h"
#include "geometry/section/simple_polygon.h"

namespace fabmesh {
namespace {

std::string at(const Vec2& p) { return fmt::format("(r {:.6g}, z {:.6g})", p.x(), p.y()); }

// The sampled profile from its base end to its rim, radii within eps of the axis snapped onto it.
std::vector<Vec2> sample_profile(const CompositeCurve& profile, double tolerance, std::size_t max_points,
                                 double* deviation) {
  if (profile.closed()) {
    throw GeometryError("profile", "a mould needs an open profile (base end to rim); this one is closed");
  }
  SampleOptions so;
  so.tolerance = tolerance;
  so.max_points = max_points;
  Polyline2 line = sample_curve(profile, so);
  *deviation = line.max_deviation;
  std::vector<Vec2> up = line.points;
  if (up.front().y() == up.back().y()) {
    throw GeometryError("profile", fmt::format("profile ends {} and {} are at the same height: which end is "
                                               "the rim is undefined",
                                               at(up.front()), at(up.back())));
  }
  if (up.front().y() > up.back().y()) std::reverse(up.begin(), up.end());
  const double eps = 1e-12 * std::max(1.0, profile.extent());
  for (std::size_t i = 0; i < up.size(); ++i) {
    Vec2& p = up[i];
    if (p.x() < -eps) {
      throw GeometryError("profile",
                          fmt::format("profile crosses the axis: radius {:.6g} < 0 at {}", p.x(), at(p)));
    }
    if (p.x() <= eps) p.x() = 0.0;
    if (p.x() == 0.0 && i + 1 == up.size()) {
      throw GeometryError("profile", fmt::format("the rim {} is on the axis: the cavity must open at the rim "
                                                 "to be filled through the reservoir",
                                                 at(p)));
    }
    if (p.x() == 0.0 && i > 0) {
      throw GeometryError("profile", fmt::format("profile touches the axis at {}: the cavity would pinch "
                                                 "there (only the base end may lie on the axis)",
                                                 at(p)));
    }
  }
  return up;
}

double radius_bound(const std::vector<Vec2>& pts, double deviation) {
  double r = 0.0;
  for (const Vec2& p : pts) r = std::max(r, p.x());
  return r + deviation;
}

void require_simple(const std::vector<Vec2>& loop, const std::string& what) {
  if (const auto c = find_crossing(loop, true)) {
    throw GeometryError("profile", fmt::format("the {} is not simple near {}: the profile crosses itself, "
                                               "the reservoir or its closing line to the axis",
                                               what, at(c->where)));
  }
  if (signed_area2(loop) <= 0.0) throw std::logic_error("mould section: a loop is not counter-clockwise");
}

// Cuts the cavity path at z_cut: side gets the path above, base the path below.
void cut_sections(MouldSection& s, const MouldOptions& options) {
  const std::vector<Vec2>& q = s.cavity;
  const double zc = s.z_cut, r = s.block_radius;
  std::size_t a = 0, b = 0;
  while (q[a].y() > zc) ++a;
  for (std::size_t i = 0; i < q.size(); ++i) {
    if (q[i].y() >= zc) b = i;
  }
  Vec2 x_side, y_base;
  if (a == b + 1) {
    const double t = (q[b].y() - zc) / (q[b].y() - q[a].y());
    x_side = y_base = Vec2(q[b].x() + t * (q[a].x() - q[b].x()), zc);
  } else {
    for (std::size_t i = a; i <= b; ++i) {
      if (q[i].y() != zc || (i > a && q[i].x() > q[i - 1].x())) {
        throw GeometryError("base_height",
                            fmt::format("the base cut at z = {:.6g} (base_height {}) crosses the cavity "
                                        "more than once (at {} and again near {}): choose a base_height "
                                        "where the profile crosses the cut once",
                                        zc, options.base_height, at(q[a]), at(q[b])));
      }
    }
    x_side = q[a];
    y_base = q[b];
  }
  if (x_side.x() == 0.0) {
    throw GeometryError("base_height",
                        fmt::format("the base cut at z = {:.6g} meets the cavity on the axis, so "
                                    "the side parts would pinch to a point there: raise "
                                    "base_height above {:.6g}",
                                    zc, options.base_height));
  }
  s.side_cavity.assign(q.begin(), q.begin() + static_cast<std::ptrdiff_t>(a));
  s.side_cavity.push_back(x_side);
  s.base_cavity = {y_base};
  s.base_cavity.insert(s.base_cavity.end(), q.begin() + static_cast<std::ptrdiff_t>(b + 1), q.end());

  s.side.loop = {Vec2(r, zc), Vec2(r, s.z_top)};
  s.side.loop.insert(s.side.loop.end(), s.side_cavity.begin(), s.side_cavity.end());
  s.side.on_outline.assign(s.side.loop.size(), 0);
  s.side.on_outline[0] = s.side.on_outline[1] = 1;
  s.base.loop = {Vec2(0.0, s.z_bottom), Vec2(r, s.z_bottom), Vec2(r, zc)};
  s.base.loop.insert(s.base.loop.end(), s.base_cavity.begin(), s.base_cavity.end());
  s.base.on_outline.assign(s.base.loop.size(), 0);
  s.base.on_outline[1] = s.base.on_outline[2] = 1;
  require_simple(s.side.loop, "side parts' section");
  require_simple(s.base.loop, "base part's section");
}

}  // namespace

void check_mould_options(const MouldOptions& o) {
  if (o.parts != 2 && o.parts != 3) {
    throw RangeError("parts", o.parts, fmt::format("parts = {} must be 2 or 3", o.parts));
  }
  require_positive("wall", o.wall);
  require_positive("spare", o.spare);
  if (o.spare_shape == SpareShape::Cone) require_in_range("spare_taper_deg", o.spare_taper_deg, 0.0, 60.0);
  if (o.spare_shape == SpareShape::Cone) require_positive("spare_taper_deg", o.spare_taper_deg);
  require_in_range("block_radius", o.block_radius, 0.0, 1e12);
  require_in_range("base_height", o.base_height, 0.0, 1e12);
  if (o.keys < 0 || o.keys > 64)
    throw RangeError("keys", o.keys, fmt::format("keys = {} is outside [0, 64]", o.keys));
  if (o.keys > 0 || !o.key_positions.empty()) {
    require_positive("key_radius", o.key_radius);
    require_in_range("key_clearance", o.key_clearance, 0.0, 1e12);
    require_in_range("key_margin", o.key_margin, 0.0, 1e12);
  }
  if (o.key_positions.size() > 64) {
    throw RangeError("key_positions", static_cast<double>(o.key_positions.size()),
                     fmt::format("{} key positions: at most 64", o.key_positions.size()));
  }
  require_positive("tolerance", o.tolerance);
}

MouldSection build_mould_section(const CompositeCurve& master_profile, const MouldOptions& options,
                                 double profile_tolerance) {
  check_mould_options(options);
  MouldSection s;
  const std::vector<Vec2> up =
      sample_profile(master_profile, profile_tolerance, options.max_triangles, &s.max_deviation);
  s.base_radius = up.front().x();
  s.base_z = up.front().y();
  s.rim_radius = up.back().x();
  s.rim_z = up.back().y();
  s.z_top = s.rim_z + options.spare;
  s.opening_radius = s.rim_radius;
  if (options.spare_shape == SpareShape::Cone) {
    s.opening_radius += options.spare * std::tan(options.spare_taper_deg * M_PI / 180.0);
  }
  for (const Vec2& p : up) {
    if (p.y() + s.max_deviation >= s.z_top) {
      throw GeometryError("spare", fmt::format("the profile reaches {}, not below the top of the reservoir "
                                               "at z = {:.6g} (rim + spare {}): raise spare",
                                               at(p), s.z_top, options.spare));
    }
  }
  s.cavity = {Vec2(s.opening_radius, s.z_top)};
  s.profile_begin = s.cavity.size();
  s.cavity.insert(s.cavity.end(), up.rbegin(), up.rend());
  s.profile_end = s.cavity.size();
  if (s.base_radius != 0.0) s.cavity.emplace_back(0.0, s.base_z);

  s.cavity_radius = radius_bound(s.cavity, s.max_deviation);
  const double needed = s.cavity_radius + options.wall;
  const char* what = options.block == BlockShape::Box ? "half the box's side" : "the cylinder's radius";
  if (options.block_radius == 0.0) {
    s.block_radius = needed;
  } else if (options.block_radius < needed) {
    throw RangeError("block_radius", options.block_radius,
                     fmt::format("block_radius = {} ({}) is less than the cavity's largest radius {:.6g} + "
                                 "wall {} = {:.6g}",
                                 options.block_radius, what, s.cavity_radius, options.wall, needed));
  } else {
    s.block_radius = options.block_radius;
  }
  double z_min = s.z_top;
  for (const Vec2& p : s.cavity) z_min = std::min(z_min, p.y());
  s.z_bottom = z_min - s.max_deviation - options.wall;

  // The whole section: block bottom, outer side, top to the opening, then down the cavity and the axis.
  const double r = s.block_radius;
  SweepSection whole;
  whole.loop = {Vec2(0.0, s.z_bottom), Vec2(r, s.z_bottom), Vec2(r, s.z_top)};
  whole.loop.insert(whole.loop.end(), s.cavity.begin(), s.cavity.end());
  whole.on_outline.assign(whole.loop.size(), 0);
  whole.on_outline[1] = whole.on_outline[2] = 1;
  require_simple(whole.loop, "mould section");

  if (options.base_part) {
    s.has_cut = true;
    s.z_cut = s.base_z + options.base_height;
    if (s.z_cut >= s.rim_z) {
      throw RangeError("base_height", options.base_height,
                       fmt::format("base_height = {} puts the base cut at z = {:.6g}, not below the rim at "
                                   "z = {:.6g}",
                                   options.base_height, s.z_cut, s.rim_z));
    }
    cut_sections(s, options);
  } else {
    s.side = whole;
    s.side_cavity = s.cavity;
  }
  s.proof = fmt::format(
      "the mould section (block {} x [{:.6g}, {:.6g}] minus the cavity: the profile sampled within {:.3g}, "
      "the reservoir and the closing line to the axis) is a simple counter-clockwise polygon in r >= 0 "
      "meeting the axis only along one axis edge (exact predicates){}",
      r, s.z_bottom, s.z_top, s.max_deviation,
      s.has_cut ? fmt::format(", and so are its parts above and below the cut z = {:.6g}", s.z_cut) : "");
  return s;
}

}  // namespace fabmesh
