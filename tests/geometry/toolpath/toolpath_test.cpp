// The planned toolpath as data: passes, directions, corner arcs, dog-bones,
// tabs and leads on shapes built in code.

#include "geometry/toolpath/toolpath.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "geometry/core/errors.h"
#include "tests/geometry/section/region_shapes.h"
#include "tests/geometry/toolpath/digitised_worktop.h"

using namespace fabmesh;
using namespace fabmesh::test;

namespace {

const CompositeCurve kSlab = polygon({Vec2(0, 0), Vec2(900, 0), Vec2(900, 600), Vec2(0, 600)});

CncOptions base() {
  CncOptions o;
  o.tabs.min_radius = 1000;
  return o;
}

// Twice the signed area swept by a closed path (arcs by their exact segment area).
double signed_area2(const std::vector<PathPiece>& pieces) {
  double a = 0.0;
  for (const PathPiece& p : pieces) {
    a += cross2(p.from, p.to);
    if (p.kind == PieceKind::Arc) {
      const double r = piece_radius(p);
      a += r * r * (p.sweep - std::sin(p.sweep));  // the circular segment between chord and arc
    }
  }
  return a;
}

}  // namespace

TEST_CASE("toolpath: passes descend in equal steps of at most step_down to depth plus breakthrough",
          "[geometry][toolpath]") {
  CncOptions o = base();
  o.depth = 30;
  o.step_down = 7;
  o.breakthrough = 0.5;
  const Toolpath tp = plan_toolpath(kSlab, {}, o);
  REQUIRE(tp.pass_z.size() == 5);
  for (std::size_t k = 0; k < 5; ++k) CHECK(tp.pass_z[k] == Approx(-30.5 * static_cast<double>(k + 1) / 5));
  CHECK(tp.tab_z == Approx(-27));
  o.step_down = 10;
  o.breakthrough = 0;
  CHECK(plan_toolpath(kSlab, {}, o).pass_z == std::vector<double>{-10, -20, -30});
}

TEST_CASE("toolpath: climb runs the outline clockwise and holes counter-clockwise, conventional the reverse",
          "[geometry][toolpath]") {
  const std::vector<RegionHole> holes{{ellipse({450, 300}, 120, 80, 20), "holes[0] (ellipse)"}};
  CncOptions o = base();
  for (CutDirection d : {CutDirection::Climb, CutDirection::Conventional}) {
    o.direction = d;
    const Toolpath tp = plan_toolpath(kSlab, holes, o);
    REQUIRE(tp.loops.size() == 2);
    CHECK(tp.loops[0].label == "holes[0] (ellipse)");  // holes first
    CHECK(tp.loops[1].outer);
    const double sign = d == CutDirection::Climb ? 1.0 : -1.0;
    CHECK(sign * signed_area2(tp.loops[0].pieces) > 0.0);
    CHECK(sign * signed_area2(tp.loops[1].pieces) < 0.0);
    // The outline's path encloses the slab grown by the tool radius with round corners.
    CHECK(std::abs(signed_area2(tp.loops[1].pieces)) / 2 ==
          Approx(912.0 * 612 - (4 - M_PI) * 36).epsilon(1e-12));
  }
}

TEST_CASE("toolpath: convex corners get quarter arcs of the tool radius about the corner point",
          "[geometry][toolpath]") {
  const Toolpath tp = plan_toolpath(kSlab, {}, base());
  const LoopPath& outline = tp.loops.back();
  int corners = 0;
  for (const PathPiece& p : outline.pieces) {
    if (p.role != PieceRole::Corner) continue;
    ++corners;
    CHECK(piece_radius(p) == Approx(6));
    CHECK(std::abs(p.sweep) == Approx(M_PI / 2));
    CHECK(((p.center - Vec2(0, 0)).norm() < 1e-9 || (p.center - Vec2(900, 0)).norm() < 1e-9 ||
           (p.center - Vec2(900, 600)).norm() < 1e-9 || (p.center - Vec2(0, 600)).norm() < 1e-9));
  }
  CHECK(corners == 4);
  CHECK(outline.length == Approx(2 * (900 + 600) + 2 * M_PI * 6));
  CHECK(tp.deviation == 0.0);  // lines and arcs only: exact
  CHECK(tp.clearance >= 6 - tp.options.tolerance);
}

