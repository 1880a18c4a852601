#include "io/design/read_design.h"

#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <fstream>

#include "geometry/core/error_checks.h"
#include "geometry/fairing/build_curve.h"
#include "io/design/overrides.h"

using namespace fabmesh;

namespace {

const char* kCurveHeader = "kind: curve\ntolerance: 0.01\ncurve:\n";

// The message of the FileError that parsing `yaml` throws ("" if none).
std::string error_of(const std::string& yaml) {
  try {
    parse_design(yaml, "d.yaml");
  } catch (const FileError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("design: a T-Bezier composite with joins, an ellipse arc and a line is read", "[io][design]") {
  const Design d = parse_design(std::string(kCurveHeader) + R"(
  family: tbezier
  segments:
    - points: [[1, 0.2], [0.2, 0.4], [1.6, 1.4], [1, 0.2]]
      lambda: 0
      mu: 0
    - join: {continuity: G1, alpha: 2}
      points: [[3, 1], [4, 0]]
      lambda: -1
    - join: {continuity: G2, alpha: 1, beta: 0}
      points: [[5, 1]]
    - ellipse_arc: {center: [0, 0], a: 3, b: 2, rotation_deg: 0, from_deg: 0, to_deg: 90}
      continuity: G0
)",
                                "dir/my_curve.yaml");
  CHECK(d.common.name == "my_curve");
  CHECK(std::string(kind_name(d)) == "curve");
  CHECK(d.common.units == "mm");
  CHECK(d.common.outputs.empty());  // none given: the output table supplies the kind's defaults
  const CurveSpec& c = std::get<CurveDesign>(d.body).curve;
  REQUIRE(c.segments.size() == 4);
  CHECK(c.segments[1].join->continuity == Continuity::G1);
  CHECK(c.segments[1].join->alpha == 2.0);
  CHECK(c.segments[1].lambda == -1.0);
  CHECK(c.segments[3].kind == SegmentKind::EllipseArc);
}

TEST_CASE("design: errors name file, line, column and field", "[io][design][errors]") {
  const std::string base =
      std::string(kCurveHeader) + "  family: tbezier\n  segments:\n    - points: [[0,0],[1,1],[2,1],[3,0]]\n";
  SECTION("lambda out of range") {
    const std::string e = error_of(base + "      lambda: 1.7\n");
    CHECK_THAT(e, Catch::StartsWith("d.yaml:6:7: curve.segments[0]:") && Catch::Contains("lambda = 1.7"));
  }
  SECTION("mistyped key") {
    CHECK_THAT(error_of(base + "      lamda: 0.5\n"),
               Catch::Contains("d.yaml:7:7") && Catch::Contains("unknown key 'lamda'"));
  }
  SECTION("NaN and Inf") {
    CHECK_THAT(error_of(base + "      mu: .nan\n"),
               Catch::Contains("curve.segments[0].mu") && Catch::Contains("finite"));
    CHECK_THAT(error_of(base + "      mu: .inf\n"), Catch::Contains("finite"));
  }
  SECTION("not a number") {
    CHECK_THAT(error_of(base + "      mu: abc\n"),
               Catch::Contains("d.yaml:7:11") && Catch::Contains("not a number"));
  }
  SECTION("too few control points") {
    CHECK_THAT(error_of(std::string(kCurveHeader) +
                        "  family: tbezier\n  segments:\n    - points: [[0,0],[1,1],[2,1]]\n"),
               Catch::Contains("needs 4 control points"));
  }
}

TEST_CASE("design: missing keys, bad kinds and bad tolerance are errors", "[io][design][errors]") {
  CHECK_THAT(error_of("tolerance: 0.01\n"), Catch::Contains("missing required key 'kind'"));
  CHECK_THAT(error_of("kind: teapot\n"), Catch::Contains("'teapot' is not one of"));
  CHECK_THAT(
      error_of("kind: curve\ntolerance: 0\ncurve: {family: quasi_bspline, points: [[0,0],[1,1],[2,0]]}\n"),
      Catch::Contains("d.yaml:2:12: tolerance") && Catch::Contains("must be > 0"));
  CHECK_THAT(error_of("kind: curve\ntolerance: -1\n"), Catch::Contains("must be > 0"));
  CHECK_THAT(error_of("kind: curve\n"), Catch::Contains("missing required key 'curve'"));
  CHECK_THAT(error_of("kind: curve\ncurve: [1, 2\n"), Catch::Contains("invalid YAML"));
  CHECK_THAT(error_of("- 1\n- 2\n"), Catch::Contains("must be a YAML map"));
}

TEST_CASE("design: quasi_bspline counts and ranges", "[io][design][errors]") {
  const std::string head = std::string(kCurveHeader) + "  family: quasi_bspline\n";
  CHECK_THAT(error_of(head + "  points: [[0,0],[1,1]]\n"), Catch::Contains("at least 3 points"));
  CHECK_THAT(error_of(head + "  points: [[0,0],[1,1],[2,0],[3,1]]\n  lambdas: [0]\n"),
             Catch::Contains("expected n - 1 = 2 values"));
  CHECK_THAT(error_of(head + "  points: [[0,0],[1,1],[2,0]]\n  lambdas: [-9]\n"),
             Catch::Contains("curve.lambdas[0]") && Catch::Contains("lambda_1 = -9 is outside [-8, 1]"));
  CHECK_THAT(error_of(head + "  points: [[0,0],[1,1],[2,0]]\n  fair: best\n"), Catch::Contains("curve.fair"));
}

TEST_CASE("design: a quasi_bspline through points", "[io][design]") {
  const std::string head = std::string(kCurveHeader) + "  family: quasi_bspline\n";
  const Design d = parse_design(head + "  through: [[0, 0], [3, 6], [6, 0]]\n", "d.yaml");
  const CurveSpec& spec = std::get<CurveDesign>(d.body).curve;
  REQUIRE(spec.bspline_through.size() == 3);
  REQUIRE(spec.bspline_points.size() == 3);
  CHECK(spec.bspline_points[1].y() == Approx(9.0));  // (0 + 4 y + 0) / 6 = 6
  CHECK(spec.bspline_through_deviation < 1e-15);
  const BuiltCurve built = build_curve(spec);
  CHECK(built.through == spec.bspline_through);
  CHECK((built.curve.segments()[1].point(0.0) - Vec2(3, 6)).norm() < 1e-14);

  // Where a through curve goes wrong: at the key, line and column.
  CHECK_THAT(
      error_of(head + "  through: [[0,0],[1,1],[2,0]]\n  points: [[0,0],[1,1],[2,0]]\n"),
      Catch::Contains("d.yaml:5:12: curve.through: give either points") && Catch::Contains("not both"));
  CHECK_THAT(error_of(head + "  through: [[0,0],[1,1],[2,0]]\n  fair: strain\n"),
             Catch::Contains("d.yaml:6:9: curve.fair:") && Catch::Contains("off its through points"));
  CHECK_THAT(error_of(head + "  through: [[0,0],[1,1],[2,0]]\n  lambdas: [-8]\n"),
             Catch::Contains("d.yaml:5:12: curve.through:") && Catch::Contains("singular"));
  CHECK_THAT(error_of(head + "  through: [[0,0],[1,1]]\n"),
             Catch::Contains("curve.through") && Catch::Contains("at least 3 points q0..qn"));
  // -D moves a through point as it moves a control point.
  const Design moved = parse_design(head + "  through: [[0, 0], [3, 6], [6, 0]]\n", "d.yaml",
                                    {parse_override("curve.through[1]=[3, 12]")});
  CHECK(std::get<CurveDesign>(moved.body).curve.bspline_points[1].y() == Approx(18.0));
}

TEST_CASE("design: hbezier parameters are range checked against lambda*(alpha)", "[io][design][errors]") {
  const std::string head =
      std::string(kCurveHeader) + "  family: hbezier\n  segments:\n    - points: [[0,0],[1,2],[3,3],[4,1]]\n";
  CHECK_THAT(error_of(head + "      alpha: 12\n"), Catch::Contains("alpha = 12"));
  CHECK_THAT(error_of(head + "      alpha: 1\n      lambda: -3.3\n"), Catch::Contains("lambda = -3.3"));
  CHECK(error_of(head + "      alpha: 1\n      lambda: -3.2\n").empty());
}

TEST_CASE("design: geometry errors found when the curve is built carry the file location",
          "[io][design][errors]") {
  const Design d = parse_design(std::string(kCurveHeader) + R"(
  family: tbezier
  closed: true
  segments:
    - points: [[0, 0], [1, 2], [3, 2.5], [4, 1]]
    - line: {to: [0.5, 0]}
)",
                                "d.yaml");
  // Geometry names the key; io places it at the key's line and column.
  try {
    (void)build_curve(std::get<CurveDesign>(d.body).curve);
    FAIL("an open curve declared closed was built");
  } catch (const GeometryError& e) {
    CHECK_THAT(std::string(e.what()), Catch::Contains("does not close"));
    CHECK_THAT(location_text(placed(d.common, e.location())), Catch::Contains("d.yaml:5:3: curve"));
  }
}

TEST_CASE("design: a polyline entry is the same curve as one line entry per point", "[io][design]") {
  const Design lines = parse_design(std::string(kCurveHeader) + R"(
  family: tbezier
  closed: true
  segments:
    - line: {from: [0, 0], to: [4, 0]}
    - line: {to: [4, 3]}
    - line: {to: [0, 3]}
    - line: {to: [0, 0]}
)",
                                    "a.yaml");
  const Design poly = parse_design(std::string(kCurveHeader) + R"(
  family: tbezier
  closed: true
  segments:
    - polyline: [[0, 0], [4, 0], [4, 3], [0, 3], [0, 0]]
)",
                                   "b.yaml");
  const CompositeCurve a = build_curve(std::get<CurveDesign>(lines.body).curve).curve;
  const CompositeCurve b = build_curve(std::get<CurveDesign>(poly.body).curve).curve;
  REQUIRE(a.size() == 4);
  REQUIRE(b.size() == 4);
  for (std::size_t i = 0; i < 4; ++i) {
    CHECK(b.segments()[i].kind() == SegmentKind::Line);
    CHECK(a.segments()[i].control_points()[0] == b.segments()[i].control_points()[0]);
    CHECK(a.segments()[i].control_points()[1] == b.segments()[i].control_points()[1]);
  }
  CHECK_THAT(
      error_of(std::string(kCurveHeader) + "  family: tbezier\n  segments:\n    - polyline: [[0, 0]]\n"),
      Catch::Contains("curve.segments[0].polyline") && Catch::Contains("at least 2"));
}

