#include "geometry/section/vessel_section.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include "geometry/core/error_checks.h"
#include "geometry/sampling/sample_curve.h"
#include "geometry/section/curve_clearance.h"
#include "geometry/section/inner_wall.h"
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

// Moves the off-axis vertices of `loops` closer than `clearance` to the axis
// out to it, when the loops stay simple (else leaves them); returns the
// largest move (0 when none).
double clear_axis(std::vector<std::vector<Vec2>>& loops, double clearance) {
  std::vector<std::vector<Vec2>> moved = loops;
  double largest = 0.0;
  for (std::vector<Vec2>& loop : moved) {
    for (Vec2& p : loop) {
      if (p.x() == 0.0 || p.x() >= clearance) continue;
      largest = std::max(largest, clearance - p.x());
      p.x() = clearance;
    }
  }
  if (largest == 0.0 || find_crossing(moved)) return 0.0;
  loops = std::move(moved);
  return largest;
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

// The shell's loop: the outer wall up, the inner wall down to the base (or
// the axis), the base and the bottom back to the start.
struct Shell {
  std::vector<Vec2> loop;
  InnerWall inner;
  bool cut_at_base = false;
};

Shell shell_loop(const CompositeCurve& profile, const std::vector<Vec2>& up, bool upward,
                 const VesselSectionOptions& options) {
  const Vec2& bottom = up.front();
  const Vec2& top = up.back();
  if (top.x() == 0.0) {
    throw GeometryError(
        "profile",
        fmt::format("a shell is open at its rim, but the profile's upper end {} is on the axis", at(top)));
  }
  SampleOptions so;
  so.tolerance = options.tolerance;
  so.max_points = options.max_points - std::min(options.max_points, up.size());
  Shell shell;
  // The inner wall lies toward the axis: left of a profile running upward.
  const std::string profile_name = options.name_key ? options.name_key("profile") : "profile";
  shell.inner = sample_inner_wall(profile, options.wall, upward ? 1.0 : -1.0, upward, so, profile_name);
  if (options.rim == RimCut::Level) level_inner_wall(shell.inner, profile, top.y(), upward);
  const double base = options.base > 0.0 ? options.base : options.wall;
  const double z_cut = bottom.y() + base;
  const double inner_top = shell.inner.points.front().point.y();
  if (z_cut >= inner_top) {
    throw GeometryError("base",
                        fmt::format("base {} leaves no cavity: the inner wall rises only {:.6g} above the "
                                    "bottom (z {:.6g} to {:.6g}), so the base must be thinner than that",
                                    base, inner_top - bottom.y(), bottom.y(), inner_top));
  }
  shell.cut_at_base = cut_inner_wall(shell.inner, profile, z_cut);
  shell.loop = up;
  for (const WallPoint& p : shell.inner.points) shell.loop.push_back(p.point);
  // At the base plane, or never down to it nor the axis: close horizontally to the axis.
  if (shell.loop.back().x() != 0.0) shell.loop.emplace_back(0.0, shell.loop.back().y());
  if (bottom.x() != 0.0) shell.loop.emplace_back(0.0, bottom.y());
  for (const Vec2& p : shell.loop) {
    if (p.x() < 0.0) {
      throw GeometryError("wall",
                          fmt::format("wall {} is too thick for the profile: the inner surface crosses "
                                      "the axis near {}",
                                      options.wall, at(p)));
    }
  }
  return shell;
}

// The clearance of the exact outer surface (profile, bottom) and inner
// surface (inner wall, base): the rim and the axis join them.
void check_clearance(const CompositeCurve& profile, const std::vector<CurveParam>& params, const Shell& shell,
                     const VesselSectionOptions& options, VesselSection& section) {
  std::vector<std::unique_ptr<ExactArc>> arcs;
  std::vector<ArcPiece> pieces;
  for (const Segment& seg : profile.segments()) arcs.push_back(std::make_unique<SegmentArc>(seg));
  for (std::size_t i = 0; i + 1 < params.size(); ++i) {
    const auto [s0, s1] = edge_parameters(params, i);
    pieces.push_back({arcs[params[i].segment].get(), s0, s1, 0});
  }
  const Vec2 start = profile.segments().front().point(0.0), end = profile.segments().back().point(1.0);
  const Vec2 bottom = start.y() < end.y() ? start : end;
  if (bottom.x() != 0.0) {
    arcs.push_back(std::make_unique<LineArc>(bottom, Vec2(0.0, bottom.y())));
    pieces.push_back({arcs.back().get(), 0.0, 1.0, 0});
  }
  inner_wall_pieces(shell.inner, profile, 1, arcs, pieces);
  const Vec2 last = shell.inner.points.back().point;
  if (last.x() != 0.0) {
    arcs.push_back(std::make_unique<LineArc>(last, Vec2(0.0, last.y())));
    pieces.push_back({arcs.back().get(), 0.0, 1.0, 1});
  }
  ClearanceOptions co;
  co.accuracy = 1e-3 * options.tolerance;
  const Clearance c = exact_clearance(pieces, co);
  const double required = options.min_clearance > 0.0 ? options.min_clearance : options.tolerance;
  const std::string where = fmt::format("outer surface near {} and inner surface near {}", at(c.a), at(c.b));
  if (c.upper < required) {
    const bool crossing = c.upper <= co.accuracy;
    throw GeometryError(
        "wall",
        fmt::format(
            "wall {} (base {}): {}", options.wall, options.base > 0.0 ? options.base : options.wall,
            crossing
                ? fmt::format("the exact inner surface meets the outer one ({}): the wall is too thick "
                              "for the profile there",
                              where)
                : fmt::format(
                      "the exact outer and inner surfaces come within {:.6g} of each other ({}), "
                      "closer than the {:.6g} the mesh is built within: the shell would be thinner than that "
                      "there",
                      c.upper, where, required)));
  }
  section.min_clearance = c.lower;
  section.clearance_where = where;
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
  section.max_deviation = line.max_deviation + eps;
  std::optional<Shell> shell;
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
    if (options.mode == BodyMode::Solid) {
      section.loops = solid_loops(up);
    } else {
      shell = shell_loop(profile, up, upward, options);
      section.max_deviation = std::max(section.max_deviation, shell->inner.max_deviation);
      section.loops = {shell->loop};
      section.inner_wall = shell->inner;
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
    if (shell) check_clearance(profile, params, *shell, options, section);  // the exact walls say why
    if (options.mode == BodyMode::Shell) {
      throw GeometryError(
          ErrorLocation{"wall", {}, {c->where.x(), c->where.y()}},
          fmt::format(
              "wall {} (base {}) is too thick for the profile: the shell section crosses itself near {}",
              options.wall, options.base > 0.0 ? options.base : options.wall, at(c->where)));
    }
    throw GeometryError(ErrorLocation{"profile", {}, {c->where.x(), c->where.y()}},
                        fmt::format("the profile crosses itself near {}", at(c->where)));
  }
  if (shell) check_clearance(profile, params, *shell, options, section);
  section.max_deviation += clear_axis(section.loops, options.axis_clearance);
  section.proof =
      "the section loops are simple and disjoint in r >= 0 (exact predicates), so its revolution is embedded";
  return section;
}

}  // namespace fabmesh
