// Router programs of the countertop examples, verified by simulation: each
// program runs through the CNCjs interpreter (gcode-toolpath) and the
// interpreted motions are measured against the EXACT curves of the design.

#include <fmt/format.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <set>

#include "geometry/core/errors.h"
#include "geometry/fairing/build_curve.h"
#include "geometry/toolpath/toolpath.h"
#include "io/cutting/gcode.h"
#include "io/design/dxf_loops.h"
#include "io/design/read_design.h"
#include "tests/geometry/section/region_shapes.h"
#include "tests/geometry/toolpath/digitised_worktop.h"
#include "tests/io/cutting/drill_checks.h"
#include "tests/io/cutting/interpret.h"
#include "tests/io/design/nurbs_dxf.h"
#include "tests/pipeline/cli_harness.h"

using namespace fabmesh;
using namespace fabmesh::test;
namespace fs = std::filesystem;

namespace {

bool vertical(const TraceMotion& m) { return !m.arc && m.start.head<2>() == m.end.head<2>(); }
bool in_material(const TraceMotion& m) { return std::min(m.start.z(), m.end.z()) < 0.0; }

// What the interpreted program does, measured against the exact curves (millimetres; `mm`
// converts model units). Margins >= 0 are proven passes (Lipschitz walks), < 0 failures.
struct Findings {
  std::vector<std::string> unknown;    // codes the interpreter does not know
  int bad_rapids = 0;                  // G0 below safe height other than straight up to it
  double arc_radius_mismatch = 0.0;    // largest | |start - c| - |end - c| |
  int bad_feeds = 0;                   // plunges not at the plunge feed, cuts not at the feed
  std::vector<double> deepest;         // per loop: the lowest cutting level
  std::vector<double> largest_step;    // per loop: the largest step between levels
  double offset_margin = INFINITY;     // tol - | distance to the loop's exact curve - r |, cuts in material
  double clearance_margin = INFINITY;  // distance to the part - (r - tol), every move in material
  int outside_waste = 0;               // moves in material whose middle lies inside the part
  std::vector<double> coverage;  // per loop: (r + tol) - distance from its curve to the cut-through moves
  std::vector<double> tab_stretches;  // lengths of the raised stretches of the outline
  std::size_t tab_passes = 0;         // passes deep enough to need tabs
  std::vector<double> dogbone_reach;  // per dog-bone: | distance of its tip from the corner point - r |
};

// The program's numbers in millimetres, and the exact loops scaled to millimetres.
struct Setup {
  double r = 0, tol = 0, depth = 0, tab_z = 0, safe = 0;
  double ztol = 0.01;  // mm: z levels as the program's rounding leaves them
  std::vector<std::string> labels;
  std::vector<CompositeCurve> curves;
  std::vector<CurveDistance> exact;
  std::vector<std::vector<const TraceMotion*>> loops;  // motions in each loop's pass sections
};

CompositeCurve scaled(const CompositeCurve& c, double mm) {
  if (mm == 1.0) return c;
  std::vector<Segment> segs;
  for (const Segment& s : c.segments()) {
    if (s.kind() == SegmentKind::EllipseArc) {
      EllipseArcParams e = *s.ellipse();
      e.center *= mm, e.a *= mm, e.b *= mm;
      segs.push_back(Segment::ellipse_arc(e));
    } else {
      std::array<Vec2, 4> p = s.control_points();
      for (Vec2& q : p) q *= mm;
      segs.push_back(s.with_points(p));
    }
  }
  return CompositeCurve(segs, c.closed());
}

Setup setup(const ExampleRegion& region, const Toolpath& tp, const Trace& trace, double mm) {
  const CncOptions& o = tp.options;
  Setup st;
  st.r = 0.5 * o.tool_diameter * mm;
  st.tol = o.tolerance * mm;
  st.depth = (o.depth + o.breakthrough) * mm;
  st.tab_z = tp.tab_z * mm;
  st.safe = o.safe_z * mm;
  st.labels.push_back("outline");
  st.curves.push_back(scaled(region.outline, mm));
  for (const RegionHole& h : region.holes)
    st.labels.push_back(h.label), st.curves.push_back(scaled(h.curve, mm));
  for (const CompositeCurve& c : st.curves) st.exact.emplace_back(c, 0.5);
  // Group motions by the loop whose pass comments precede them.
  st.loops.resize(st.labels.size());
  for (const TraceMotion& m : trace.motions) {
    for (std::size_t l = 0; l < st.labels.size(); ++l) {
      std::string label = st.labels[l];
      for (char& c : label) c = c == '(' ? '[' : c == ')' ? ']' : c;
      if (m.section.rfind(label + ": pass", 0) == 0) st.loops[l].push_back(&m);
    }
  }
  return st;
}

// Rapids only at safe height (or straight up to it), arcs with one radius, the asked feeds.
void measure_moves(const Setup& st, const CncOptions& o, double mm, const Trace& trace, Findings& f) {
  for (const TraceMotion& m : trace.motions) {
    if (m.motion == "G0") {
      const bool up = vertical(m) && std::abs(m.end.z() - st.safe) < st.ztol && m.end.z() >= m.start.z();
      const bool level = std::abs(m.start.z() - st.safe) < st.ztol && std::abs(m.end.z() - st.safe) < st.ztol;
      f.bad_rapids += !(up || level);
      continue;
    }
    if (m.arc) {
      const double r0 = (m.start.head<2>() - m.center.head<2>()).norm();
      const double r1 = (m.end.head<2>() - m.center.head<2>()).norm();
      f.arc_radius_mismatch = std::max(f.arc_radius_mismatch, std::abs(r0 - r1));
    }
    const double want = vertical(m) ? o.plunge * mm : o.feed * mm;
    f.bad_feeds += std::abs(m.feed - want) > 1e-4 * want;  // F is rounded like the coordinates
  }
}

// The cutting levels of each loop: the deepest and the largest step between them.
void measure_levels(const Setup& st, const CncOptions& o, Findings& f) {
  for (std::size_t l = 0; l < st.labels.size(); ++l) {
    std::set<double> levels;
    for (const TraceMotion* m : st.loops[l]) {
      if (!vertical(*m) && m->start.z() < 0 && m->comment.empty()) levels.insert(m->start.z());
    }
    f.deepest.push_back(levels.empty() ? 0.0 : *levels.begin());
    double prev = 0.0, step = 0.0;
    for (auto it = levels.rbegin(); it != levels.rend(); ++it) {
      if (l == 0 && o.tabs.count > 0 && std::abs(*it - st.tab_z) < st.ztol) continue;
      step = std::max(step, prev - *it);
      prev = *it;
    }
    f.largest_step.push_back(step);
  }
}

// On the distinct moves in material (passes repeat the same path): the exact offset
// (|distance to the loop's curve - r| <= tol), nothing of the part cut (distance to every
// loop >= r - tol, the middle in the waste), dog-bones reaching their corner point.
void measure_paths(const Setup& st, const Toolpath& tp, double mm, Findings& f) {
  std::map<std::string, std::pair<const TraceMotion*, std::size_t>> distinct;
  for (std::size_t l = 0; l < st.labels.size(); ++l) {
    for (const TraceMotion* m : st.loops[l]) {
      if (!in_material(*m) || vertical(*m)) continue;
      distinct.emplace(
          fmt::format("{:.6f} {:.6f} {:.6f} {:.6f} {} {:.6f} {:.6f} {}", m->start.x(), m->start.y(),
                      m->end.x(), m->end.y(), m->motion, m->center.x(), m->center.y(), m->comment),
          std::pair{m, l});
    }
  }
  const double r = st.r, tol = st.tol;
  for (const auto& [key, entry] : distinct) {
    const auto [m, l] = entry;
    if (m->comment == "dogbone") {  // X -> D and back: at D the tool's disc reaches the corner point exactly
      double reach = INFINITY;
      for (const LoopCheck& c : tp.checks.loops) {
        for (const LoopCorner& k : c.concave_corners) {
          for (const Vec3& end : {m->start, m->end}) {
            reach = std::min(reach, std::abs((end.head<2>() - mm * k.at).norm() - r));
          }
        }
      }
      f.dogbone_reach.push_back(reach);
      continue;
    }
    if (m->comment != "lead in" && m->comment != "lead out" && m->comment != "helix") {
      const CurveDistance& own = st.exact[l];
      f.offset_margin = std::min(
          f.offset_margin,
          lipschitz_walk(
              *m, [&](const Vec2& p) { return tol - std::abs(own.nearest(p, 2.0 * r).distance - r); }, 1e-4,
              nullptr));
    }
    f.clearance_margin = std::min(f.clearance_margin, lipschitz_walk(
                                                          *m,
                                                          [&](const Vec2& p) {
                                                            double d = INFINITY;
                                                            for (const CurveDistance& e : st.exact) {
                                                              d = std::min(d, e.nearest(p, r + 1.0).distance);
                                                            }
                                                            return d - (r - tol);
                                                          },
                                                          1e-4, nullptr));
    const Vec2 mid = motion_point(*m, 0.5).head<2>();
    bool waste = !inside_polygon(st.exact[0].polygon(), mid);
    for (std::size_t h = 1; h < st.exact.size(); ++h)
      waste = waste || inside_polygon(st.exact[h].polygon(), mid);
    f.outside_waste += !waste;
  }
}

// Cut through: each point of a loop's exact curve within r + tol of a full-depth move (the
// outline's, under a tab, of a move at the tab height instead).
void measure_coverage(const Setup& st, Findings& f) {
  for (std::size_t l = 0; l < st.labels.size(); ++l) {
    std::vector<const TraceMotion*> full, raised;
    for (const TraceMotion* m : st.loops[l]) {
      if (vertical(*m) || m->motion == "G0") continue;
      if (std::abs(m->start.z() + st.depth) < st.ztol) full.push_back(m);
      if (std::abs(m->start.z() - st.tab_z) < st.ztol && m->comment.empty()) raised.push_back(m);
    }
    auto reach = [&](const std::vector<const TraceMotion*>& set, const Vec2& q) {
      double d = INFINITY;
      for (const TraceMotion* m : set) d = std::min(d, motion_distance(*m, q));
      return (st.r + st.tol) - d;
    };
    f.coverage.push_back(lipschitz_walk_curve(
        st.curves[l],
        [&](const Vec2& q) { return l == 0 ? std::max(reach(full, q), reach(raised, q)) : reach(full, q); },
        1e-4, nullptr));
  }
}

// Tabs: the raised stretches of the outline, from a tab step up to a tab step down.
void measure_tabs(const Setup& st, const Toolpath& tp, Findings& f) {
  double run = -1.0;
  for (const TraceMotion* m : st.loops[0]) {
    if (m->comment == "tab" && m->end.z() > m->start.z()) run = 0.0;
    if (run >= 0.0 && !vertical(*m))
      run += std::abs(m->start.z() - st.tab_z) < st.ztol ? motion_length(*m) : INFINITY;
    if (m->comment == "tab" && m->end.z() < m->start.z()) f.tab_stretches.push_back(run), run = -1.0;
  }
  f.tab_passes = static_cast<std::size_t>(
      std::count_if(tp.pass_z.begin(), tp.pass_z.end(), [&](double z) { return z < tp.tab_z - 1e-9; }));
}

Findings measure_program(const ExampleRegion& region, const Toolpath& tp, const Trace& trace, double mm) {
  const Setup st = setup(region, tp, trace, mm);
  Findings f;
  f.unknown = trace.unknown;
  measure_moves(st, tp.options, mm, trace, f);
  measure_levels(st, tp.options, f);
  measure_paths(st, tp, mm, f);
  measure_coverage(st, f);
  measure_tabs(st, tp, f);
  return f;
}

// Everything the brief asks of a program.
void require_good_program(const Findings& f, const Toolpath& tp, double mm) {
  const CncOptions& o = tp.options;
  const double depth = (o.depth + o.breakthrough) * mm;
  CHECK(f.unknown.empty());
  CHECK(f.bad_rapids == 0);
  CHECK(f.arc_radius_mismatch <= 5e-3);  // mm: rounding of the end point and the centre
  CHECK(f.bad_feeds == 0);
  for (std::size_t l = 0; l < f.deepest.size(); ++l) {
    INFO("loop " << l);
    CHECK(f.deepest[l] == Approx(-depth).margin(0.01));
    CHECK(f.largest_step[l] <= o.step_down * mm + 0.01);
    CHECK(f.coverage[l] >= 0.0);
  }
  CHECK(f.offset_margin >= 0.0);
  CHECK(f.clearance_margin >= 0.0);
  CHECK(f.outside_waste == 0);
  CHECK(f.tab_stretches.size() == o.tabs.count * f.tab_passes);
  for (double s : f.tab_stretches)
    CHECK(s == Approx((o.tabs.width + o.tool_diameter) * mm).margin(o.tolerance * mm));
  // Tabs spread: each within its own share of the outline's path around its ideal place.
  const LoopPath& outline = tp.loops.back();
  const double share = outline.length / static_cast<double>(std::max<std::size_t>(1, o.tabs.count));
  for (std::size_t j = 0; j < outline.tabs.size(); ++j) {
    const double centre = 0.5 * (outline.tabs[j].first + outline.tabs[j].second);
    CHECK(std::abs(centre - (static_cast<double>(j) + 0.5) * share) < 0.5 * share);
  }
  for (double d : f.dogbone_reach) CHECK(d <= 2e-3 * mm);
}

CncOptions options_for(const ExampleRegion& region) {
  CncOptions o;
  o.depth = region.thickness;
  o.tolerance = region.tolerance;
  return o;
}

// Plans, encodes, interprets and measures; `verify` as planned with `plan`'s tool unless given.
Findings run_example(const ExampleRegion& region, const CncOptions& plan, const GcodeOptions& g = {},
                     const CncOptions* verify = nullptr, Toolpath* planned = nullptr) {
  Toolpath tp = plan_toolpath(region.outline, region.holes, plan);
  GcodeOptions go = g;
  go.name = region.name;
  const std::string program = encode_gcode(tp, go);
  const Trace trace = interpret(program, region.name + ".nc");
  if (verify) tp.options = *verify;
  const double mm = millimetres_per_unit(go.model_units);
  Findings f = measure_program(region, tp, trace, mm);
  if (planned) *planned = std::move(tp);
  return f;
}

void verify_example(const std::string& file, CncOptions o, const GcodeOptions& g = {}) {
  const ExampleRegion region = load_countertop_example(file);
  Toolpath tp;
  const Findings f = run_example(region, o, g, nullptr, &tp);
  require_good_program(f, tp, millimetres_per_unit(g.model_units));
}

}  // namespace