TEST_CASE("design: a polyline can read its points from a CSV file beside the design", "[io][design]") {
  const std::string dir = std::string(FABMESH_TEST_TMP) + "/";
  {
    std::ofstream csv(dir + "square.csv");
    csv << "x,y\n# the front edge first\n0,0\n4, 0\n4;3\n0 3\n0,0\n";
  }
  const std::string yaml =
      std::string(kCurveHeader) +
      "  family: tbezier\n  closed: true\n  segments:\n    - polyline: {file: square.csv}\n";
  const Design d = parse_design(yaml, dir + "square.yaml");
  const CompositeCurve c = build_curve(std::get<CurveDesign>(d.body).curve).curve;
  REQUIRE(c.size() == 4);
  CHECK(c.segments()[1].control_points()[0] == Vec2(4, 0));
  CHECK(c.segments()[1].control_points()[1] == Vec2(4, 3));

  std::ofstream(dir + "bad.csv") << "0,0\n1,1\n2,oops\n";
  try {
    parse_design(
        std::string(kCurveHeader) + "  family: tbezier\n  segments:\n    - polyline: {file: bad.csv}\n",
        dir + "bad.yaml");
    FAIL("a bad CSV row must be an error");
  } catch (const FileError& e) {
    // Located at the design's key that names the file, then at the CSV's row and column.
    CHECK_THAT(e.what(), Catch::StartsWith(dir + "bad.yaml:6:24: curve.segments[0].polyline.file: ") &&
                             Catch::Contains("bad.csv:3:3: 'oops' is not a number"));
  }
  CHECK_THAT(error_of(std::string(kCurveHeader) +
                      "  family: tbezier\n  segments:\n    - polyline: {file: /nonexistent/p.csv}\n"),
             Catch::Contains("cannot open the points file"));
}

