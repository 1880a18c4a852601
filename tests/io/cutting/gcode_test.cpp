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

TEST_CASE(
    "gcode: tap holes are drilled first, by tool, one block of every word each, then M6 back to the bit",
    "[io][cutting][gcode][drill]") {
  Toolpath tp = slab_with_round_sink();
  const std::string plain = encode_gcode(tp, {});
  // Three holes, given out of tool order: drilled T2, T2, T3, each tool changed to once.
  tp.drills = drilling_order({{Vec2(100, 500), 35, 2, "holes[1] (drill)"},
                              {Vec2(200.25, 500), 28, 3, "holes[2] (drill)"},
                              {Vec2(800, 100), 35, 2, "holes[3] (drill)"}},
                             tp.options);
  REQUIRE(tp.drills.size() == 3);
  CHECK(tp.drills[1].label == "holes[3] (drill)");
  const std::string program = encode_gcode(tp, {});
  CHECK(program == encode_gcode(tp, {}));
  CHECK_THAT(
      program,
      Catch::Contains("(tools: T1 end mill 12 mm, T2 drill 35 mm, T3 drill 28 mm)\n"
                      "(drilling first: 3 holes, G81 from R 10 to z -30 at 600 mm/min, spindle 18000 rpm)\n"
                      "G21 G90 G94 G17\nG0 Z10\n"
                      "(drill T2: diameter 35 mm, 2 holes)\nM6 T2\nM3 S18000\n"
                      "G98 G81 X100 Y500 Z-30 R10 F600 (holes[1] [drill])\n"
                      "G98 G81 X800 Y100 Z-30 R10 F600 (holes[3] [drill])\nG80\n"
                      "(drill T3: diameter 28 mm, 1 hole)\nG0 Z10\nM5\nM6 T3\nM3 S18000\n"
                      "G98 G81 X200.25 Y500 Z-30 R10 F600 (holes[2] [drill])\nG80\n"
                      "(routing: T1, the end mill)\nG0 Z10\nM5\nM6 T1\nM3 S18000\nG0 X"));
  // The routing is the program without holes, move for move; its first feed states F again.
  const std::string routing = plain.substr(plain.find("\nG0 X"));
  CHECK(program.substr(program.find("\nG0 X")) == routing);
  CHECK(routing.find(" F600") < routing.find("G1 ", routing.find("G1 ") + 1));
  // The estimate counts the cycles: 40 mm down from R each, the rapids up and across.
  const ToolpathTotals with = toolpath_totals(tp);
  tp.drills.clear();
  const ToolpathTotals without = toolpath_totals(tp);
  CHECK(with.drilling == Approx(120));
  CHECK(with.cutting == without.cutting);
  CHECK(with.rapid > without.rapid + 3 * 40);
  CHECK(with.minutes == Approx(without.minutes + 120.0 / 600 + (with.rapid - without.rapid) / 10000));
  // Without tap holes nor a tool table nothing changes: no tool change at all.
  CHECK(encode_gcode(tp, {}) == plain);
  CHECK(plain.find("M6") == std::string::npos);
}

TEST_CASE("gcode: pecks (G83 Q), an R plane, a tool table and a cm model written in inches",
          "[io][cutting][gcode][drill]") {
  CncOptions o;
  o.tool_diameter = 1.2;
  o.depth = 3;
  o.breakthrough = 0.1;
  o.step_down = 1;
  o.feed = 300;
  o.plunge = 60;
  o.safe_z = 1;
  o.lead_in = 0.8;
  o.tabs.width = 1;
  o.tabs.height = 0.3;
  o.tolerance = 0.005;
  o.tools = {{7, ToolType::Drill, 3.5}, {5, ToolType::EndMill, 1.2}};
  o.drill.peck = 1.27;
  o.drill.retract = 0.254;
  o.drill.feed = 25.4;
  o.drill.spindle = 2000;
  const CompositeCurve slab = polygon({Vec2(0, 0), Vec2(90, 0), Vec2(90, 60), Vec2(0, 60)});
  Toolpath tp = plan_toolpath(slab, {}, o);
  tp.drills = drilling_order({{Vec2(25.4, 12.7), 3.5, 7, "holes[0] (drill)"}}, o);
  GcodeOptions g;
  g.model_units = "cm";
  g.units = "in";
  g.decimals = 4;
  const std::string program = encode_gcode(tp, g);
  CHECK_THAT(program, Catch::Contains(
                          "\nM6 T7\nM3 S2000\nG98 G83 X10 Y5 Z-1.2205 R0.1 Q0.5 F10 (holes[0] [drill])\nG80\n"
                          "(routing: T5, the end mill)\nG0 Z0.3937\nM5\nM6 T5\nM3 S18000\n"));
  CHECK_THAT(program, Catch::Contains("(tools: T5 end mill 0.4724 in, T7 drill 1.378 in)"));
  // A tool table given without tap holes: the program still selects the bit by its number.
  tp.drills.clear();
  CHECK_THAT(encode_gcode(tp, g),
             Catch::Contains("G0 Z0.3937\n(routing: T5, the end mill)\nM6 T5\nM3 S18000\nG0 X"));
}