TEST_CASE("router program: countertop_g1 interpreted by CNCjs cuts the exact offset, every hole, the tabs",
          "[io][cutting][gcode][toolpath][countertop]") {
  const ExampleRegion region = load_countertop_example("countertop_g1.yaml");
  verify_example("countertop_g1.yaml", options_for(region));
}

TEST_CASE("router program: countertop_g2 (exact oval sink) conventional, with a breakthrough",
          "[io][cutting][gcode][toolpath][countertop]") {
  const ExampleRegion region = load_countertop_example("countertop_g2.yaml");
  CncOptions o = options_for(region);
  o.direction = CutDirection::Conventional;
  o.breakthrough = 0.5;
  o.tabs.count = 6;
  verify_example("countertop_g2.yaml", o);
}

TEST_CASE(
    "router program: countertop_asymmetric_line, its rotated cooktop with 8 mm corners accepted for a 12 mm "
    "tool",
    "[io][cutting][gcode][toolpath][countertop]") {
  const ExampleRegion region = load_countertop_example("countertop_asymmetric_line.yaml");
  verify_example("countertop_asymmetric_line.yaml", options_for(region));
}

TEST_CASE(
    "router program: countertop_symmetric_ellipse is refused at its concave bump corners without relief",
    "[io][cutting][gcode][toolpath][countertop][errors]") {
  const ExampleRegion region = load_countertop_example("countertop_symmetric_ellipse.yaml");
  try {
    plan_toolpath(region.outline, region.holes, options_for(region));
    FAIL("a concave G0 corner was accepted without relief");
  } catch (const GeometryError& e) {
    CHECK(e.where() == "outline");
    const std::string what = e.what();
    CHECK_THAT(what, Catch::Contains("segment 3 (line)") && Catch::Contains("segment 4 (ellipse_arc)"));
    CHECK_THAT(what, Catch::Contains("(1600, 650)") && Catch::Contains("90 degrees"));
    CHECK_THAT(what, Catch::Contains("relief: dogbone"));
  }
}

