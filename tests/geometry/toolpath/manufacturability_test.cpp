// What a 12 mm router bit can and cannot cut, decided on the exact curves
// before any toolpath exists.

#include <catch2/catch.hpp>
#include <cmath>
#include <functional>

#include "geometry/core/errors.h"
#include "geometry/toolpath/toolpath.h"
#include "tests/geometry/section/region_shapes.h"

using namespace fabmesh;
using namespace fabmesh::test;

namespace {

// A 900 x 600 slab with one sink: a rounded rectangle with corner radius `corner`.
std::vector<RegionHole> sink(double corner) {
  return {{rounded_rect(200, 150, 700, 450, corner), "holes[0] (rounded_rect)"}};
}

const CompositeCurve kSlab = polygon({Vec2(0, 0), Vec2(900, 0), Vec2(900, 600), Vec2(0, 600)});

CncOptions twelve() {
  CncOptions o;
  o.tool_diameter = 12;
  o.depth = 30;
  o.tabs.min_radius = 1000;
  return o;
}

// The GeometryError of planning, with its message.
GeometryError refusal(const CompositeCurve& outline, const std::vector<RegionHole>& holes,
                      const CncOptions& o) {
  try {
    plan_toolpath(outline, holes, o);
  } catch (const GeometryError& e) {
    return e;
  }
  FAIL("planning accepted the region");
  return GeometryError("", "");
}

// A dumbbell hole: two circles of radius 30, 100 apart, joined by a neck `neck` wide.
CompositeCurve dumbbell(Vec2 c, double neck) {
  const double h = 0.5 * neck, x = std::sqrt(30.0 * 30.0 - h * h);
  const double a = std::asin(h / 30.0) * 180.0 / M_PI;
  auto arc = [](Vec2 centre, double from, double to) {
    EllipseArcParams e;
    e.center = centre;
    e.a = e.b = 30;
    e.from_deg = from;
    e.to_deg = to;
    return Segment::ellipse_arc(e);
  };
  const Vec2 b = c + Vec2(100, 0);
  return CompositeCurve({Segment::line(c + Vec2(x, -h), b + Vec2(-x, -h)), arc(b, 180 + a, 540 - a),
                         Segment::line(b + Vec2(-x, h), c + Vec2(x, h)), arc(c, a, 360 - a)},
                        true);
}

}  // namespace

TEST_CASE(
    "manufacturability: a sink with 5 mm corners is refused for a 12 mm tool, naming hole, segment, point, "
    "radius",
    "[geometry][toolpath][manufacturability][errors]") {
  const GeometryError e = refusal(kSlab, sink(5), twelve());
  CHECK(e.where() == "holes[0] (rounded_rect)");
  const std::string what = e.what();
  CHECK_THAT(what, Catch::Contains("segment 1 (ellipse_arc)"));
  CHECK_THAT(what, Catch::Contains("radius of curvature of 5 "));
  CHECK_THAT(what, Catch::Contains("tool radius 6"));
  CHECK_THAT(what, Catch::Contains("("));  // a point
}

TEST_CASE("manufacturability: the same sink with 8 mm corners is cut, its corners on arcs of radius 2",
          "[geometry][toolpath][manufacturability]") {
  const Toolpath tp = plan_toolpath(kSlab, sink(8), twelve());
  REQUIRE(tp.loops.size() == 2);
  const LoopPath& hole = tp.loops.front();
  CHECK(hole.label == "holes[0] (rounded_rect)");
  int corners = 0;
  for (const PathPiece& p : hole.pieces) {
    if (p.kind == PieceKind::Arc && p.role == PieceRole::Offset) {
      CHECK(piece_radius(p) == Approx(2.0));
      ++corners;
    }
  }
  CHECK(corners == 4);
  CHECK(tp.checks.loops[1].min_concave_radius == Approx(8.0));
  CHECK(tp.checks.loops[0].min_concave_radius == INFINITY);  // a convex outline
  CHECK(tp.checks.loops[0].convex_corners.size() == 4);
}

TEST_CASE(
    "manufacturability: a sink whose corners equal the tool radius is cut with the tool standing in them",
    "[geometry][toolpath][manufacturability]") {
  const Toolpath tp = plan_toolpath(kSlab, sink(6), twelve());
  for (const PathPiece& p : tp.loops.front().pieces) CHECK(p.kind == PieceKind::Line);
  CHECK(path_length(tp.loops.front().pieces) == Approx(2 * (488 + 288)));
}

TEST_CASE("manufacturability: a T-Bezier dent tighter than the tool is refused with the proven radius",
          "[geometry][toolpath][manufacturability][errors]") {
  // The front edge dips into the slab: concave for the tool outside.
  const CompositeCurve outline(
      {Segment::line({0, 0}, {400, 0}),
       Segment::tbezier({Vec2(400, 0), Vec2(440, 0), Vec2(445, 40), Vec2(450, 40)}, 0.0, 0.0),
       Segment::tbezier({Vec2(450, 40), Vec2(455, 40), Vec2(460, 0), Vec2(500, 0)}, 0.0, 0.0),
       Segment::line({500, 0}, {900, 0}), Segment::line({900, 0}, {900, 600}),
       Segment::line({900, 600}, {0, 600}), Segment::line({0, 600}, {0, 0})},
      true);
  const GeometryError e = refusal(outline, {}, twelve());
  CHECK(e.where() == "outline");
  const std::string what = e.what();
  CHECK_THAT(what, Catch::Contains("segment 1 (tbezier)") || Catch::Contains("segment 2 (tbezier)"));
  CHECK_THAT(what, Catch::Contains("below the tool radius 6"));
  // The radius reported is the least one, to the bound's precision: compare with dense sampling of
  // the stretch turning right along the edge (away from the tool below it).
  double least = INFINITY;
  for (std::size_t i : {1, 2}) {
    for (int k = 0; k <= 100000; ++k) {
      const double curv = outline.segments()[i].curvature(k / 100000.0);
      if (curv < 0) least = std::min(least, -1.0 / curv);
    }
  }
  const std::string key = "radius of curvature of ";
  REQUIRE(what.find(key) != std::string::npos);
  CHECK(std::stod(what.substr(what.find(key) + key.size())) == Approx(least).epsilon(1e-5));
}