TEST_CASE("drilling: a hole's drill must be in the table and of its diameter, webs as between routed loops",
          "[io][cutting][gcode][drill][errors]") {
  CncOptions o;
  CHECK_THROWS_AS(drilling_order({{Vec2(0, 0), 0, 2, "holes[0] (drill)"}}, o), GeometryError);
  CHECK_THROWS_AS(drilling_order({{Vec2(0, 0), 35, 1, "holes[0] (drill)"}}, o), GeometryError);  // the bit
  o.tools = {{1, ToolType::EndMill, 12}, {2, ToolType::Drill, 35}};
  CHECK_NOTHROW(drilling_order({{Vec2(0, 0), 35, 2, "holes[0] (drill)"}}, o));
  try {
    drilling_order({{Vec2(0, 0), 30, 2, "holes[4] (drill)"}}, o);
    FAIL("a 35 mm drill for a 30 mm hole was accepted");
  } catch (const GeometryError& e) {
    CHECK(e.where() == "holes[4] (drill)");
    CHECK_THAT(std::string(e.what()), Catch::Contains("tool 2 is a drill of diameter 35, not the hole's 30"));
  }
  CHECK_THROWS_AS(drilling_order({{Vec2(0, 0), 35, 3, "holes[0] (drill)"}}, o), GeometryError);
  // The tool table itself.
  o.tools = {{1, ToolType::EndMill, 12}, {1, ToolType::Drill, 35}};
  CHECK_THROWS_AS(validate_cnc_options(o), RangeError);
  o.tools = {{1, ToolType::EndMill, 10}};
  CHECK_THROWS_AS(validate_cnc_options(o), RangeError);
  o.tools = {{1, ToolType::Drill, 35}};
  CHECK_THROWS_AS(validate_cnc_options(o), RangeError);
  o.tools = {{2, ToolType::Drill, 35}};
  CHECK_NOTHROW(validate_cnc_options(o));
  CHECK(end_mill_number(o) == 1);
  o.drill.retract = 11;  // above safe_z
  CHECK_THROWS_AS(validate_cnc_options(o), RangeError);
  // A 35 mm hole 20 from a loop's samples keeps a web of 2.5 (+ the samples' deviation): under 12.
  o.drill.retract.reset();
  const std::vector<Vec2> outline{Vec2(0, 0), Vec2(900, 0), Vec2(900, 600), Vec2(0, 600)};
  const std::vector<Vec2> sink{Vec2(400, 200), Vec2(500, 200), Vec2(500, 300), Vec2(400, 300)};
  const std::vector<Vec2> tap{};  // the drill's own loop is skipped
  const std::vector<const std::vector<Vec2>*> loops{&outline, &sink, &tap};
  const std::vector<std::string> labels{"outline", "holes[0] (rounded_rect)", "holes[1] (drill)"};
  const std::vector<DrillHole> ok{{Vec2(450, 340), 35, 2, "holes[1] (drill)"}};
  CHECK_NOTHROW(check_drill_webs(ok, {2}, loops, labels, 0.01, o));
  const std::vector<DrillHole> near{{Vec2(450, 320), 35, 2, "holes[1] (drill)"}};
  try {
    check_drill_webs(near, {2}, loops, labels, 0.01, o);
    FAIL("a 2.5 web was accepted");
  } catch (const GeometryError& e) {
    CHECK(e.where() == "holes[1] (drill)");
    CHECK_THAT(std::string(e.what()),
               Catch::Contains(
                   "holes[1] (drill): the web between it and holes[0] (rounded_rect) is at most 2.51 near "
                   "(450, 301.25), narrower than 12"));
  }
  o.min_web = 2;
  CHECK_NOTHROW(check_drill_webs(near, {2}, loops, labels, 0.01, o));
}