TEST_CASE("router program: countertop_symmetric_ellipse with dog-bones reaches both corner points",
          "[io][cutting][gcode][toolpath][countertop]") {
  const ExampleRegion region = load_countertop_example("countertop_symmetric_ellipse.yaml");
  CncOptions o = options_for(region);
  o.relief = CornerRelief::Dogbone;
  Toolpath tp;
  const Findings f = run_example(region, o, {}, nullptr, &tp);
  require_good_program(f, tp, 1.0);
  CHECK(f.dogbone_reach.size() == 4);  // into each bump corner and back (passes repeat the same moves)
}

TEST_CASE("router program: inch output (G20) interprets to the same cut in millimetres",
          "[io][cutting][gcode][toolpath][countertop]") {
  const ExampleRegion region = load_countertop_example("countertop_g1.yaml");
  GcodeOptions g;
  g.units = "in";
  const Toolpath tp = plan_toolpath(region.outline, region.holes, options_for(region));
  const std::string program = encode_gcode(tp, g);
  CHECK(program.find("G20 G90 G94 G17") != std::string::npos);
  const Trace trace = interpret(program, "countertop_g1_in.nc");
  CHECK(trace.units == "G20");
  require_good_program(measure_program(region, tp, trace, 1.0), tp, 1.0);
}

