#include "io/design/read_design.h"

#include <catch2/catch.hpp>
#include <fstream>

#include "geometry/core/error_checks.h"
#include "geometry/fairing/build_curve.h"

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