namespace {

// A 1200 x 600 countertop with a sink and three tap holes (35, 28 and 35 mm)
// behind it, cut on a router; `cnc` goes on in the cnc section.
std::string tap_hole_design(const std::string& holes_extra = "", const std::string& cnc = "") {
  return "name: t\nkind: countertop\ntolerance: 0.05\nthickness: 30\n"
         "outline:\n  family: tbezier\n  closed: true\n  segments:\n"
         "    - polyline: [[0, 0], [1200, 0], [1200, 600], [0, 600], [0, 0]]\n"
         "holes:\n"
         "  - rounded_rect: {center: [600, 330], size: [500, 380], radius: 40}\n"
         "  - drill: {center: [600, 80], diameter: 35}\n"
         "  - drill: {center: [300, 80], diameter: 28}\n"
         "  - drill: {center: [900, 80], diameter: 35}\n" +
         holes_extra + "cnc:\n  tool_diameter: 12\n" + cnc;
}

// The FileError that reading `yaml` (as t.yaml) throws: its key, and its
// message starts at the key's place ("t.yaml:LINE:COLUMN: KEY: ...").
void check_bad(const std::string& yaml, const std::string& key, const std::string& says) {
  INFO(yaml);
  try {
    parse_design(yaml, "t.yaml");
    FAIL("accepted");
  } catch (const FileError& e) {
    const std::string what = e.what();
    INFO(what);
    CHECK(e.location().key == key);
    CHECK(e.location().line > 0);
    CHECK(what.rfind("t.yaml:", 0) == 0);
    CHECK_THAT(what, Catch::Contains(": " + key + ": ") && Catch::Contains(says));
  }
}

}  // namespace

