#include "geometry/mould/master_sections.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/core/error_checks.h"
#include "geometry/core/errors.h"
#include "geometry/mesh/revolution_margin.h"
#include "geometry/mesh/revolve.h"
#include "geometry/mould/master_sectors.h"
#include "geometry/section/simple_polygon.h"
#include "geometry/toolpath/boundary_index.h"

namespace fabmesh {
namespace {

// More sections than any printer needs: a bed barely taller than the pin.
constexpr int kMaxSections = 100;

bool on_axis_edge(const Vec2& a, const Vec2& b) { return a.x() == 0.0 && b.x() == 0.0; }

// The radii where the loop's edges off the axis cross the height z (no vertex lies on it).
std::vector<double> crossings(const std::vector<Vec2>& loop, double z) {
  std::vector<double> r;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Vec2 &a = loop[i], &b = loop[(i + 1) % loop.size()];
    if (on_axis_edge(a, b) || (a.y() - z) * (b.y() - z) >= 0.0) continue;
    r.push_back(a.x() + (z - a.y()) / (b.y() - a.y()) * (b.x() - a.x()));
  }
  std::sort(r.begin(), r.end());
  return r;
}

// The part of the loop on the side of the height z that `keep_above` says
// (Sutherland-Hodgman against one half-plane): one simple polygon when the
// line crosses the boundary twice (once on the axis).
std::vector<Vec2> clip(const std::vector<Vec2>& loop, double z, bool keep_above) {
  auto inside = [&](const Vec2& p) { return keep_above ? p.y() >= z : p.y() <= z; };
  std::vector<Vec2> out;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Vec2 &a = loop[i], &b = loop[(i + 1) % loop.size()];
    if (inside(a)) out.push_back(a);
    if (inside(a) != inside(b)) {
      const double t = (z - a.y()) / (b.y() - a.y());
      out.emplace_back(a.x() + t * (b.x() - a.x()), z);
    }
  }
  return out;
}

// Distance between segment ab and the axis-aligned rectangle [0, w] x [z0, z1]:
// 0 when an end lies in it, else the least distance to its four sides.
double segment_rectangle_distance(const Vec2& a, const Vec2& b, double w, double z0, double z1) {
  auto inside = [&](const Vec2& p) { return p.x() >= 0.0 && p.x() <= w && p.y() >= z0 && p.y() <= z1; };
  if (inside(a) || inside(b)) return 0.0;
  const Vec2 corners[4] = {{0.0, z0}, {w, z0}, {w, z1}, {0.0, z1}};
  double d = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 4; ++k) d = std::min(d, segment_distance(a, b, corners[k], corners[(k + 1) % 4]));
  return d;
}

// V = 2 pi * integral of r over the polygon (Pappus), by the shoelace form of the first moment.
double revolved_volume(const std::vector<Vec2>& loop) {
  double moment = 0.0;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Vec2 &a = loop[i], &b = loop[(i + 1) % loop.size()];
    moment += (a.x() + b.x()) * (a.x() * b.y() - b.x() * a.y());
  }
  return 2.0 * M_PI * moment / 6.0;
}

// Replaces the cut edge along height z between the axis and the profile by
// the pin's (above z) or the hole's (into the slab) outline.
void notch(std::vector<Vec2>& loop, double z, bool pin, double radius, double depth) {
  for (std::size_t i = 0; i < loop.size(); ++i) {
    Vec2& p = loop[i];
    if (p.x() != 0.0 || p.y() != z) continue;
    const auto at = loop.begin() + static_cast<std::ptrdiff_t>(i);
    if (pin) {  // the top edge runs in to the axis: out along the pin instead
      *at = Vec2(radius, z);
      loop.insert(at + 1, {Vec2(radius, z + depth), Vec2(0.0, z + depth)});
    } else {  // the bottom edge runs out from the axis: down the hole first
      *at = Vec2(0.0, z + depth);
      loop.insert(at + 1, {Vec2(radius, z + depth), Vec2(radius, z)});
    }
    return;
  }
  throw std::logic_error(fmt::format("master sections: no cut edge on the axis at z = {}", z));
}