TEST_CASE("toolpath: dog-bones run from where the offsets meet to where the tool's disc touches the corner",
          "[geometry][toolpath]") {
  // A square cut-out with sharp corners: every corner is concave for the tool inside it.
  const std::vector<RegionHole> holes{
      {polygon({Vec2(300, 200), Vec2(600, 200), Vec2(600, 400), Vec2(300, 400)}), "holes[0] (outline)"}};
  CncOptions o = base();
  REQUIRE_THROWS_AS(plan_toolpath(kSlab, holes, o), GeometryError);
  o.relief = CornerRelief::Dogbone;
  const Toolpath tp = plan_toolpath(kSlab, holes, o);
  const LoopPath& hole = tp.loops.front();
  const std::vector<Vec2> corners{Vec2(300, 200), Vec2(600, 200), Vec2(600, 400), Vec2(300, 400)};
  int bones = 0;
  for (std::size_t i = 0; i + 1 < hole.pieces.size(); ++i) {
    const PathPiece& in = hole.pieces[i];
    if (in.role != PieceRole::Dogbone) continue;
    const PathPiece& out = hole.pieces[++i];
    REQUIRE(out.role == PieceRole::Dogbone);
    CHECK(out.to.isApprox(in.from));  // and back
    double reach = INFINITY, start = INFINITY;
    for (const Vec2& c : corners)
      reach = std::min(reach, (in.to - c).norm()), start = std::min(start, (in.from - c).norm());
    CHECK(reach == Approx(6));
    CHECK(start == Approx(6 * std::sqrt(2.0)));  // the offsets of both sides meet on the bisector
    ++bones;
  }
  CHECK(bones == 4);
  CHECK(tp.checks.loops[1].concave_corners.size() == 4);
}

TEST_CASE("toolpath: tabs lie on straight stretches, width + tool diameter long, clear of the start",
          "[geometry][toolpath][tabs]") {
  CncOptions o = base();
  o.tabs.count = 6;
  const Toolpath tp = plan_toolpath(kSlab, {}, o);
  const LoopPath& outline = tp.loops.back();
  REQUIRE(outline.tabs.size() == 6);
  double prev = 0.0;
  for (const auto& [a, b] : outline.tabs) {
    CHECK(b - a == Approx(o.tabs.width + o.tool_diameter));
    CHECK(a >= prev);
    CHECK(a >= o.tool_diameter);
    CHECK(b <= outline.length - o.tool_diameter);
    prev = b + o.tool_diameter;
    // On a straight offset piece: both ends and the middle lie on one line piece.
    double u = 0.0;
    for (const PathPiece& p : outline.pieces) {
      const double len = piece_length(p);
      if (u <= a && b <= u + len) CHECK(p.kind == PieceKind::Line);
      CHECK(!(u < b && a < u + len && p.role == PieceRole::Corner));
      u += len;
    }
  }
  CHECK(tp.warnings.empty());
  o.tabs.count = 200;  // 200 * 34 mm does not fit on 3 m of edges: those that fit, and a warning
  const Toolpath crowded = plan_toolpath(kSlab, {}, o);
  const LoopPath& full = crowded.loops.back();
  CHECK(full.tabs.size() > 30);
  CHECK(full.tabs.size() < 200);
  for (std::size_t i = 1; i < full.tabs.size(); ++i)
    CHECK(full.tabs[i].first >= full.tabs[i - 1].second + o.tool_diameter - 1e-9);
  REQUIRE(crowded.warnings.size() == 1);
  CHECK_THAT(crowded.warnings[0], Catch::StartsWith("outline: " + std::to_string(full.tabs.size()) +
                                                    " of 200 tabs placed; no room for " +
                                                    std::to_string(200 - full.tabs.size()) + " more"));
}