TEST_CASE("design: tap holes are circles with a drill, numbered from 2 without a tool table",
          "[io][design][countertop][drill]") {
  const Design d = parse_design(tap_hole_design(), "t.yaml");
  const auto& c = std::get<CountertopDesign>(d.body);
  REQUIRE(c.holes.size() == 4);
  CHECK_FALSE(c.holes[0].drill);
  for (std::size_t i = 1; i < 4; ++i) {
    INFO(i);
    REQUIRE(c.holes[i].drill);
    CHECK(c.holes[i].shape == "drill");
    CHECK(c.holes[i].curve.key == fmt::format("holes[{}]", i));
    // The exact circle: one whole ellipse arc of equal semi-axes about the centre.
    REQUIRE(c.holes[i].curve.segments.size() == 1);
    const SegmentSpec& s = c.holes[i].curve.segments[0];
    CHECK(s.kind == SegmentKind::EllipseArc);
    CHECK(s.ellipse.a == 0.5 * c.holes[i].drill->diameter);
    CHECK(s.ellipse.b == s.ellipse.a);
    CHECK(s.ellipse.center == c.holes[i].drill->center);
    CHECK(s.ellipse.to_deg - s.ellipse.from_deg == 360.0);
  }
  // Each diameter the next number from 2, in order of first use.
  CHECK(c.holes[1].drill->tool == 2);
  CHECK(c.holes[2].drill->tool == 3);
  CHECK(c.holes[3].drill->tool == 2);
  REQUIRE(c.cnc);
  CHECK(c.cnc->options.tools.empty());
  CHECK(end_mill_number(c.cnc->options) == 1);
  CHECK(c.cnc->options.drill.peck == 0.0);
  CHECK(drill_feed(c.cnc->options) == c.cnc->options.plunge);
  CHECK(drill_retract(c.cnc->options) == c.cnc->options.safe_z);
  // Without a cnc section a tap hole is a cut-out of the files only.
  std::string plain = tap_hole_design();
  plain.erase(plain.find("cnc:"));
  const Design p = parse_design(plain, "t.yaml");
  CHECK(std::get<CountertopDesign>(p.body).holes[1].drill->tool == 0);
}