// Section `whole` (of `sections`) cut into o.sectors sectors, each a section
// of its own, appended to `out`.
void add_sectors(MasterSection whole, int sections, const MasterSplitOptions& o, MasterSplit& out) {
  SectorOptions so;
  so.sectors = o.sectors;
  so.segments = o.segments;
  so.pin_radius = 0.5 * o.pin_diameter;
  so.pin_length = out.pin_height;
  so.hole_radius = out.hole_radius;
  so.hole_depth = out.hole_depth;
  const Vec2 pin = place_joint_pin(whole.loop, so, whole.name);
  const char* piece = o.sectors == 2 ? "half" : "quarter";
  const double joint = M_PI * (so.pin_radius * so.pin_radius * so.pin_length -
                               so.hole_radius * so.hole_radius * so.hole_depth);
  for (MasterSector& c : cut_sectors(whole.loop, pin, so)) {
    MasterSection s;
    s.name = sections == 1 ? fmt::format("{}-{}", piece, c.index + 1)
                           : fmt::format("{}-{}-{}", whole.name, piece, c.index + 1);
    s.z_low = whole.z_low;
    s.z_high = whole.z_high;
    s.pin = whole.pin;
    s.hole = whole.hole;
    s.loop = whole.loop;
    s.from_quadrant = c.from_quadrant;
    s.to_quadrant = c.to_quadrant;
    s.joint_pin = pin;
    s.soup = std::move(c.soup);
    s.volume = whole.volume / o.sectors + joint;
    out.sections.push_back(std::move(s));
  }
}

}  // namespace