TEST_CASE("toolpath: a hole's own tabs hold its slug, the tool rising over them in its last passes",
          "[geometry][toolpath][tabs]") {
  const std::vector<RegionHole> holes{{rounded_rect(200, 150, 700, 450, 30), "holes[0] (rounded_rect)"},
                                      {ellipse({800, 520}, 40, 30, 0), "holes[1] (ellipse)"}};
  CncOptions o = base();
  o.tabs.count = 4;
  TabOptions sink;
  sink.count = 2;
  sink.width = 8;
  sink.height = 5;
  sink.min_radius = 1000;
  o.hole_tabs = {sink, no_tabs()};
  const Toolpath tp = plan_toolpath(kSlab, holes, o);
  REQUIRE(tp.loops.size() == 3);
  CHECK(tp.loops[0].tabs.size() == 2);  // the sink
  CHECK(tp.loops[0].tab_height == 5);
  CHECK(tp.loops[1].tabs.empty());      // the small oval: none asked
  CHECK(tp.loops[2].tabs.size() == 4);  // the outline
  CHECK(tp.warnings.empty());
  // The sink's tab moves rise to 5 above the bottom, in the passes below that.
  const double sink_tab_z = -(o.depth - 5);
  int ups = 0;
  for (const ToolMove& m : tp.moves) {
    if (m.loop != 0 || m.kind != MoveKind::TabUp) continue;
    CHECK(m.to.z() == Approx(sink_tab_z));
    ++ups;
  }
  const std::size_t deep = static_cast<std::size_t>(
      std::count_if(tp.pass_z.begin(), tp.pass_z.end(), [&](double z) { return z < sink_tab_z - 1e-9; }));
  CHECK(ups == static_cast<int>(2 * deep));
  // A hole too small for its tabs: what fits, and a warning naming it.
  TabOptions many = sink;
  many.count = 12;
  many.min_radius.reset();
  o.hole_tabs = {no_tabs(), many};
  const Toolpath crowded = plan_toolpath(kSlab, holes, o);
  REQUIRE(crowded.warnings.size() == 1);
  CHECK_THAT(crowded.warnings[0], Catch::StartsWith("holes[1] (ellipse): "));
  CHECK(crowded.loops[1].tabs.size() < 12);
}

TEST_CASE("toolpath: a ramp entry descends along the path at the ramp angle, never plunging into material",
          "[geometry][toolpath][ramp]") {
  const std::vector<RegionHole> holes{{ellipse({450, 300}, 60, 40, 15), "holes[0] (ellipse)"}};
  CncOptions o = base();
  o.entry = EntryKind::Ramp;
  o.ramp_angle_deg = 4;
  o.step_down = 10;
  o.depth = 30;
  const Toolpath tp = plan_toolpath(kSlab, holes, o);
  const double slope = std::tan(4 * M_PI / 180);
  Vec3 at = tp.moves.front().to;
  double floor = 0.0;  // the deepest z reached so far on the current loop
  std::size_t loop = tp.moves.front().loop;
  int ramps = 0;
  for (const ToolMove& m : tp.moves) {
    if (m.loop != loop) loop = m.loop, floor = 0.0;
    const double drop = at.z() - m.to.z();
    if (m.kind == MoveKind::Plunge) {
      // Down in the waste to the floor already cut, never below it.
      CHECK(m.to.z() >= floor - 1e-9);
    }
    if (m.kind == MoveKind::Ramp) {
      ++ramps;
      double run = (Vec2(m.to.x(), m.to.y()) - Vec2(at.x(), at.y())).norm();
      if (m.shape == PieceKind::Arc) run = (Vec2(at.x(), at.y()) - m.center).norm() * std::abs(m.sweep);
      CHECK(drop >= -1e-12);
      CHECK(drop <= slope * run * (1 + 1e-9) + 1e-12);
    }
    if (m.kind == MoveKind::Cut) CHECK(m.to.z() >= floor - 1e-9);  // cuts run at the depth the ramp reached
    floor = std::min(floor, m.to.z());
    at = m.to;
  }
  CHECK(ramps > 0);
  // Each pass: a ramp that ends at the loop's start at the pass's depth.
  for (std::size_t i = 0; i + 1 < tp.moves.size(); ++i) {
    const ToolMove& m = tp.moves[i];
    if (m.kind != MoveKind::Ramp || tp.moves[i + 1].kind == MoveKind::Ramp) continue;
    const LoopPath& lp = tp.loops[m.loop];
    CHECK((Vec2(m.to.x(), m.to.y()) - lp.pieces.front().from).norm() <= 1e-9);
    CHECK(std::find(tp.pass_z.begin(), tp.pass_z.end(), m.to.z()) != tp.pass_z.end());
  }
  // Tabs keep clear of the ramp's stretch (half of step / tan(angle), plus a tool diameter).
  const double half = 0.5 * 10 / slope;
  for (const auto& [a, b] : tp.loops.back().tabs) CHECK(a >= half + o.tool_diameter - 1e-9);
}

