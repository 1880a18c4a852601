#include "geometry/section/vessel_section.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geometry/core/errors.h"
#include "geometry/sampling/sample_curve.h"
#include "geometry/section/simple_polygon.h"

namespace fabmesh {
namespace {

std::string at(const Vec2& p) { return fmt::format("(r {:.6g}, z {:.6g})", p.x(), p.y()); }

// Snaps radii within `eps` of the axis onto it; rejects radii below -eps.
void snap_to_axis(std::vector<Vec2>& pts, double eps) {
  for (Vec2& p : pts) {
    if (p.x() < -eps) {
      throw GeometryError("profile",
                          fmt::format("profile crosses the axis: radius {:.6g} < 0 at {}", p.x(), at(p)));
    }
    if (p.x() <= eps) p.x() = 0.0;
  }
}

// An axis vertex whose neighbours are both off the axis pinches the body to a point.
void reject_isolated_axis_contacts(const std::vector<Vec2>& loop) {
  const std::size_t n = loop.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (loop[i].x() != 0.0) continue;
    if (loop[(i + n - 1) % n].x() != 0.0 && loop[(i + 1) % n].x() != 0.0) {
      throw GeometryError("profile",
                          fmt::format("profile touches the axis at the single point {}: the body would "
                                      "pinch to a point there (not a manifold); keep the profile off the "
                                      "axis or let it run along the axis",
                                      at(loop[i])));
    }
  }
}

// A solid profile split where it runs along the axis: each off-axis run,
// closed along the axis, is one body's loop (base -> rim, then down the axis).
std::vector<std::vector<Vec2>> solid_loops(const std::vector<Vec2>& up) {
  std::vector<std::vector<Vec2>> loops;
  std::vector<Vec2> run;
  auto close_run = [&]() {
    if (run.size() >= 2) {
      if (run.back().x() != 0.0) run.emplace_back(0.0, run.back().y());
      if (run.front().x() != 0.0) run.emplace_back(0.0, run.front().y());
      loops.push_back(run);
    }
    run.clear();
  };
  for (std::size_t i = 0; i < up.size(); ++i) {
    const bool on_axis = up[i].x() == 0.0;
    const bool next_on_axis = i + 1 < up.size() && up[i + 1].x() == 0.0;
    run.push_back(up[i]);
    if (on_axis && next_on_axis) {  // an axis edge separates two bodies
      close_run();
    }
  }
  close_run();
  return loops;
}

// Inner wall: the profile offset by `wall` along its inward normal (toward
// the axis for a profile running upward), at the exact curve's parameters.
std::vector<Vec2> inner_offset(const CompositeCurve& profile, const std::vector<CurveParam>& params,
                               double wall, bool upward, double* max_abs_curvature) {
  std::vector<Vec2> inner;
  inner.reserve(params.size());
  for (const CurveParam& p : params) {
    const CurveJet j = profile.segments()[p.segment].jet(p.s);
    const double speed = j[1].norm();
    Vec2 left(-j[1].y(), j[1].x());
    left /= speed;
    if (!upward) left = -left;
    // Curvature toward the inside (positive: the wall's inner side is concave there).
    const double k = (upward ? 1.0 : -1.0) * cross2(j[1], j[2]) / (speed * speed * speed);
    if (max_abs_curvature) *max_abs_curvature = std::max(*max_abs_curvature, std::abs(k));
    if (k * wall >= 1.0) {
      throw GeometryError("wall",
                          fmt::format("wall {} is too thick for the profile: its radius of curvature is "
                                      "{:.6g} at {} (segment {}), so the inner surface would fold over",
                                      wall, 1.0 / k, at(j[0]), p.segment + 1));
    }
    inner.push_back(j[0] + wall * left);
  }
  return inner;
}

// The inner wall from the rim down, cut where it reaches z_cut or the axis;
// the cut point is appended, then the loop continues along the base to the axis.
std::vector<Vec2> trim_inner(const std::vector<Vec2>& inner_top_down, double z_cut) {
  std::vector<Vec2> out{inner_top_down.front()};
  for (std::size_t i = 1; i < inner_top_down.size(); ++i) {
    const Vec2 a = out.back(), b = inner_top_down[i];
    const double tz = (b.y() < z_cut) ? (a.y() - z_cut) / (a.y() - b.y()) : 2.0;
    const double tr = (b.x() < 0.0) ? a.x() / (a.x() - b.x()) : 2.0;
    if (tz <= 1.0 || tr <= 1.0) {
      if (tz <= tr) {
        out.emplace_back(a.x() + tz * (b.x() - a.x()), z_cut);
        out.emplace_back(0.0, z_cut);
      } else {
        out.emplace_back(0.0, a.y() + tr * (b.y() - a.y()));
      }
      return out;
    }
    out.push_back(b);
  }
  // Never reached the base plane or the axis: close horizontally to the axis.
  out.emplace_back(0.0, out.back().y());
  return out;
}

void remove_repeated(std::vector<Vec2>& loop) {
  std::vector<Vec2> out;
  for (const Vec2& p : loop) {
    if (out.empty() || p != out.back()) out.push_back(p);
  }
  while (out.size() > 1 && out.front() == out.back()) out.pop_back();
  // Collinear runs along the axis collapse to their ends.
  std::vector<Vec2> clean;
  const std::size_t n = out.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& prev = out[(i + n - 1) % n];
    const Vec2& next = out[(i + 1) % n];
    if (out[i].x() == 0.0 && prev.x() == 0.0 && next.x() == 0.0) continue;
    clean.push_back(out[i]);
  }
  loop = std::move(clean);
}

}  // namespace