TEST_CASE("manufacturability: a hole narrower than the tool is refused as smaller than the tool",
          "[geometry][toolpath][manufacturability][errors]") {
  const GeometryError e = refusal(kSlab, {{ellipse({450, 300}, 40, 5, 30), "holes[0] (ellipse)"}}, twelve());
  CHECK(e.where() == "holes[0] (ellipse)");
  CHECK_THAT(std::string(e.what()), Catch::Contains("smaller than the tool diameter 12"));
  CHECK_THAT(std::string(e.what()), Catch::Contains("120 degrees"));
}

TEST_CASE("manufacturability: a neck in a hole narrower than the tool is refused where the tool cannot pass",
          "[geometry][toolpath][manufacturability][errors]") {
  const GeometryError e = refusal(kSlab, {{dumbbell({350, 300}, 10), "holes[0] (outline)"}}, twelve());
  CHECK(e.where() == "holes[0] (outline)");
  CHECK_THAT(std::string(e.what()),
             Catch::Contains("does not fit") && Catch::Contains("narrower than the tool"));
  // With a 14 mm neck the tool passes.
  CHECK_NOTHROW(plan_toolpath(kSlab, {{dumbbell({350, 300}, 14), "holes[0] (outline)"}}, twelve()));
}

TEST_CASE("manufacturability: two holes 8 mm apart are refused naming both, unless the web check is off",
          "[geometry][toolpath][manufacturability][errors]") {
  const std::vector<RegionHole> holes{{rounded_rect(100, 100, 400, 500, 20), "holes[0] (rounded_rect)"},
                                      {rounded_rect(408, 100, 700, 500, 20), "holes[1] (rounded_rect)"}};
  const GeometryError e = refusal(kSlab, holes, twelve());
  CHECK(e.where() == "holes[1] (rounded_rect)");
  CHECK_THAT(std::string(e.what()),
             Catch::Contains("holes[0] (rounded_rect)") && Catch::Contains("at most 8"));
  CncOptions o = twelve();
  o.min_web = 0.0;
  const Toolpath tp = plan_toolpath(kSlab, holes, o);
  CHECK(tp.checks.min_web == Approx(8.0).margin(0.01));
}

TEST_CASE("manufacturability: a sharp concave corner is refused without relief, naming the joint",
          "[geometry][toolpath][manufacturability][errors]") {
  // An L-shaped slab: its inside corner at (400, 300) turns away from the tool.
  const CompositeCurve l_shape =
      polygon({Vec2(0, 0), Vec2(900, 0), Vec2(900, 300), Vec2(400, 300), Vec2(400, 600), Vec2(0, 600)});
  const GeometryError e = refusal(l_shape, {}, twelve());
  CHECK(e.where() == "outline");
  CHECK_THAT(std::string(e.what()), Catch::Contains("segment 2 (line) and segment 3 (line) at (400, 300)"));
  CHECK_THAT(std::string(e.what()), Catch::Contains("relief: dogbone"));
}

TEST_CASE("cnc options: every value out of range is a RangeError naming its field",
          "[geometry][toolpath][errors]") {
  const std::vector<std::pair<std::string, std::function<void(CncOptions&)>>> cases{
      {"cnc.tool_diameter", [](CncOptions& o) { o.tool_diameter = 0; }},
      {"cnc.depth", [](CncOptions& o) { o.depth = -1; }},
      {"cnc.breakthrough", [](CncOptions& o) { o.breakthrough = -0.5; }},
      {"cnc.step_down", [](CncOptions& o) { o.step_down = NAN; }},
      {"cnc.step_down", [](CncOptions& o) { o.step_down = 1e-4; }},  // 300000 passes
      {"cnc.feed", [](CncOptions& o) { o.feed = 0; }},
      {"cnc.plunge", [](CncOptions& o) { o.plunge = INFINITY; }},
      {"cnc.spindle", [](CncOptions& o) { o.spindle = -18000; }},
      {"cnc.safe_z", [](CncOptions& o) { o.safe_z = 0; }},
      {"cnc.lead_in", [](CncOptions& o) { o.lead_in = -8; }},
      {"cnc.tolerance", [](CncOptions& o) { o.tolerance = 0; }},
      {"cnc.tolerance", [](CncOptions& o) { o.tolerance = 7; }},  // not below the tool radius
      {"cnc.min_web", [](CncOptions& o) { o.min_web = -1.0; }},
      {"cnc.tabs.width", [](CncOptions& o) { o.tabs.width = 0; }},
      {"cnc.tabs.height", [](CncOptions& o) { o.tabs.height = 30; }},
      {"cnc.tabs.count", [](CncOptions& o) { o.tabs.count = 5000; }},
      {"cnc.tabs.min_radius", [](CncOptions& o) { o.tabs.min_radius = 0.0; }},
  };
  for (const auto& [field, spoil] : cases) {
    CncOptions o;
    spoil(o);
    INFO(field);
    try {
      validate_cnc_options(o);
      FAIL("accepted");
    } catch (const RangeError& e) {
      CHECK(e.field() == field);
      CHECK_THAT(std::string(e.what()), Catch::StartsWith(field));
    }
  }
  CHECK_NOTHROW(validate_cnc_options(CncOptions{}));
}