TEST_CASE("design: a tool table gives the drills and the router bit, the drill cycle its options",
          "[io][design][countertop][drill]") {
  const std::string table =
      "  tools:\n"
      "    - {number: 4, type: drill, diameter: 35}\n"
      "    - {number: 3, type: drill, diameter: 35}\n"
      "    - {number: 9, type: drill, diameter: 28}\n"
      "    - {number: 6, type: end_mill, diameter: 12}\n"
      "  drill: {peck: 8, retract: 2, feed: 250, spindle: 3000}\n";
  const Design d = parse_design(tap_hole_design("", table), "t.yaml");
  const auto& c = std::get<CountertopDesign>(d.body);
  CHECK(c.holes[1].drill->tool == 3);  // the lowest-numbered drill of its diameter
  CHECK(c.holes[2].drill->tool == 9);
  CHECK(c.holes[3].drill->tool == 3);
  const CncOptions& o = c.cnc->options;
  REQUIRE(o.tools.size() == 4);
  CHECK(o.tools[3].type == ToolType::EndMill);
  CHECK(end_mill_number(o) == 6);
  CHECK(o.drill.peck == 8.0);
  CHECK(drill_retract(o) == 2.0);
  CHECK(drill_feed(o) == 250.0);
  CHECK(drill_spindle(o) == 3000.0);
  // A hole may name its drill; the table's end mill is the bit when tool_diameter is not given.
  std::string named = tap_hole_design("", table);
  named.replace(named.find("center: [900, 80], diameter: 35}"), 32,
                "center: [900, 80], diameter: 35, tool: 4}");
  named.replace(named.find("  tool_diameter: 12\n"), 20, "");
  const Design n = parse_design(named, "t.yaml");
  CHECK(std::get<CountertopDesign>(n.body).holes[3].drill->tool == 4);
  CHECK(std::get<CountertopDesign>(n.body).cnc->options.tool_diameter == 12.0);
}