TEST_CASE(
    "router program: the measurements catch a path 0.2 mm off, a tool cutting into the part, missing tabs",
    "[io][cutting][gcode][toolpath][countertop]") {
  const ExampleRegion region = load_countertop_example("countertop_g1.yaml");
  const CncOptions asked = options_for(region);
  CncOptions wider = asked, narrower = asked, no_tabs = asked;
  wider.tool_diameter += 0.4;     // the program keeps 0.2 mm too far from the part
  narrower.tool_diameter -= 0.4;  // the program cuts 0.2 mm into the part
  no_tabs.tabs.count = 0;
  const Findings far = run_example(region, wider, {}, &asked);
  CHECK(far.offset_margin < 0.0);
  CHECK(far.clearance_margin >= 0.0);
  const Findings gouge = run_example(region, narrower, {}, &asked);
  CHECK(gouge.offset_margin < 0.0);
  CHECK(gouge.clearance_margin < 0.0);
  const Findings untabbed = run_example(region, no_tabs, {}, &asked);
  CHECK(untabbed.tab_stretches.empty());
  CHECK(untabbed.offset_margin >= 0.0);
}

TEST_CASE("router program: the estimated lengths and time are those of the program CNCjs interprets",
          "[io][cutting][gcode][toolpath][countertop]") {
  for (const char* file : {"countertop_g1.yaml", "countertop_dxf_template.yaml"}) {
    INFO(file);
    const ExampleRegion region = load_countertop_example(file);
    const CncOptions o = options_for(region);
    const Toolpath tp = plan_toolpath(region.outline, region.holes, o);
    const std::string program = encode_gcode(tp, {});
    const Trace trace = interpret(program, std::string(file) + ".nc");
    const ToolpathTotals totals = toolpath_totals(tp);
    // What the controller runs at the cutting feed and at the plunge feed, by
    // the interpreter's own geometry (arcs by radius and turn).
    double cutting = 0.0, plunging = 0.0;
    for (const TraceMotion& m : trace.motions) {
      if (m.motion == "G0") continue;
      const double length = std::hypot(motion_length(m), m.end.z() - m.start.z());
      if (m.feed == o.feed) cutting += length;
      if (m.feed == o.plunge) plunging += length;
    }
    // Each move's ends are rounded to the program's decimals.
    const double slack = 4e-3 * static_cast<double>(trace.motions.size());
    CHECK(totals.cutting > 0.0);
    CHECK(std::abs(cutting - totals.cutting) <= slack);
    CHECK(std::abs(plunging - totals.plunging) <= slack);
    CHECK(totals.rapid > 0.0);
    CHECK(
        totals.minutes ==
        Approx(totals.cutting / o.feed + totals.plunging / o.plunge + totals.rapid / o.rapid).epsilon(1e-12));
    CHECK(program.find(fmt::format("(estimated {:.1f} min without acceleration: cutting ", totals.minutes)) !=
          std::string::npos);
  }
}