MasterSplit split_master(const std::vector<Vec2>& loop, const MasterSplitOptions& o) {
  require_positive("print.pin_diameter", o.pin_diameter);
  if (!(o.pin_clearance >= 0.0) || !std::isfinite(o.pin_clearance)) {
    throw RangeError("print.pin_clearance", o.pin_clearance,
                     fmt::format("pin_clearance {} must be a number >= 0", o.pin_clearance),
                     ErrorLocation{"print.pin_clearance"});
  }
  if (o.sectors != 1 && o.sectors != 2 && o.sectors != 4)
    throw std::logic_error("split_master: a master is cut into 1, 2 or 4 sectors");
  MasterSplit out;
  out.sectors = o.sectors;
  const double pin_r = 0.5 * o.pin_diameter;
  out.pin_height = o.pin_diameter;
  out.hole_radius = pin_r + o.pin_clearance;
  out.hole_depth = out.pin_height + o.pin_clearance;
  if (!(o.bed_height > out.pin_height)) {
    throw RangeError(
        "print.bed", o.bed_height,
        fmt::format("the bed's height {:.6g} leaves no room for a section under its registration "
                    "pin ({:.6g} tall: pin_diameter); use a smaller pin_diameter",
                    o.bed_height, out.pin_height),
        ErrorLocation{"print.bed"});
  }
  double z0 = std::numeric_limits<double>::infinity(), z1 = -z0;
  for (const Vec2& p : loop) {
    z0 = std::min(z0, p.y());
    z1 = std::max(z1, p.y());
  }
  const double height = z1 - z0;
  // One section needs no pin (a master cut only through its axis); more stand each with its pin on top.
  const double sections =
      height <= o.bed_height ? 1.0 : std::ceil(height / (o.bed_height - out.pin_height) - 1e-12);
  if (!(sections <= kMaxSections)) {
    throw GeometryError(
        "print.bed", fmt::format("the master ({:.6g} tall) would need {:.6g} sections under pins {:.6g} tall "
                                 "on a bed {:.6g} tall; fabmesh makes at most {}: use a taller bed or a "
                                 "smaller pin_diameter",
                                 height, sections, out.pin_height, o.bed_height, kMaxSections));
  }
  const int n = std::max(1, static_cast<int>(sections));
  const double slab = height / n;
  if (n > 1 && slab < out.hole_depth + pin_r) {
    throw GeometryError(
        "print.bed", fmt::format("the master ({:.6g} tall) would need {} sections of {:.6g}, too short for "
                                 "the hole of a pin ({:.6g} deep, with {:.6g} of wall over it): use a taller "
                                 "bed or a smaller pin_diameter",
                                 height, n, slab, out.hole_depth, pin_r));
  }
  for (int k = 1; k < n; ++k) {
    double z = z0 + slab * k;
    // A cut through a vertex would leave a degenerate edge: move it up by the least step that misses them.
    while (std::any_of(loop.begin(), loop.end(), [&](const Vec2& p) { return p.y() == z; }))
      z = std::nextafter(z, z1);
    const std::vector<double> r = crossings(loop, z);
    if (r.size() != 1) {
      throw GeometryError("print.bed",
                          fmt::format("the cut at z = {:.6g} (the master in {} sections for the bed's height "
                                      "{:.6g}) crosses the master's profile {} times: a section would fall "
                                      "apart; use a bed height that cuts where the profile is crossed once",
                                      z, n, o.bed_height, r.size()));
    }
    if (r.front() < out.hole_radius + pin_r) {
      throw GeometryError("print.pin_diameter",
                          fmt::format("the master is {:.6g} in radius at the cut z = {:.6g}, too narrow for "
                                      "the pin's hole (radius {:.6g} = pin_diameter / 2 + pin_clearance) and "
                                      "its wall ({:.6g}, the pin's radius): use a smaller pin_diameter",
                                      r.front(), z, out.hole_radius, pin_r));
    }
    out.cuts.push_back(z);
  }

  RevolveOptions ro;
  ro.segments = o.segments;
  for (int k = 0; k < n; ++k) {
    MasterSection s;
    s.name = fmt::format("section-{}", k + 1);
    s.z_low = k == 0 ? z0 : out.cuts[static_cast<std::size_t>(k - 1)];
    s.z_high = k + 1 == n ? z1 : out.cuts[static_cast<std::size_t>(k)];
    s.hole = k > 0;
    s.pin = k + 1 < n;
    std::vector<Vec2> part = loop;
    if (s.hole) part = clip(part, s.z_low, true);
    if (s.pin) part = clip(part, s.z_high, false);
    if (s.hole) {
      // The hole keeps the pin's radius of material around it, from the profile and the top cut.
      double wall = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < part.size(); ++i) {
        const Vec2 &a = part[i], &b = part[(i + 1) % part.size()];
        if (on_axis_edge(a, b) || (a.y() == s.z_low && b.y() == s.z_low)) continue;
        wall = std::min(wall,
                        segment_rectangle_distance(a, b, out.hole_radius, s.z_low, s.z_low + out.hole_depth));
      }
      if (wall < pin_r) {
        throw GeometryError(
            "print.pin_diameter",
            fmt::format("the hole for the pin in the bottom of {} (radius {:.6g}, {:.6g} deep from "
                        "z = {:.6g}) comes within {:.6g} of the master's surface; it needs {:.6g} "
                        "(the pin's radius): use a smaller pin_diameter",
                        s.name, out.hole_radius, out.hole_depth, s.z_low, wall, pin_r));
      }
      notch(part, s.z_low, false, out.hole_radius, out.hole_depth);
    }
    if (s.pin) notch(part, s.z_high, true, pin_r, out.pin_height);
    if (const auto c = find_crossing(part, true)) {
      throw std::logic_error(fmt::format("master {}: the notched section is not simple near ({}, {})", s.name,
                                         c->where.x(), c->where.y()));
    }
    s.volume = revolved_volume(part);
    if (o.sectors > 1) {  // its pieces are swept and capped from the loop: no whole revolution
      s.loop = std::move(part);
      add_sectors(std::move(s), n, o, out);
      continue;
    }
    RevolvedSoup revolved = revolve({part}, ro);
    s.soup = std::move(revolved.soup);
    s.topology = std::move(revolved.topology);
    s.proof = EmbeddingProof(fmt::format(
        "the master's section cut to z in [{:.6g}, {:.6g}], each cut crossing the profile once off the axis, "
        "so the slab's part of the section is one polygon{}{}; simple (its edges checked pairwise); revolved "
        "in {} uniform angular steps",
        s.z_low, s.z_high,
        s.hole ? fmt::format(
                     ", notched on the axis by the hole (radius {:.6g}, depth {:.6g}) at least the pin's "
                     "radius from the profile",
                     out.hole_radius, out.hole_depth)
               : std::string(),
        s.pin ? fmt::format(", with the pin (radius {:.6g}, height {:.6g}) on the axis above the top cut",
                            pin_r, out.pin_height)
              : std::string(),
        o.segments));
    s.proof->margin = revolution_margin({part}, o.segments);
    s.loop = std::move(part);
    out.sections.push_back(std::move(s));
  }
  return out;
}

}  // namespace fabmesh