TEST_CASE("design: bad tap holes and tool tables are FileErrors at their key",
          "[io][design][countertop][drill][errors]") {
  const std::string drills =
      "  tools: [{number: 1, type: end_mill, diameter: 12}, {number: 2, type: drill, diameter: 35}, "
      "{number: 3, type: drill, diameter: 28}]\n";
  // A diameter not > 0.
  {
    std::string y = tap_hole_design();
    y.replace(y.find("diameter: 28"), 12, "diameter: 0");
    check_bad(y, "holes[2].drill.diameter", "must be > 0");
  }
  // No drill of the hole's diameter in the table.
  {
    std::string y = tap_hole_design("  - drill: {center: [100, 500], diameter: 30}\n", drills);
    check_bad(y, "holes[4].drill.diameter", "no drill of that diameter (drills: T2 35, T3 28)");
  }
  // Two tools of one number; a tool diameter not > 0; a type neither end_mill nor drill.
  check_bad(tap_hole_design("",
                            "  tools: [{number: 2, type: drill, diameter: 35}, {number: 2, type: drill, "
                            "diameter: 28}]\n"),
            "cnc.tools[1].number", "cnc.tools[0] has that number already");
  check_bad(tap_hole_design("",
                            "  tools: [{number: 2, type: drill, diameter: 35}, {number: 3, type: drill, "
                            "diameter: -28}]\n"),
            "cnc.tools[1].diameter", "must be > 0");
  check_bad(tap_hole_design("",
                            "  tools: [{number: 2, type: drill, diameter: 35}, {number: 3, type: saw, "
                            "diameter: 28}]\n"),
            "cnc.tools[1].type", "'saw' is not one of: end_mill, drill");
  // The end mill is the router bit: of its diameter, and only one.
  check_bad(tap_hole_design("",
                            "  tools: [{number: 1, type: end_mill, diameter: 10}, {number: 2, type: drill, "
                            "diameter: 35}, {number: 3, type: drill, diameter: 28}]\n"),
            "cnc.tools[0].diameter", "cnc.tool_diameter = 12");
  check_bad(tap_hole_design("",
                            "  tools: [{number: 1, type: end_mill, diameter: 12}, {number: 5, type: "
                            "end_mill, diameter: 12}]\n"),
            "cnc.tools[1].type", "the router cut uses one bit");
  // With no end mill listed, tool 1 is the router bit's.
  check_bad(tap_hole_design("",
                            "  tools: [{number: 1, type: drill, diameter: 35}, {number: 3, type: drill, "
                            "diameter: 28}]\n"),
            "cnc.tools[0].number", "the router bit is tool 1");
  // A named drill larger (or smaller) than the hole it drills, or the end mill.
  {
    const std::string big =
        "  tools: [{number: 2, type: drill, diameter: 35}, {number: 3, type: drill, diameter: 28}, "
        "{number: 7, type: drill, diameter: 40}]\n";
    std::string y = tap_hole_design("", big);
    y.replace(y.find("diameter: 35}\n  - drill: {center: [300"), 13, "diameter: 35, tool: 7}");
    check_bad(y, "holes[1].drill.tool", "larger than the hole it drills");
    std::string small = tap_hole_design("", big);
    small.replace(small.find("diameter: 35}\n  - drill: {center: [300"), 13, "diameter: 35, tool: 3}");
    check_bad(small, "holes[1].drill.tool", "smaller than the hole (35): the hole would come out 28");
    std::string mill = tap_hole_design("", drills);
    mill.replace(mill.find("diameter: 28}"), 13, "diameter: 28, tool: 1}");
    check_bad(mill, "holes[2].drill.tool", "the end mill");
  }
  // A tool number with no table to number it in, or with no cnc section at all.
  {
    std::string y = tap_hole_design();
    y.replace(y.find("diameter: 28}"), 13, "diameter: 28, tool: 3}");
    check_bad(y, "holes[2].drill.tool", "gives no tools");
    y.erase(y.find("cnc:"));
    check_bad(y, "holes[2].drill.tool", "the design has no cnc section");
  }
  // Tabs on a tap hole; a drill with an unknown key or no diameter.
  check_bad(tap_hole_design("  - drill: {center: [100, 500], diameter: 35}\n    tabs: {count: 2}\n"),
            "holes[4].tabs", "a drilled hole has no tabs");
  check_bad(tap_hole_design("  - drill: {center: [100, 500], radius: 17.5}\n"), "holes[4].drill.radius",
            "unknown key 'radius'");
  check_bad(tap_hole_design("  - drill: {center: [100, 500]}\n"), "holes[4].drill", "diameter");
  // The drill cycle's options.
  check_bad(tap_hole_design("", "  drill: {peck: -1}\n"), "cnc.drill.peck", "must be >= 0");
  check_bad(tap_hole_design("", "  drill: {retract: 20}\n"), "cnc.drill.retract", "at most cnc.safe_z");
  check_bad(tap_hole_design("", "  drill: {feed: 0}\n"), "cnc.drill.feed", "must be > 0");
  check_bad(tap_hole_design("", "  drill: {dwell: 1}\n"), "cnc.drill.dwell", "unknown key 'dwell'");
}