TEST_CASE("router program: a ramp entry, tabs on cut-outs and a finishing pass run in CNCjs as planned",
          "[io][cutting][gcode][toolpath][countertop][ramp][finish]") {
  const ExampleRegion region = load_countertop_example("countertop_g1.yaml");
  CncOptions o = options_for(region);
  o.entry = EntryKind::Ramp;
  o.ramp_angle_deg = 1;  // a ramp long enough to reach the sink's corner arcs
  TabOptions slug;       // two tabs on each cut-out, 5 high
  slug.count = 2;
  slug.height = 5;
  o.hole_tabs.assign(region.holes.size(), slug);
  o.finish = 0.5;
  const Toolpath tp = plan_toolpath(region.outline, region.holes, o);
  REQUIRE(tp.warnings.empty());
  const std::string program = encode_gcode(tp, {});
  CHECK(program.find("(entry: zig-zag ramp at 1 degrees along the path)") != std::string::npos);
  const Trace trace = interpret(program, "ramp.nc");
  CHECK(trace.unknown.empty());
  const double slope = std::tan(1 * M_PI / 180);
  int ramps = 0, helices = 0, hole_tab_moves = 0;
  const double hole_tab_z = -(o.depth - 5);
  for (const TraceMotion& m : trace.motions) {
    if (m.motion == "G0") continue;
    const double drop = m.start.z() - m.end.z();
    const double run = motion_length(m);
    if (m.comment == "ramp") {
      ++ramps;
      helices += m.arc && drop > 0.0 ? 1 : 0;
      // Down along the path no steeper than the ramp (ends rounded to the program's decimals).
      CHECK(drop <= slope * run + 2e-3);
      CHECK(m.feed == o.feed);
    } else if (drop > 1e-9 && m.end.z() < 0.0) {
      // Any other way down in material is a straight vertical move at the plunge feed into the
      // floor already cut (from a tab, or to the previous pass's floor in the waste).
      CHECK(vertical(m));
      CHECK(m.feed == o.plunge);
    }
    if (m.section.rfind("holes", 0) == 0 && !vertical(m) && std::abs(m.start.z() - hole_tab_z) < 1e-3 &&
        std::abs(m.end.z() - hole_tab_z) < 1e-3)
      ++hole_tab_moves;
  }
  CHECK(ramps > 0);
  CHECK(helices > 0);  // the sink's corner arcs on the ramp are helices
  CHECK(hole_tab_moves > 0);
  // One finishing pass per loop, every motion of it at full depth or over a tab.
  std::set<std::string> finished;
  for (const TraceMotion& m : trace.motions) {
    if (m.section.find("finishing pass") == std::string::npos || m.motion == "G0") continue;
    finished.insert(m.section);
    if (!vertical(m)) CHECK((std::abs(m.end.z() + o.depth) < 1e-3 || m.end.z() > -o.depth + 2.9));
  }
  CHECK(finished.size() == tp.loops.size());
  // The program's time estimate is the interpreted program's.
  const ToolpathTotals totals = toolpath_totals(tp);
  double cutting = 0.0;
  for (const TraceMotion& m : trace.motions) {
    if (m.motion != "G0" && m.feed == o.feed)
      cutting += std::hypot(motion_length(m), m.end.z() - m.start.z());
  }
  CHECK(std::abs(cutting - totals.cutting) <= 4e-3 * static_cast<double>(trace.motions.size()));
}

namespace {

// The digitised worktop of toolpath_test.cpp: a concave front of radius 19 m by 301 points,
// convex back corners of radius 100 by 41 points each, and a digitised round sink of radius
// 200 by 360 points.
ExampleRegion digitised_worktop() {
  const std::vector<Vec2> p = digitised_worktop_points();
  std::vector<Vec2> sink;
  for (int i = 0; i < 360; ++i) {
    const double a = 2.0 * M_PI * i / 360;
    sink.emplace_back(900 + 200 * std::cos(a), 380 + 200 * std::sin(a));
  }
  ExampleRegion region;
  region.outline = polygon(p);
  region.holes.push_back({polygon(sink), "holes[0] (outline)"});
  region.thickness = 30;
  region.tolerance = 0.05;
  region.name = "digitised_worktop";
  return region;
}

struct MoveCounts {
  int lines = 0, arcs = 0;
};

// G1 and G2/G3 moves along the paths in material (not vertical, not leads, ramps or helices).
MoveCounts count_cuts(const Trace& trace) {
  MoveCounts c;
  for (const TraceMotion& m : trace.motions) {
    if (m.motion == "G0" || vertical(m) || !in_material(m) || !m.comment.empty()) continue;
    (m.arc ? c.arcs : c.lines) += 1;
  }
  return c;
}

}  // namespace

namespace {

// A 1200 x 600 worktop whose 80 mm corners are NURBS quarter circles (one
// drawn backwards) and an oval sink saved as a NURBS ellipse (the circle's
// control points stretched: 200 x 120).
ExampleRegion nurbs_worktop() {
  const double k = std::sqrt(0.5);
  std::string entities =
      dxf_line("A1", "OUTLINE", {80, 0}, {1120, 0}) + dxf_line("A2", "OUTLINE", {1200, 80}, {1200, 520}) +
      dxf_line("A3", "OUTLINE", {1120, 600}, {80, 600}) + dxf_line("A4", "OUTLINE", {0, 520}, {0, 80});
  entities += dxf_nurbs("B1", "OUTLINE", {{1120, 0}, {1200, 0}, {1200, 80}}, {1, k, 1});
  entities += dxf_nurbs("B2", "OUTLINE", {{1200, 520}, {1200, 600}, {1120, 600}}, {1, k, 1});
  entities += dxf_nurbs("B3", "OUTLINE", {{0, 520}, {0, 600}, {80, 600}}, {1, k, 1});  // backwards
  entities += dxf_nurbs("B4", "OUTLINE", {{0, 80}, {0, 0}, {80, 0}}, {1, k, 1});
  entities += dxf_nurbs_ellipse("C1", "HOLES", {600, 300}, 200, 120);
  const std::string text = dxf_drawing(entities);
  DxfLoopQuery q;
  q.units = "mm";
  q.layer = "OUTLINE";
  ExampleRegion region;
  const DxfLoops outline = parse_dxf_loops(text, "nurbs_worktop.dxf", q);
  REQUIRE(outline.loops.size() == 1);
  region.outline = build_curve(outline.loops[0].curve).curve;
  q.layer = "HOLES";
  const DxfLoops holes = parse_dxf_loops(text, "nurbs_worktop.dxf", q);
  REQUIRE(holes.loops.size() == 1);
  region.holes.push_back({build_curve(holes.loops[0].curve).curve, "holes[0] (dxf)"});
  region.thickness = 30;
  region.tolerance = 0.05;
  region.name = "nurbs_worktop";
  return region;
}

}  // namespace

