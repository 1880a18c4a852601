// The pieces both SVG writers (outline and toolpath) are made of.

#include "io/cutting/svg_writing.h"

#include <algorithm>
#include <catch2/catch.hpp>

using namespace fabmesh;

TEST_CASE("svg_writing: numbers round-trip, y is flipped, -0 is 0", "[io][svg]") {
  CHECK(svg_number(0.1) == "0.1");
  CHECK(svg_number(-0.0) == "0");
  CHECK(svg_number(1e21) == "1e+21");
  CHECK(svg_point(Vec2(1.5, 2.0)) == "1.5 -2");
  CHECK(svg_point(Vec2(-3.0, 0.0)) == "-3 0");
}

TEST_CASE("svg_writing: the start tag spans the box and margin, m is drawn in mm", "[io][svg]") {
  const std::string mm = svg_start(Vec2(0, 0), Vec2(10, 4), 1.0, "mm");
  CHECK(mm ==
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"12mm\" height=\"6mm\" viewBox=\"-1 -5 12 6\">\n");
  CHECK_THAT(svg_start(Vec2(0, 0), Vec2(1, 1), 0.0, "m"),
             Catch::Contains("width=\"1000mm\" height=\"1000mm\" viewBox=\"0 -1 1 1\""));
}

TEST_CASE("svg_writing: a loop is M then L and A commands, the next loop starts with M", "[io][svg]") {
  CutLoop square;
  square.entities.push_back({CutKind::Polyline, {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}}, {}});
  std::string d;
  append_svg_loop(d, square);
  CHECK(d == "M 0 0 L 1 0 L 1 -1 L 0 -1 L 0 0");
  CutLoop circle;
  EllipseArcParams arc;
  arc.center = Vec2(5, 0);
  arc.a = arc.b = 1.0;
  arc.from_deg = 0.0;
  arc.to_deg = 360.0;
  circle.entities.push_back({CutKind::Arc, {{6, 0}, {6, 0}}, arc});
  append_svg_loop(d, circle);
  // Three pieces of 120 degrees, counter-clockwise (sweep flag 0 after the flip).
  CHECK_THAT(d, Catch::StartsWith("M 0 0 L 1 0 L 1 -1 L 0 -1 L 0 0 M 6 0 A 1 1 0 0 0 "));
  CHECK(std::count(d.begin(), d.end(), 'A') == 3);
}