TEST_CASE(
    "toolpath: the lead arc arrives tangent at the start from the waste side, a quarter circle of lead_in",
    "[geometry][toolpath]") {
  const std::vector<RegionHole> holes{{rounded_rect(200, 150, 700, 450, 30), "holes[0] (rounded_rect)"}};
  for (CutDirection d : {CutDirection::Climb, CutDirection::Conventional}) {
    CncOptions o = base();
    o.direction = d;
    const Toolpath tp = plan_toolpath(kSlab, holes, o);
    for (const LoopPath& lp : tp.loops) {
      REQUIRE(lp.lead);
      const PathPiece& lead = *lp.lead;
      CHECK(lead.to == lp.pieces.front().from);
      CHECK(piece_length(lead) == Approx(o.lead_in));
      CHECK(piece_tangent(lead, piece_length(lead)).isApprox(piece_tangent(lp.pieces.front(), 0.0), 1e-12));
      // The plunge point lies farther from the part than the path: outside the slab, inside the hole.
      const Vec2 p = lead.from;
      if (lp.outer) {
        CHECK((p.x() < -6 || p.x() > 906 || p.y() < -6 || p.y() > 606));
      } else {
        CHECK((p.x() > 206 && p.x() < 694 && p.y() > 156 && p.y() < 444));
      }
    }
  }
}

TEST_CASE("toolpath: moves start at safe height, plunge at the lead's start and end retracted",
          "[geometry][toolpath]") {
  const Toolpath tp = plan_toolpath(kSlab, {{ellipse({450, 300}, 100, 60, 0), "holes[0] (ellipse)"}}, base());
  REQUIRE(!tp.moves.empty());
  CHECK(tp.moves.front().kind == MoveKind::Rapid);
  CHECK(tp.moves.front().to.z() == tp.options.safe_z);
  CHECK(tp.moves.back().kind == MoveKind::Retract);
  CHECK(tp.moves.back().to.z() == tp.options.safe_z);
  int plunges = 0, tab_ups = 0;
  for (std::size_t i = 1; i < tp.moves.size(); ++i) {
    const ToolMove& m = tp.moves[i];
    if (m.kind == MoveKind::Plunge) {
      ++plunges;
      CHECK(m.to.head<2>().isApprox(tp.moves[i - 1].to.head<2>()));  // straight down
      CHECK(tp.loops[m.loop].lead->from.isApprox(m.to.head<2>()));
    }
    tab_ups += m.kind == MoveKind::TabUp;
  }
  CHECK(plunges == 2 * 3);  // two loops, three passes
  CHECK(tab_ups == 4);      // the last pass only: the tab tops at -27 lie below the second pass at -20
  CHECK(tp.deviation <= 0.5 * tp.options.tolerance);
  CHECK(tp.deviation > 0.0);  // the ellipse's offset is a chain of chords
}