TEST_CASE("router program: NURBS corners and a NURBS oval sink are cut on their exact offsets",
          "[io][cutting][gcode][toolpath][countertop][rational]") {
  const ExampleRegion region = nurbs_worktop();
  std::size_t rational = 0;
  for (const Segment& s : region.outline.segments()) rational += s.kind() == SegmentKind::RationalBezier;
  for (const Segment& s : region.holes[0].curve.segments())
    rational += s.kind() == SegmentKind::RationalBezier;
  CHECK(rational == 8);
  CHECK(std::abs(exact_area(region.outline)) ==
        Approx(1200.0 * 600.0 - (4.0 - M_PI) * 6400.0).epsilon(1e-12));
  CHECK(std::abs(exact_area(region.holes[0].curve)) == Approx(M_PI * 200.0 * 120.0).epsilon(1e-12));
  Toolpath tp;
  const Findings f = run_example(region, options_for(region), {}, nullptr, &tp);
  require_good_program(f, tp, 1.0);
}

TEST_CASE("router program: a digitised worktop cut in fitted arcs runs in CNCjs on the exact offset",
          "[io][cutting][gcode][toolpath][countertop][arcfit][digitised]") {
  const ExampleRegion region = digitised_worktop();
  CncOptions o = options_for(region);
  o.arc_fit = false;
  Toolpath plain_tp;
  const Findings plain = run_example(region, o, {}, nullptr, &plain_tp);
  require_good_program(plain, plain_tp, 1.0);
  o.arc_fit = true;
  Toolpath tp;
  const Findings fitted = run_example(region, o, {}, nullptr, &tp);
  require_good_program(fitted, tp, 1.0);
  CHECK(tp.deviation <= 0.5 * o.tolerance);
  const Trace before = interpret(encode_gcode(plain_tp, {}), "digitised_plain.nc");
  const std::string program = encode_gcode(tp, {});
  const Trace after = interpret(program, "digitised_fitted.nc");
  const MoveCounts b = count_cuts(before), a = count_cuts(after);
  // Fewer lines: most of the G1 moves (and the tool's tiny arcs round the points) become arcs.
  CHECK(a.lines + a.arcs < (b.lines + b.arcs) / 10);
  CHECK(a.lines < b.lines / 10);
  WARN("digitised worktop, moves along the path in material: "
       << b.lines << " G1 + " << b.arcs << " G2/G3 without arc fitting, " << a.lines << " G1 + " << a.arcs
       << " G2/G3 with (" << tp.fit_replaced << " pieces as " << tp.fit_arcs << " arcs and " << tp.fit_lines
       << " lines, within " << tp.fit_deviation << ")");
  CHECK_THAT(program, Catch::Contains(fmt::format("(arc fitting: {} line and corner moves fitted as {} arcs",
                                                  tp.fit_replaced, tp.fit_arcs)));
  // The estimate is the interpreted program's.
  double cutting = 0.0;
  for (const TraceMotion& m : after.motions) {
    if (m.motion != "G0" && m.feed == o.feed)
      cutting += std::hypot(motion_length(m), m.end.z() - m.start.z());
  }
  CHECK(std::abs(cutting - toolpath_totals(tp).cutting) <= 4e-3 * static_cast<double>(after.motions.size()));
}

TEST_CASE("router program: arc fitting on the examples' curved chains keeps every measured property",
          "[io][cutting][gcode][toolpath][countertop][arcfit]") {
  for (const char* file : {"countertop_g1.yaml", "countertop_g2.yaml", "countertop_dxf_template.yaml"}) {
    INFO(file);
    const ExampleRegion region = load_countertop_example(file);
    CncOptions o = options_for(region);
    o.arc_fit = true;
    Toolpath tp;
    const Findings f = run_example(region, o, {}, nullptr, &tp);
    require_good_program(f, tp, 1.0);
    CHECK(tp.deviation <= 0.5 * o.tolerance);
  }
}