VesselSection build_vessel_section(const CompositeCurve& profile, const VesselSectionOptions& options) {
  require_positive("tolerance", options.tolerance);
  if (options.mode == BodyMode::Shell) require_positive("wall", options.wall);
  if (options.mode == BodyMode::Shell && options.base != 0.0) require_positive("base", options.base);

  SampleOptions so;
  so.tolerance = options.tolerance;
  so.max_points = options.max_points;
  std::vector<CurveParam> params;
  Polyline2 line = sample_curve(profile, so, &params);
  const double eps = 1e-12 * std::max(1.0, profile.extent());
  snap_to_axis(line.points, eps);

  VesselSection section;
  section.max_deviation = line.max_deviation;
  std::vector<Vec2> loop;

  if (profile.closed()) {
    if (options.mode == BodyMode::Shell) {
      throw GeometryError(
          "profile", "a closed profile is revolved as a solid ring; body.mode shell needs an open profile");
    }
    section.loops = {line.points};
  } else {
    const bool upward = line.points.back().y() > line.points.front().y();
    if (line.points.back().y() == line.points.front().y()) {
      throw GeometryError("profile",
                          fmt::format("profile ends {} and {} are at the same height: which end is the "
                                      "rim is undefined",
                                      at(line.points.front()), at(line.points.back())));
    }
    std::vector<Vec2> up = line.points;  // base -> rim
    if (!upward) std::reverse(up.begin(), up.end());
    const Vec2 bottom = up.front(), top = up.back();
    if (options.mode == BodyMode::Solid) {
      section.loops = solid_loops(up);
    } else {
      if (top.x() == 0.0) {
        throw GeometryError("profile",
                            fmt::format("a shell is open at its rim, but the profile's upper end {} is on "
                                        "the axis",
                                        at(top)));
      }
      // Offsetting scales chord deviations by up to 1 + wall |k|: sample finely enough for the inner wall
      // too.
      double kmax = 0.0;
      std::vector<Vec2> inner = inner_offset(profile, params, options.wall, upward, &kmax);
      const double factor = 1.0 + options.wall * kmax;
      if (factor > 1.0 + 1e-9) {
        so.tolerance = options.tolerance / factor;
        line = sample_curve(profile, so, &params);
        snap_to_axis(line.points, eps);
        up = line.points;
        if (!upward) std::reverse(up.begin(), up.end());
        inner = inner_offset(profile, params, options.wall, upward, nullptr);
      }
      section.max_deviation = line.max_deviation * factor;
      if (upward) std::reverse(inner.begin(), inner.end());  // rim -> base
      const double base = options.base > 0.0 ? options.base : options.wall;
      const std::vector<Vec2> trimmed = trim_inner(inner, bottom.y() + base);
      loop = up;
      loop.insert(loop.end(), trimmed.begin(), trimmed.end());
      if (bottom.x() != 0.0) loop.emplace_back(0.0, bottom.y());
      section.loops = {loop};
      for (const Vec2& p : loop) {
        if (p.x() < 0.0) {
          throw GeometryError("wall",
                              fmt::format("wall {} is too thick for the profile: the inner surface crosses "
                                          "the axis near {}",
                                          options.wall, at(p)));
        }
      }
    }
  }
  if (section.loops.empty()) throw GeometryError("profile", "the profile encloses no area with the axis");
  for (std::vector<Vec2>& l : section.loops) {
    remove_repeated(l);
    if (l.size() < 3) throw GeometryError("profile", "the profile encloses no area with the axis");
    if (signed_area2(l) < 0.0) std::reverse(l.begin(), l.end());
    reject_isolated_axis_contacts(l);
    for (const Vec2& p : l) section.max_radius = std::max(section.max_radius, p.x());
  }
  if (const auto c = find_crossing(section.loops)) {
    if (options.mode == BodyMode::Shell) {
      throw GeometryError(
          "wall", fmt::format("wall {} (base {}) is too thick for the profile: the shell section "
                              "crosses itself near {}",
                              options.wall, options.base > 0.0 ? options.base : options.wall, at(c->where)));
    }
    throw GeometryError("profile", fmt::format("the profile crosses itself near {}", at(c->where)));
  }
  section.proof =
      "the section loops are simple and disjoint in r >= 0 (exact predicates), so its revolution is embedded";
  return section;
}

}  // namespace fabmesh