TEST_CASE("toolpath: an outline given clockwise and holes given either way cut the same paths",
          "[geometry][toolpath]") {
  const CompositeCurve ccw = rounded_rect(0, 0, 900, 600, 40);
  const CompositeCurve cw = polygon({Vec2(0, 0), Vec2(0, 600), Vec2(900, 600), Vec2(900, 0)});
  const CompositeCurve sharp = polygon({Vec2(0, 0), Vec2(900, 0), Vec2(900, 600), Vec2(0, 600)});
  const CompositeCurve hole = ellipse({450, 300}, 150, 90, 10);
  const CompositeCurve hole_cw({Segment::ellipse_arc([] {
                                 EllipseArcParams e;
                                 e.center = {450, 300};
                                 e.a = 150;
                                 e.b = 90;
                                 e.rotation_deg = 10;
                                 e.from_deg = 360;
                                 e.to_deg = 0;
                                 return e;
                               }())},
                               true);
  CncOptions o = base();
  const Toolpath a = plan_toolpath(sharp, {{hole, "holes[0] (ellipse)"}}, o);
  const Toolpath b = plan_toolpath(cw, {{hole_cw, "holes[0] (ellipse)"}}, o);
  for (std::size_t l = 0; l < 2; ++l) {
    CHECK(a.loops[l].length == Approx(b.loops[l].length).epsilon(1e-9));
    CHECK(signed_area2(a.loops[l].pieces) == Approx(signed_area2(b.loops[l].pieces)).epsilon(1e-6));
  }
  // And the rounded outline's path is its offset: corner arcs of 40 + 6.
  const Toolpath c = plan_toolpath(ccw, {}, o);
  CHECK(c.loops.back().length == Approx(2 * (820 + 520) + 2 * M_PI * 46));
}

TEST_CASE("toolpath: a digitised outline's slight concave turns are cut through, tabs find room",
          "[geometry][toolpath][digitised]") {
  // A 2400 x 650 worktop whose front edge is a concave arc of radius 19 m given as 301 points
  // (rising 38 mm into the part at the middle), and whose back corners are rounded convexly
  // (radius 100) by 41 points each: a digitised template.
  const std::vector<Vec2> p = digitised_worktop_points();
  const CompositeCurve outline = polygon(p);
  CncOptions o;
  o.tolerance = 0.05;
  const Toolpath tp = plan_toolpath(outline, {}, o);
  const LoopCheck& check = tp.checks.loops[0];
  CHECK(check.concave_corners.empty());
  CHECK(check.shallow_corners.size() >= 299);
  for (const PathPiece& piece : tp.loops[0].pieces) CHECK(piece.role != PieceRole::Dogbone);
  CHECK(tp.loops[0].tabs.size() == 4);
  CHECK(tp.warnings.empty());
  // The round the tool leaves at each such corner is within a quarter of the tolerance.
  for (const LoopCorner& c : check.shallow_corners)
    CHECK(6.0 * (1.0 / std::cos(0.5 * c.turn) - 1.0) <= 0.25 * o.tolerance);
  // A real inside corner (90 degrees) is still refused without relief.
  const CompositeCurve notch =
      polygon({Vec2(0, 0), Vec2(900, 0), Vec2(900, 600), Vec2(450, 600), Vec2(450, 300), Vec2(0, 300)});
  CHECK_THROWS_AS(plan_toolpath(notch, {}, o), GeometryError);
}

