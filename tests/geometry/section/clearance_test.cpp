#include "geometry/section/clearance.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "geometry/core/errors.h"
#include "geometry/curves/curve_spec.h"
#include "geometry/section/region.h"

using namespace fabmesh;

namespace {

CompositeCurve circle(Vec2 center, double r) {
  EllipseArcParams e;
  e.center = center;
  e.a = e.b = r;
  return CompositeCurve({Segment::ellipse_arc(e)}, true);
}

CompositeCurve rectangle(double w, double h) {
  CurveSpec spec;
  spec.closed = true;
  for (const Vec2& p : {Vec2(w, 0), Vec2(w, h), Vec2(0, h), Vec2(0, 0)}) {
    SegmentSpec s;
    s.kind = SegmentKind::Line;
    s.points = spec.segments.empty() ? std::vector<Vec2>{Vec2(0, 0), p} : std::vector<Vec2>{p};
    spec.segments.push_back(s);
  }
  return construct_curve(spec);
}

}  // namespace

TEST_CASE("clearance: two circles are exactly their centre distance minus the radii apart",
          "[section][clearance]") {
  const CompositeCurve a = circle({0, 0}, 100), b = circle({250, 30}, 60);
  const SegmentArc arc_a(a.segments()[0]), arc_b(b.segments()[0]);
  std::vector<ArcPiece> pieces;
  for (int k = 0; k < 12; ++k) pieces.push_back({&arc_a, k / 12.0, (k + 1) / 12.0, 0});
  for (int k = 0; k < 7; ++k) pieces.push_back({&arc_b, k / 7.0, (k + 1) / 7.0, 1});
  ClearanceOptions o;
  o.accuracy = 1e-6;
  const Clearance c = exact_clearance(pieces, o);
  const double exact = std::hypot(250.0, 30.0) - 160.0;
  CHECK(c.lower <= exact);
  CHECK(c.upper >= exact - 1e-9);
  CHECK(c.upper - c.lower <= 1e-6);
  CHECK(c.group_a != c.group_b);
  // Crossing curves: the clearance is 0.
  const CompositeCurve d = circle({150, 0}, 60);
  const SegmentArc arc_d(d.segments()[0]);
  pieces.resize(12);
  for (int k = 0; k < 5; ++k) pieces.push_back({&arc_d, k / 5.0, (k + 1) / 5.0, 1});
  CHECK(exact_clearance(pieces, o).upper <= 1e-6);
}

TEST_CASE(
    "region: holes whose exact curves come closer than the tolerance are refused, though their polygons "
    "do not meet",
    "[section][clearance][errors]") {
  // Polygons inscribed in circles lie inside them: the sampled holes are farther
  // apart than the exact ones, by up to twice the sampling deviation.
  const double tolerance = 0.5, gap = 0.3;
  RegionOptions o;
  o.tolerance = tolerance;
  o.outline_key = "outline";
  const std::vector<RegionHole> holes{{circle({300, 300}, 100), "holes[0] (ellipse)", "holes[0]"},
                                      {circle({500 + gap, 300}, 100), "holes[1] (ellipse)", "holes[1]"}};
  try {
    build_region(rectangle(1000, 600), holes, o);
    FAIL("closer than the tolerance, yet accepted");
  } catch (const GeometryError& e) {
    CHECK(e.where() == "holes[1]");
    REQUIRE(e.location().point.size() == 2);  // near the closest place, on holes[1]'s side
    CHECK(e.location().point[0] == Approx(400 + gap).margin(0.01));
    CHECK_THAT(std::string(e.what()), Catch::Contains("holes[1] (ellipse) comes within 0.3") &&
                                          Catch::Contains("holes[0] (ellipse)") &&
                                          Catch::Contains("closer than the tolerance 0.5"));
  }
  // Farther than the tolerance: accepted, with the exact clearance reported.
  const std::vector<RegionHole> apart{{circle({300, 300}, 100), "holes[0] (ellipse)", ""},
                                      {circle({500.8, 300}, 100), "holes[1] (ellipse)", ""}};
  const Region2 r = build_region(rectangle(1000, 600), apart, o);
  CHECK(r.min_clearance == Approx(0.8).margin(1e-3 * tolerance));
  CHECK(r.min_clearance <= 0.8);
  CHECK_THAT(r.clearance_where,
             Catch::Contains("holes[0] (ellipse) near (400") && Catch::Contains("holes[1]"));
  // A hole nearly touching the outline.
  const std::vector<RegionHole> edge{
      {circle({300, 100.2}, 100), "holes[0] (ellipse)", "design.yaml:9:5: holes[0]"}};
  CHECK_THROWS_AS(build_region(rectangle(1000, 600), edge, o), GeometryError);
}