TEST_CASE("router program: a helix entry descends in the waste at the pitch angle to every pass's depth",
          "[io][cutting][gcode][toolpath][countertop][helix]") {
  for (const char* file : {"countertop_g1.yaml", "countertop_cnc.yaml"}) {
    INFO(file);
    const ExampleRegion region = load_countertop_example(file);
    CncOptions o = options_for(region);
    o.entry = EntryKind::Helix;
    o.ramp_angle_deg = 2;
    Toolpath tp;
    const Findings f = run_example(region, o, {}, nullptr, &tp);
    // Every move in material, the helices included, keeps the tool clear of the part (the
    // clearance walk), and the loops are cut through as before.
    require_good_program(f, tp, 1.0);
    const std::string program = encode_gcode(tp, {});
    const Trace trace = interpret(program, std::string("helix_") + file + ".nc");
    const double slope = std::tan(2 * M_PI / 180);
    std::map<std::string, std::set<double>> floors;  // per pass section: the depths the helix reached
    int helix_moves = 0;
    for (const TraceMotion& m : trace.motions) {
      if (m.motion == "G0") continue;
      const double drop = m.start.z() - m.end.z();
      if (m.comment == "helix") {
        ++helix_moves;
        CHECK(m.arc);
        CHECK(drop >= -1e-9);
        CHECK(drop <= slope * motion_length(m) + 2e-3);
        CHECK(m.feed == o.feed);
        floors[m.section].insert(m.end.z());
      } else if (drop > 1e-9 && m.end.z() < 0.0) {
        // Any other way down in material is vertical into the floor already cut.
        CHECK(vertical(m));
      }
    }
    CHECK(helix_moves > 0);
    // Each pass's helix reaches that pass's depth, where the pass's cut runs.
    std::size_t passes = 0;
    for (const auto& [section, zs] : floors) {
      INFO(section);
      const auto pos = section.find("at z ");
      REQUIRE(pos != std::string::npos);
      const double z = std::stod(section.substr(pos + 5));
      CHECK(*zs.begin() == Approx(z).margin(1e-3));
      ++passes;
    }
    CHECK(passes == tp.loops.size() * tp.pass_z.size());
    for (const LoopPath& lp : tp.loops) {
      REQUIRE(lp.helix);
      CHECK(piece_radius(*lp.helix) <= 0.5 * 0.5 * o.tool_diameter + 1e-12);
      CHECK(std::abs(lp.helix->sweep) == Approx(2 * M_PI));
      CHECK_THAT(program, Catch::Contains(lp.outer ? "(outline: entry: helix of radius "
                                                   : "]: entry: helix of radius "));
    }
  }
}

TEST_CASE("router program: a helix entry with no room in the waste is refused naming the loop and radius",
          "[io][cutting][gcode][toolpath][countertop][helix][errors]") {
  // A slot 13 wide for a 12 mm tool: the tool's centre runs a line; no circle fits beside it.
  const CompositeCurve slab = polygon({Vec2(0, 0), Vec2(900, 0), Vec2(900, 600), Vec2(0, 600)});
  const std::vector<RegionHole> holes{{rounded_rect(300, 293.5, 600, 306.5, 6.4), "holes[0] (rounded_rect)"}};
  CncOptions o;
  o.tabs.count = 0;
  o.entry = EntryKind::Helix;
  o.tolerance = 0.05;
  o.min_web = 0;
  try {
    plan_toolpath(slab, holes, o);
    FAIL("accepted");
  } catch (const GeometryError& e) {
    CHECK(e.where() == "holes[0] (rounded_rect)");
    CHECK_THAT(std::string(e.what()), Catch::Contains("no room in the waste for a helix entry") &&
                                          Catch::Contains("needs a clear circle of radius 6.75"));
  }
  o.helix_radius = 7;  // more than the tool radius: out of range
  CHECK_THROWS_AS(plan_toolpath(slab, holes, o), RangeError);
}

TEST_CASE("router program: the digitised example (a CSV of points) is cut in fitted arcs, verified by CNCjs",
          "[io][cutting][gcode][toolpath][countertop][arcfit][digitised]") {
  const ExampleRegion region = load_countertop_example("countertop_digitised.yaml");
  Toolpath tp;
  const Findings f = run_example(region, options_for(region), {}, nullptr, &tp);
  require_good_program(f, tp, 1.0);
  CHECK(tp.checks.loops[0].concave_corners.empty());
  CHECK(tp.fit_replaced > 400);
  CHECK(tp.fit_arcs < tp.fit_replaced / 10);
  CHECK(tp.deviation <= 0.5 * region.tolerance);
  CHECK(count_cuts(interpret(encode_gcode(tp, {}), "countertop_digitised.nc")).lines < 60);
}

namespace {

// countertop_cnc.yaml with three tap holes: 35 mm behind the sink, 28 mm
// between the sink and the cooktop, 35 mm at the left end; `cnc` goes on in
// its cnc section. Written to dir/name.
std::string tap_hole_design(const fs::path& dir, const std::string& name, const std::string& cnc) {
  std::string text = read_file(testing::example("countertop_cnc.yaml"));
  const std::string cooktop = "radius: 10}   # cooktop\n";
  const auto at = text.find(cooktop);
  REQUIRE(at != std::string::npos);
  text.insert(at + cooktop.size(),
              "  - drill: {center: [650, 595], diameter: 35}\n"
              "  - drill: {center: [1150, 595], diameter: 28}\n"
              "  - drill: {center: [150, 400], diameter: 35}\n");
  text += cnc;
  testing::write_text(dir / name, text);
  return (dir / name).string();
}

}  // namespace

