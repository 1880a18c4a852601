// The G-code text itself: layout, numbers, arcs, units, errors; and the
// interpreter harness catching codes it does not know.

#include "io/cutting/gcode.h"

#include <catch2/catch.hpp>
#include <cctype>
#include <sstream>

#include "geometry/core/errors.h"
#include "tests/geometry/section/region_shapes.h"
#include "tests/io/cutting/interpret.h"

using namespace fabmesh;
using namespace fabmesh::test;

namespace {

const CompositeCurve kSlab = polygon({Vec2(0, 0), Vec2(900, 0), Vec2(900, 600), Vec2(0, 600)});

Toolpath slab_with_round_sink() {
  CncOptions o;
  o.tabs.min_radius = 1000;
  return plan_toolpath(kSlab, {{ellipse({450, 300}, 50, 50, 0), "holes[0] (ellipse)"}}, o);
}

// Every word of every line outside comments: letter and number text.
std::vector<std::pair<char, std::string>> words(const std::string& program) {
  std::vector<std::pair<char, std::string>> out;
  std::istringstream lines(program);
  std::string line;
  while (std::getline(lines, line)) {
    const std::string code = line.substr(0, line.find('('));
    std::istringstream in(code);
    std::string w;
    while (in >> w) out.emplace_back(w[0], w.substr(1));
  }
  return out;
}

}  // namespace

TEST_CASE(
    "gcode: header, modal setup, spindle and end, numbers without trailing zeros or -0, same bytes twice",
    "[io][cutting][gcode]") {
  const Toolpath tp = slab_with_round_sink();
  GcodeOptions g;
  g.name = "sink (test)";
  const std::string program = encode_gcode(tp, g);
  CHECK(program == encode_gcode(tp, g));
  CHECK(program.rfind("(fabmesh toolpath: sink [test])\n", 0) == 0);  // no nested parentheses in comments
  CHECK(program.find("\nG21 G90 G94 G17\nG0 Z10\nM3 S18000\nG0 X") != std::string::npos);
  CHECK(program.size() > 6);
  CHECK(program.substr(program.size() - 7) == "M5\nM30\n");
  for (const auto& [letter, number] : words(program)) {
    INFO(letter << number);
    CHECK(std::string("GMXYZIJFS").find(letter) != std::string::npos);
    CHECK(number != "-0");
    CHECK(!number.empty());
    if (number.find('.') != std::string::npos) {
      CHECK(number.back() != '0');
      CHECK(number.back() != '.');
      CHECK(number.size() - number.find('.') - 1 <= 4);  // tolerance 0.01: rounding <= 0.0005 needs 4
    }
  }
  g.decimals = 5;
  const std::string fine = encode_gcode(tp, g);
  std::size_t longest = 0;
  for (const auto& [letter, number] : words(fine)) {
    if (number.find('.') != std::string::npos)
      longest = std::max(longest, number.size() - number.find('.') - 1);
  }
  CHECK(longest == 5);
}

TEST_CASE("gcode: a round sink is cut by G2/G3 arcs of its radius minus the tool radius, halves at most",
          "[io][cutting][gcode]") {
  const Toolpath tp = slab_with_round_sink();
  const Trace trace = interpret(encode_gcode(tp), "round_sink.nc");
  CHECK(trace.unknown.empty());
  int arcs = 0;
  for (const TraceMotion& m : trace.motions) {
    if (!m.arc || m.section.rfind("holes[0]", 0) != 0 || !m.comment.empty()) continue;
    ++arcs;
    CHECK(m.motion == "G3");  // climb: counter-clockwise inside a hole
    CHECK((m.center.head<2>() - Vec2(450, 300)).norm() < 1e-3);
    CHECK((m.start.head<2>() - Vec2(450, 300)).norm() == Approx(44).margin(1e-3));
    CHECK((m.end.head<2>() - m.start.head<2>()).norm() > 1.0);  // never a full circle in one word
  }
  CHECK(arcs == 2 * 3);  // two halves per pass, three passes
}

TEST_CASE("gcode: units and decimals out of range are refused", "[io][cutting][gcode][errors]") {
  const Toolpath tp = slab_with_round_sink();
  GcodeOptions g;
  g.units = "ft";
  CHECK_THROWS_AS(encode_gcode(tp, g), InputError);
  g.units = "mm";
  g.model_units = "furlong";
  CHECK_THROWS_AS(encode_gcode(tp, g), InputError);
  g.model_units = "mm";
  g.decimals = 12;
  CHECK_THROWS_AS(encode_gcode(tp, g), RangeError);
}

TEST_CASE("gcode: a model in centimetres is written in millimetres (G21) scaled by 10",
          "[io][cutting][gcode]") {
  const CompositeCurve slab = polygon({Vec2(0, 0), Vec2(90, 0), Vec2(90, 60), Vec2(0, 60)});
  CncOptions o;
  o.tool_diameter = 1.2;
  o.depth = 3;
  o.step_down = 1;
  o.feed = 300;
  o.plunge = 60;
  o.safe_z = 1;
  o.lead_in = 0.8;
  o.tabs.width = 1;
  o.tabs.height = 0.3;
  o.tabs.min_radius = 100;
  o.tolerance = 0.001;
  const Toolpath tp = plan_toolpath(slab, {}, o);
  GcodeOptions g;
  g.model_units = "cm";
  const Trace trace = interpret(encode_gcode(tp, g), "slab_cm.nc");
  double lo = INFINITY, hi = -INFINITY, deepest = 0.0;
  for (const TraceMotion& m : trace.motions) {
    lo = std::min(lo, m.end.x()), hi = std::max(hi, m.end.x()), deepest = std::min(deepest, m.end.z());
    if (m.motion != "G0" && m.start.head<2>() != m.end.head<2>()) CHECK(m.feed == Approx(3000));
  }
  CHECK(hi >= 906.0 - 1e-3);  // the outline's path: 900 mm + the 6 mm tool radius
  CHECK(deepest == Approx(-30));
}

TEST_CASE("gcode-trace: codes the interpreter has no handler for are reported, not skipped silently",
          "[io][cutting][gcode]") {
  const Trace trace = interpret("G21 G90\nG41 D1\nG1 X10 F100\nG64 P0.01\nM30\n", "unknown_codes.nc");
  CHECK(trace.unknown == std::vector<std::string>{"G41", "G64"});
  REQUIRE(trace.motions.size() == 1);
  CHECK(trace.motions[0].end.x() == 10);
}
