#include "geometry/section/region.h"

#include <catch2/catch.hpp>

#include "geometry/core/errors.h"
#include "geometry/section/simple_polygon.h"
#include "tests/geometry/section/region_shapes.h"

using namespace fabmesh;
using namespace fabmesh::test;

namespace {

std::string region_error(const CompositeCurve& outline, const std::vector<RegionHole>& holes) {
  try {
    build_region(outline, holes, {});
  } catch (const GeometryError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("region: outline counter-clockwise, holes clockwise, area within the sampling bound",
          "[section][region][countertop]") {
  const CompositeCurve outline = rounded_rect(0, 0, 2400, 650, 80);
  std::vector<RegionHole> holes{{ellipse({600, 325}, 250, 180, 15), "holes[0] (ellipse)"},
                                {rounded_rect(1300, 150, 2000, 500, 40), "holes[1] (rounded_rect)"}};
  // Give the second hole clockwise and the outline both ways: orientation is normalised.
  for (const bool reverse_outline : {false, true}) {
    CompositeCurve o = outline;
    if (reverse_outline) {
      // A clockwise rectangle of lines: the outer loop still comes out counter-clockwise.
      o = polygon({{0, 0}, {0, 650}, {2400, 650}, {2400, 0}});
    }
    RegionOptions options;
    options.tolerance = 0.05;
    const Region2 r = build_region(o, holes, options);
    CHECK(signed_area2(r.outer) > 0.0);
    REQUIRE(r.holes.size() == 2);
    for (const auto& h : r.holes) CHECK(signed_area2(h) < 0.0);
    CHECK(r.max_deviation <= 0.05);
    double exact = std::abs(exact_area(o)), perimeter = exact_length(o);
    for (const auto& h : holes) exact -= std::abs(exact_area(h.curve)), perimeter += exact_length(h.curve);
    CHECK(std::abs(r.area - exact) <= r.max_deviation * perimeter);
    CHECK(!find_crossing(region_loops(r)));
    CHECK(!r.proof.empty());
  }
}

TEST_CASE("region: an outline that does not close is rejected at its closing joint",
          "[section][region][countertop][errors]") {
  const CompositeCurve open({Segment::line({0, 0}, {100, 0}), Segment::line({100, 0}, {100, 50}),
                             Segment::line({100, 50}, {0, 50}), Segment::line({0, 50}, {0, 5})},
                            true);
  const std::string msg = region_error(open, {});
  CHECK_THAT(msg, Catch::Contains("does not close") && Catch::Contains("closing joint"));
  const CompositeCurve not_closed({Segment::line({0, 0}, {1, 0}), Segment::line({1, 0}, {0, 1})}, false);
  CHECK_THAT(region_error(not_closed, {}), Catch::Contains("closed"));
}

TEST_CASE("region: an outline crossing itself is rejected naming its segments",
          "[section][region][countertop][errors]") {
  const CompositeCurve bow = polygon({{0, 0}, {100, 100}, {100, 0}, {0, 100}});
  const std::string msg = region_error(bow, {});
  CHECK_THAT(msg, Catch::Contains("outline crosses itself") && Catch::Contains("segment 0") &&
                      Catch::Contains("segment 2"));
}

TEST_CASE("region: holes outside, crossing, touching, overlapping or nested are rejected",
          "[section][region][countertop][errors]") {
  const CompositeCurve outline = polygon({{0, 0}, {1000, 0}, {1000, 600}, {0, 600}});
  SECTION("outside") {
    const std::string msg = region_error(outline, {{ellipse({1500, 300}, 100, 50, 0), "holes[0] (ellipse)"}});
    CHECK_THAT(msg, Catch::Contains("holes[0] (ellipse) is not inside the outline"));
  }
  SECTION("crossing the outline") {
    const std::string msg = region_error(outline, {{ellipse({980, 300}, 100, 50, 0), "holes[0] (ellipse)"}});
    CHECK_THAT(msg, Catch::Contains("holes[0] (ellipse) crosses or touches the outline"));
  }
  SECTION("touching the outline at a point") {
    const std::string msg =
        region_error(outline, {{polygon({{500, 0}, {600, 100}, {400, 100}}), "holes[0] (outline)"}});
    CHECK_THAT(msg, Catch::Contains("holes[0] (outline) crosses or touches the outline"));
  }
  SECTION("overlapping another hole") {
    const std::string msg =
        region_error(outline, {{ellipse({300, 300}, 150, 100, 0), "holes[0] (ellipse)"},
                               {rounded_rect(400, 200, 700, 400, 20), "holes[1] (rounded_rect)"}});
    CHECK_THAT(msg, Catch::Contains("holes[1] (rounded_rect) overlaps holes[0] (ellipse) near ("));
  }
  SECTION("nested in another hole") {
    const std::string msg = region_error(outline, {{ellipse({300, 300}, 200, 150, 0), "holes[0] (ellipse)"},
                                                   {ellipse({300, 300}, 50, 30, 10), "holes[1] (ellipse)"}});
    CHECK_THAT(msg, Catch::Contains("holes[1] (ellipse) lies inside holes[0] (ellipse)"));
  }
}