TEST_CASE("toolpath: a finishing pass cuts the edge at full depth after roughing that leaves the stock",
          "[geometry][toolpath][finish]") {
  const std::vector<RegionHole> holes{{rounded_rect(200, 150, 700, 450, 30), "holes[0] (rounded_rect)"}};
  CncOptions o = base();
  o.finish = 0.5;
  o.tabs.count = 4;
  const Toolpath tp = plan_toolpath(kSlab, holes, o);
  REQUIRE(tp.roughing.size() == tp.loops.size());
  const double r = 0.5 * o.tool_diameter;
  for (std::size_t l = 0; l < tp.loops.size(); ++l) {
    INFO(tp.loops[l].label);
    // The roughing path runs the stock further into the waste all round (its area differs by
    // stock x perimeter, more for the outline, less for the hole).
    const double finish_area = std::abs(signed_area2(tp.loops[l].pieces)) / 2;
    const double rough_area = std::abs(signed_area2(tp.roughing[l].pieces)) / 2;
    const double expected = o.finish * 0.5 * (tp.loops[l].length + tp.roughing[l].length);
    CHECK(std::abs(rough_area - finish_area) == Approx(expected).epsilon(1e-3));
    CHECK(tp.roughing[l].tabs.size() == tp.loops[l].tabs.size());
    REQUIRE(tp.loops[l].lead);
    CHECK(piece_radius(*tp.loops[l].lead) == Approx(o.finish));
  }
  // Each loop: every pass on the roughing path, then one finishing pass at full depth.
  std::vector<int> finishing_plunges(tp.loops.size(), 0), rough_plunges(tp.loops.size(), 0);
  for (const ToolMove& m : tp.moves) {
    if (m.kind != MoveKind::Plunge) continue;
    if (m.finishing) {
      ++finishing_plunges[m.loop];
      CHECK(m.to.z() == Approx(tp.pass_z.back()));
      // Down inside the roughed slot: on the roughing path (within the stock's reach).
      const double u = nearest_along(tp.roughing[m.loop].pieces, Vec2(m.to.x(), m.to.y()));
      CHECK((path_point(tp.roughing[m.loop].pieces, u).first - Vec2(m.to.x(), m.to.y())).norm() <=
            1e-6 * r + 1e-9);
    } else {
      ++rough_plunges[m.loop];
    }
  }
  for (std::size_t l = 0; l < tp.loops.size(); ++l) {
    CHECK(finishing_plunges[l] == 1);
    CHECK(rough_plunges[l] == static_cast<int>(tp.pass_z.size()));
  }
  CHECK(toolpath_totals(tp).cutting > toolpath_totals(plan_toolpath(kSlab, holes, base())).cutting);
  o.finish = 6;  // the tool radius: refused
  CHECK_THROWS_AS(plan_toolpath(kSlab, holes, o), RangeError);
}

TEST_CASE(
    "toolpath: digitised points along a concave curve tighter than the tool are refused with its radius",
    "[geometry][toolpath][digitised]") {
  // A 900 x 600 slab with a concave notch of radius 4 in its top edge, digitised every 0.5 degrees
  // of turn 7.2 degrees: each corner alone would be shallow, the stretch is tighter than a 12 mm tool.
  std::vector<Vec2> p{Vec2(0, 0), Vec2(900, 0), Vec2(900, 600), Vec2(454, 600)};
  for (int i = 1; i < 25; ++i) {
    const double a = M_PI * i / 25;  // round the notch's centre (450, 600), dipping into the part
    p.emplace_back(450 + 4 * std::cos(a), 600 - 4 * std::sin(a));
  }
  p.emplace_back(446, 600);
  p.emplace_back(0, 600);
  CncOptions o = base();
  o.tolerance = 0.05;
  try {
    plan_toolpath(polygon(p), {}, o);
    FAIL("accepted");
  } catch (const GeometryError& e) {
    CHECK_THAT(std::string(e.what()),
               Catch::Contains("has a radius of 4") && Catch::Contains("below the tool radius 6"));
  }
}

TEST_CASE("toolpath: a round sink's tabs go on its curve when min_radius is left to its default",
          "[geometry][toolpath][tabs]") {
  // A round sink of radius 100: its tool path (radius 94) is nowhere as flat
  // as 20 tool diameters (240), so the default takes the loop's own curvature.
  const std::vector<RegionHole> holes{{ellipse({600, 300}, 100, 100, 0), "holes[0] (ellipse)"}};
  CncOptions o = base();
  TabOptions sink;
  sink.count = 2;
  o.hole_tabs = {sink};
  const Toolpath tp = plan_toolpath(kSlab, holes, o);
  REQUIRE(tp.loops.size() == 2);
  CHECK(tp.loops[0].tabs.size() == 2);
  CHECK(tp.warnings.empty());
  // Asked for explicitly, the bound stays: a radius of 240 leaves the sink unheld, with a warning.
  sink.min_radius = 240;
  o.hole_tabs = {sink};
  const Toolpath strict = plan_toolpath(kSlab, holes, o);
  CHECK(strict.loops[0].tabs.empty());
  REQUIRE(strict.warnings.size() == 1);
  CHECK_THAT(strict.warnings[0], Catch::StartsWith("holes[0] (ellipse): 0 of 2 tabs placed"));
}