TEST_CASE("router program: tap holes are drilled first, one canned cycle each, the routing runs as before",
          "[io][cutting][gcode][toolpath][countertop][drill]") {
  const fs::path dir = testing::fresh_dir("router_tap_holes");
  struct Variant {
    std::string name, cnc;
    std::map<int, DrillSpec::Tool> tools;
    int end_mill = 1;
    double peck = 0.0, feed = 600.0, retract = 10.0;
    std::string header;
  };
  const std::vector<Variant> variants{
      // No tool table: the router bit is T1, the 35 mm drill T2, the 28 mm one T3; G81 at the plunge feed.
      {"numbered.yaml",
       "",
       {{1, {ToolType::EndMill, 12}}, {2, {ToolType::Drill, 35}}, {3, {ToolType::Drill, 28}}},
       1,
       0.0,
       600.0,
       10.0,
       "(tools: T1 end mill 12 mm, T2 drill 35 mm, T3 drill 28 mm)"},
      // A table (two 35 mm drills: the lower number drills), pecks, an R plane, an inch program.
      {"table.yaml",
       "  tools:\n    - {number: 5, type: end_mill, diameter: 12}\n    - {number: 8, type: drill, diameter: "
       "35}\n"
       "    - {number: 7, type: drill, diameter: 35}\n    - {number: 3, type: drill, diameter: 28}\n"
       "  drill: {peck: 8, retract: 3, feed: 250, spindle: 3000}\n  units: in\n",
       {{5, {ToolType::EndMill, 12}},
        {8, {ToolType::Drill, 35}},
        {7, {ToolType::Drill, 35}},
        {3, {ToolType::Drill, 28}}},
       5,
       8.0,
       250.0,
       3.0,
       "(tools: T5 end mill 0.4724 in, T3 drill 1.1024 in, T7 drill 1.378 in)"},
  };
  for (const Variant& v : variants) {
    INFO(v.name);
    const std::string path = tap_hole_design(dir, v.name, v.cnc);
    Design design = read_design(path);
    design.common.outputs = {{"nc", "test", 0, 0}, {"toolpath_svg", "test", 0, 0}};
    const fs::path out = dir / (v.name + "-out");
    const Result r = run_job(design, testing::into(out));
    const auto& c = std::get<CountertopDesign>(design.body);
    REQUIRE(std::get<CountertopProducts>(r.products).toolpath);
    const Toolpath& tp = *std::get<CountertopProducts>(r.products).toolpath;
    const std::string program = read_file((out / "countertop_cnc.nc").string());
    // The holes where the design puts them, and what drills them.
    std::vector<ExpectedDrill> holes;
    for (std::size_t i = 0; i < c.holes.size(); ++i) {
      if (c.holes[i].drill)
        holes.push_back({c.holes[i].drill->center, c.holes[i].drill->diameter, fmt::format("holes[{}]", i)});
    }
    REQUIRE(holes.size() == 3);
    DrillSpec spec;
    spec.thickness = c.thickness;
    spec.through = tp.options.depth + tp.options.breakthrough;
    spec.safe_z = tp.options.safe_z;
    spec.feed = v.feed;
    spec.peck = v.peck;
    spec.rounding = tp.rounding_allowance;
    spec.tools = v.tools;
    spec.end_mill = v.end_mill;
    const CannedCycles cycles = read_canned_cycles(program);
    check_drilling(cycles, holes, spec);
    for (const DrillBlock& b : cycles.blocks)
      CHECK(b.r * (cycles.units == "G20" ? 25.4 : 1.0) == Approx(v.retract).margin(spec.rounding));
    CHECK(cycles.changes.size() == 3);  // two drills, then the end mill
    CHECK_THAT(program, Catch::Contains(v.header));
    CHECK_THAT(program, Catch::Contains(fmt::format("\nM6 T{}\n", v.end_mill)));
    // The rest of the program, run by CNCjs: the routed loops cut as every program's are.
    const Trace trace = interpret_around_cycles(program, cycles, v.name + ".nc");
    ExampleRegion region = load_countertop_example(path);
    region.holes.erase(
        std::remove_if(region.holes.begin(), region.holes.end(),
                       [](const RegionHole& h) { return h.label.find("(drill)") != std::string::npos; }),
        region.holes.end());
    REQUIRE(region.holes.size() == 2);
    REQUIRE(tp.loops.size() == 3);  // the sink, the cooktop, the outline: the tap holes are not routed
    require_good_program(measure_program(region, tp, trace, 1.0), tp, 1.0);
    // The estimate counts the cycles: each feeds down from R through the slab.
    const ToolpathTotals totals = toolpath_totals(tp);
    CHECK(totals.drilling == Approx(3 * (v.retract + spec.through)));
    CHECK(totals.minutes == Approx(totals.cutting / tp.options.feed + totals.plunging / tp.options.plunge +
                                   totals.rapid / tp.options.rapid + totals.drilling / v.feed)
                                .epsilon(1e-12));
    // The drawing marks each drilled hole: its circle and a cross.
    const std::string svg = read_file((out / "countertop_cnc.toolpath.svg").string());
    for (std::size_t k = 0; k < 3; ++k) {
      CHECK_THAT(svg, Catch::Contains(fmt::format("<g id=\"drill-{}\"", k)));
      CHECK_THAT(svg, Catch::Contains(fmt::format("r=\"{}\"/><path d=\"M ", 0.5 * tp.drills[k].diameter)));
    }
    // The same design, the same bytes.
    const Result again = run_job(design, testing::into(dir / (v.name + "-again")));
    CHECK(read_file((dir / (v.name + "-again") / "countertop_cnc.nc").string()) == program);
  }
}
