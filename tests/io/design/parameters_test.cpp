// Named parameters and expressions in designs (docs/design-files.md,
// "Parameters and expressions"): the evaluator, the reader, `-D NAME=VALUE`.

#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <thread>
#include <vector>

#include "geometry/core/errors.h"
#include "io/design/design_source.h"
#include "io/design/expression.h"
#include "io/design/read_design.h"
#include "tests/io/design/cup_design.h"
#include "tests/io/design/design_text.h"

using namespace fabmesh;
using fabmesh::test::read_error;
using fabmesh::test::read_text;
using fabmesh::test::replaced;

namespace {

// The golden shell cup with its height, wall and base named. Line 6 declares
// height (its value at column 19), line 11 uses it in the profile's points
// (points[0][1] at column 18, points[1][1] at column 38), line 13 in the body
// (wall at column 27).
const std::string kParamCup = R"(name: cup
kind: vessel
units: cm
tolerance: 0.005
parameters:
  height: {value: 4, min: 2, max: 10, step: 0.1, description: "foot to rim"}
  wall: 0.3
  base: "=wall + 0.1"
profile:
  family: quasi_bspline
  points: [[1.5, "=2 + height"], [1, "=1 + height"], [2, 4], [3, 3], [1.5, 2]]
  lambdas: [0, 0, 0]
body: {mode: shell, wall: "=wall", base: "=base"}
)";

double eval(const std::string& text) {
  ExpressionEvaluator e;
  e.define("h", 10.0);
  e.define("w", 0.5);
  for (const std::string& name : e.names(text)) CHECK((name == "h" || name == "w"));
  return e.evaluate(text);
}

std::string eval_error(const std::string& text) {
  try {
    eval(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

const VesselDesign& vessel(const Design& d) { return std::get<VesselDesign>(d.body); }

}  // namespace

TEST_CASE("expressions: arithmetic, precedence, unary minus, functions and pi", "[io][design][parameters]") {
  CHECK(eval("1 + 2 * 3") == 7.0);
  CHECK(eval("(1 + 2) * 3") == 9.0);
  CHECK(eval("1 - 2 - 3") == -4.0);
  CHECK(eval("8 / 2 / 2") == 2.0);
  CHECK(eval("2 ^ 3 ^ 2") == 512.0);  // right to left
  CHECK(eval("-2 ^ 2") == -4.0);      // the power first
  CHECK(eval("2 ^ -1") == 0.5);
  CHECK(eval("2 * -3") == -6.0);
  CHECK(eval("-(1 + 2)") == -3.0);
  CHECK(eval("-h") == -10.0);
  CHECK(eval("+h") == 10.0);
  CHECK(eval("h * 0.6") == 6.0);
  CHECK(eval("1e-3 * h") == 0.01);
  CHECK(eval("min(3, h, 2)") == 2.0);
  CHECK(eval("max(3, h, 2)") == 10.0);
  CHECK(eval("min(w)") == 0.5);
  CHECK(eval("abs(-w)") == 0.5);
  CHECK(eval("sqrt(h * 10)") == 10.0);
  CHECK(eval("pi") == Approx(3.14159265358979323846).epsilon(0));
  CHECK(eval("sin(pi / 2)") == 1.0);
  CHECK(eval("cos(0)") == 1.0);
  CHECK(eval("tan(pi / 4)") == Approx(1.0));
  CHECK(eval("atan2(1, 1) * 4") == Approx(3.14159265358979323846));
  CHECK(eval("atan2(0, -1)") == Approx(3.14159265358979323846));  // (y, x)
  CHECK(eval("sin(30)") == Approx(std::sin(30.0)));               // radians
  // The names an expression uses, once each, functions and pi left out.
  ExpressionEvaluator e;
  CHECK(e.names("h * sin(w) + h / pi + max(wall_2, _x)") ==
        std::vector<std::string>{"h", "w", "wall_2", "_x"});
}

TEST_CASE("expressions: what they do not allow, and results that are not numbers",
          "[io][design][parameters]") {
  CHECK_THAT(eval_error("ln(h)"),
             Catch::StartsWith("the function 'ln' is not allowed: expressions use numbers"));
  CHECK_THAT(eval_error("rint(w)"), Catch::StartsWith("the function 'rint' is not allowed"));
  CHECK_THAT(eval_error("sum(1, 2)"), Catch::StartsWith("the function 'sum' is not allowed"));
  CHECK_THAT(eval_error("foo(1)"), Catch::StartsWith("there is no function 'foo'"));
  CHECK_THAT(eval_error("_e * 2"), Catch::StartsWith("the constant '_e' is not allowed"));
  CHECK_THAT(eval_error("_pi"), Catch::StartsWith("the constant '_pi' is not allowed"));
  CHECK_THAT(eval_error("sin"), Catch::StartsWith("'sin' is a function: write sin(...)"));
  CHECK_THAT(eval_error("h > 1 ? 2 : 3"), Catch::StartsWith("the operator '>' is not allowed"));
  // The conditional is allowed (a switch is 1 or 0); comparisons stay out of it.
  CHECK(eval("1 ? 2 : 3") == 2);
  CHECK(eval("0 ? 2 : 3") == 3);
  CHECK(eval("0 ? 1 / 0 : 3") == 3);  // the branch not taken is not evaluated
  CHECK_THAT(eval_error("h && w"), Catch::StartsWith("the operator '&&' is not allowed"));
  CHECK_THAT(eval_error("h || w"), Catch::StartsWith("the operator '||' is not allowed"));
  CHECK_THAT(eval_error("h == w"), Catch::StartsWith("the operator '==' is not allowed"));
  CHECK_THAT(eval_error("h = 2"), Catch::StartsWith("the operator '=' is not allowed"));
  CHECK_THAT(eval_error("h % 3"), Catch::StartsWith("the operator '%' is not allowed"));
  CHECK_THAT(eval_error("\"text\""), Catch::StartsWith("'\"' is not allowed"));
  CHECK_THAT(eval_error("1, 2"), Catch::StartsWith("a ',' outside a function's parentheses"));
  CHECK_THAT(eval_error("  "), Catch::StartsWith("the expression is empty"));
  CHECK_THAT(eval_error("2 * (3"), Catch::StartsWith("syntax error: "));
  CHECK_THAT(eval_error("2 h"), Catch::StartsWith("syntax error: "));
  CHECK_THAT(eval_error("h / (w - 0.5)"), Catch::Equals("division by zero (10 / 0)"));
  CHECK_THAT(eval_error("1 / (1 / 0)"),
             Catch::Equals("division by zero (1 / 0)"));  // not hidden by a later step
  CHECK_THAT(eval_error("min(1 / 0, 3)"), Catch::Equals("division by zero (1 / 0)"));
  CHECK_THAT(eval_error("0 ^ -1"), Catch::StartsWith("division by zero"));
  CHECK_THAT(eval_error("sqrt(-1)"), Catch::Equals("sqrt(-1): the square root of a negative number"));
  CHECK_THAT(eval_error("(-8) ^ (1 / 3)"), Catch::Contains("a negative number to a fractional power"));
  CHECK_THAT(eval_error("10 ^ 400"), Catch::Equals("10 ^ 400 is not a finite number"));
  CHECK_THAT(eval_error("1e300 * 1e300 / 1e300"), Catch::Equals("1e+300 * 1e+300 is not a finite number"));
  CHECK_THAT(eval_error("h * 1e12"),
             Catch::Equals("the result 10000000000000 is too large: numbers in a design are at most 1e+12 in "
                           "magnitude"));
  CHECK(eval("h * 1e11") == 1e12);  // the limit itself is a number
}

TEST_CASE("parameters: a design's parameters and expressions read as the numbers they stand for",
          "[io][design][parameters]") {
  const Design d = read_text(kParamCup);
  const VesselDesign& v = vessel(d);
  CHECK(v.profile.bspline_points[0] == Vec2(1.5, 6));
  CHECK(v.profile.bspline_points[1] == Vec2(1, 5));
  CHECK(v.wall == 0.3);
  CHECK(v.base == 0.3 + 0.1);
  REQUIRE(d.common.parameters.size() == 3);
  const DesignParameter& h = d.common.parameters[0];
  CHECK(h.name == "height");
  CHECK(h.value == 4.0);
  CHECK(h.min == 2.0);
  CHECK(h.max == 10.0);
  CHECK(h.step == 0.1);
  CHECK(h.description == "foot to rim");
  CHECK(d.common.parameters[1].name == "wall");
  CHECK_FALSE(d.common.parameters[1].min.has_value());
  CHECK(d.common.parameters[2].name == "base");
  CHECK(d.common.parameters[2].value == 0.3 + 0.1);
  // The same design with the literals the expressions give reads the same.
  const Design literal = read_text(test::kCup);  // the golden shell cup, as the other reading tests share it
  CHECK(vessel(literal).profile.bspline_points == v.profile.bspline_points);
  CHECK(vessel(literal).base == v.base);
  CHECK(literal.common.parameters.empty());
  // A parameter may use one declared after it; any number may be an expression, parameters or not.
  const Design later =
      read_text(replaced(replaced(kParamCup, "  wall: 0.3\n", "  wall: \"=thick / 2\"\n  thick: 0.6\n"),
                         "tolerance: 0.005", "tolerance: \"=1 / 200\""));
  CHECK(vessel(later).wall == 0.3);
  CHECK(later.common.tolerance == 0.005);
  CHECK(later.common.parameters[1].value == 0.3);
}

TEST_CASE("parameters: a bad name, reference or value is bad input at the expression's line and column",
          "[io][design][parameters][errors]") {
  SECTION("an unknown name") {
    CHECK(read_error(replaced(kParamCup, "\"=1 + height\"", "\"=1 + heigth\"")) ==
          "cup.yaml:11:38: profile.points[1][1]: \"=1 + heigth\": unknown name 'heigth' (the parameters are: "
          "height, wall, base)");
    CHECK(read_error(replaced(kParamCup, "base: \"=wall + 0.1\"", "base: \"=wal + 0.1\"")) ==
          "cup.yaml:8:9: parameters.base: \"=wal + 0.1\": unknown name 'wal' (the parameters are: height, "
          "wall, "
          "base)");
  }
  SECTION("a function, a constant or an operator expressions do not allow") {
    CHECK_THAT(
        read_error(replaced(kParamCup, "\"=1 + height\"", "\"=ln(height)\"")),
        Catch::StartsWith("cup.yaml:11:38: profile.points[1][1]: \"=ln(height)\": the function 'ln' is not "
                          "allowed: expressions use numbers"));
    CHECK_THAT(
        read_error(replaced(kParamCup, "\"=1 + height\"", "\"=rint(height)\"")),
        Catch::StartsWith("cup.yaml:11:38: profile.points[1][1]: \"=rint(height)\": the function 'rint'"));
    CHECK_THAT(
        read_error(replaced(kParamCup, "\"=1 + height\"", "\"=height > 4 ? 5 : 4\"")),
        Catch::StartsWith("cup.yaml:11:38: profile.points[1][1]: \"=height > 4 ? 5 : 4\": the operator "
                          "'>' is not allowed"));
    CHECK_THAT(read_error(replaced(kParamCup, "\"=1 + height\"", "\"=1 ? 5 :\"")),
               Catch::StartsWith("cup.yaml:11:38: profile.points[1][1]: \"=1 ? 5 :\": syntax error"));
    CHECK_THAT(
        read_error(replaced(kParamCup, "\"=wall\"", "\"=wall && 1\"")),
        Catch::StartsWith("cup.yaml:13:27: body.wall: \"=wall && 1\": the operator '&&' is not allowed"));
    CHECK_THAT(read_error(replaced(kParamCup, "\"=wall\"", "\"=_e\"")),
               Catch::StartsWith("cup.yaml:13:27: body.wall: \"=_e\": the constant '_e' is not allowed"));
  }
  SECTION("a cycle") {
    CHECK(
        read_error(replaced(kParamCup, "  wall: 0.3\n", "  wall: 0.3\n  a: \"=b + 1\"\n  b: \"=a * 2\"\n")) ==
        "cup.yaml:9:6: parameters.b: \"=a * 2\": the parameters refer to each other in a cycle: a -> b -> a");
    CHECK(read_error(replaced(kParamCup, "base: \"=wall + 0.1\"", "base: \"=base + 0.1\"")) ==
          "cup.yaml:8:9: parameters.base: \"=base + 0.1\": the parameters refer to each other in a cycle: "
          "base -> "
          "base");
    // Through a range bound too.
    CHECK(read_error(replaced(replaced(kParamCup, "min: 2,", "min: \"=base\","), "\"=wall + 0.1\"",
                              "\"=height / 10\"")) ==
          "cup.yaml:8:9: parameters.base: \"=height / 10\": the parameters refer to each other in a cycle: "
          "height -> base -> height");
  }
  SECTION(
      "a division by zero, a square root of a negative number, a result that is not finite or too large") {
    CHECK(read_error(replaced(kParamCup, "\"=wall + 0.1\"", "\"=wall / (height - 4)\"")) ==
          "cup.yaml:8:9: parameters.base: \"=wall / (height - 4)\": division by zero (0.3 / 0) (with wall = "
          "0.3, "
          "height = 4)");
    CHECK(read_error(replaced(kParamCup, "\"=wall + 0.1\"", "\"=sqrt(wall - 1)\"")) ==
          "cup.yaml:8:9: parameters.base: \"=sqrt(wall - 1)\": sqrt(-0.7): the square root of a negative "
          "number "
          "(with wall = 0.3)");
    CHECK_THAT(read_error(replaced(kParamCup, "\"=wall + 0.1\"", "\"=wall * 10 ^ 200 * 10 ^ 200\"")),
               Catch::StartsWith("cup.yaml:8:9: parameters.base: \"=wall * 10 ^ 200 * 10 ^ 200\": ") &&
                   Catch::EndsWith(" is not a finite number (with wall = 0.3)"));
    CHECK(read_error(replaced(kParamCup, "\"=2 + height\"", "\"=height * 1e12\"")) ==
          "cup.yaml:11:18: profile.points[0][1]: \"=height * 1e12\": the result 4000000000000 is too large: "
          "numbers "
          "in a design are at most 1e+12 in magnitude (with height = 4)");
  }
  SECTION("a value outside its range, or a bad range") {
    CHECK(read_error(replaced(kParamCup, "value: 4,", "value: 15,")) ==
          "cup.yaml:6:19: parameters.height: 15 is outside [2, 10]");
    CHECK(read_error(replaced(kParamCup, "value: 4,", "value: \"=wall\",")) ==
          "cup.yaml:6:19: parameters.height: 0.3 is outside [2, 10]");
    CHECK(read_error(replaced(kParamCup, "max: 10,", "max: 1,")) ==
          "cup.yaml:6:35: parameters.height.max: max = 1 is below min = 2");
    CHECK(read_error(replaced(kParamCup, "step: 0.1,", "step: 0,")) ==
          "cup.yaml:6:45: parameters.height.step: step = 0 must be > 0");
    CHECK(read_error(replaced(kParamCup, "{value: 4, min: 2, max: 10,", "{value: 4, min: 5,")) ==
          "cup.yaml:6:19: parameters.height: 4 is below the minimum 5");
    CHECK(read_error(replaced(kParamCup, "{value: 4, min: 2, max: 10,", "{value: 4, max: 3,")) ==
          "cup.yaml:6:19: parameters.height: 4 is above the maximum 3");
    CHECK(read_error(replaced(kParamCup, "value: 4, ", "")) ==
          "cup.yaml:6:11: parameters.height: missing required key 'value'");
    CHECK_THAT(read_error(replaced(kParamCup, "step: 0.1,", "stpe: 0.1,")),
               Catch::StartsWith("cup.yaml:6:39: parameters.height.stpe: unknown key 'stpe'"));
  }
  SECTION("a bad name, a name taken by designs or by expressions, a name declared twice") {
    CHECK_THAT(read_error(replaced(kParamCup, "  wall: 0.3\n", "  wall: 0.3\n  2x: 1\n")),
               Catch::StartsWith("cup.yaml:8:3: parameters.2x: '2x' is not a parameter name"));
    CHECK_THAT(read_error(replaced(kParamCup, "  wall: 0.3\n", "  wall: 0.3\n  wall-2: 1\n")),
               Catch::StartsWith("cup.yaml:8:3: parameters.wall-2: 'wall-2' is not a parameter name"));
    CHECK(
        read_error(replaced(kParamCup, "  wall: 0.3\n", "  wall: 0.3\n  thickness: 1\n")) ==
        "cup.yaml:8:3: parameters.thickness: 'thickness' is a top-level key of designs: choose another name");
    CHECK(read_error(replaced(kParamCup, "  wall: 0.3\n", "  wall: 0.3\n  profile: 1\n")) ==
          "cup.yaml:8:3: parameters.profile: 'profile' is a top-level key of designs: choose another name");
    CHECK(
        read_error(replaced(kParamCup, "  wall: 0.3\n", "  wall: 0.3\n  pi: 3\n")) ==
        "cup.yaml:8:3: parameters.pi: 'pi' names a function or constant of expressions: choose another name");
    CHECK_THAT(read_error(replaced(kParamCup, "  wall: 0.3\n", "  wall: 0.3\n  ln: 3\n")),
               Catch::Contains("'ln' names a function or constant of expressions"));
    CHECK(read_error(replaced(kParamCup, "  wall: 0.3\n", "  wall: 0.3\n  wall: 0.4\n")) ==
          "cup.yaml:8:3: parameters.wall: parameter 'wall' is declared twice (first at line 7, column 3)");
    CHECK_THAT(read_error(replaced(kParamCup, "  wall: 0.3\n", "  wall: [0.3]\n")),
               Catch::StartsWith("cup.yaml:7:9: parameters.wall: expected a number, an expression"));
    CHECK_THAT(read_error(replaced(kParamCup, "  wall: 0.3\n", "  wall: thick\n")),
               Catch::StartsWith("cup.yaml:7:9: parameters.wall: 'thick' is not a number"));
  }
  SECTION("a value the expression gives that is wrong for its key is reported at the expression") {
    CHECK_THAT(read_error(replaced(kParamCup, "\"=wall\"", "\"=wall - 1\"")),
               Catch::StartsWith("cup.yaml:13:27: body.wall: "));
  }
  SECTION("every error is a FileError at the expression's line and column") {
    try {
      read_text(replaced(kParamCup, "\"=1 + height\"", "\"=1 + heigth\""));
      FAIL("no error");
    } catch (const FileError& e) {
      CHECK(e.line() == 11);
      CHECK(e.column() == 38);
      CHECK(e.location().key == "profile.points[1][1]");
      CHECK(e.location().line == 11);
    }
  }
}

TEST_CASE("parameters: -D NAME=VALUE sets a declared parameter, its range still applies",
          "[io][design][parameters][overrides]") {
  const Design d = read_text(kParamCup, {"height=5", "wall=0.25"});
  CHECK(vessel(d).profile.bspline_points[0] == Vec2(1.5, 7));
  CHECK(vessel(d).profile.bspline_points[1] == Vec2(1, 6));
  CHECK(vessel(d).wall == 0.25);
  CHECK(d.common.parameters[0].value == 5.0);
  CHECK(d.common.parameters[0].min == 2.0);  // the range is kept
  CHECK(d.common.parameters[2].value == 0.25 + 0.1);
  // The value may be an expression; the full path works too.
  CHECK(read_text(kParamCup, {"height==wall * 20"}).common.parameters[0].value == 6.0);
  CHECK(read_text(kParamCup, {"parameters.height.value=7"}).common.parameters[0].value == 7.0);
  // An expression in an override of any field.
  CHECK(vessel(read_text(kParamCup, {"body.wall==wall / 2"})).wall == 0.15);
  // Out of range: the override is named.
  CHECK(read_error(kParamCup, {"height=15"}) == "-D height=15: parameters.height: 15 is outside [2, 10]");
  CHECK(
      read_error(kParamCup, {"height==heigth"}) ==
      "-D height==heigth: parameters.height: \"=heigth\": unknown name 'heigth' (the parameters are: height, "
      "wall, base)");
  CHECK(read_error(kParamCup, {"body.wall==wall / 0"}) ==
        "-D body.wall==wall / 0: body.wall: \"=wall / 0\": division by zero (0.3 / 0) (with wall = 0.3)");
  // A design without parameters: -D of a plain name is a top-level key as ever.
  const std::string plain = R"(name: cup
kind: vessel
units: cm
profile:
  family: quasi_bspline
  points: [[1.5, 6], [1, 5], [2, 4], [3, 3], [1.5, 2]]
body: {mode: shell, wall: 0.3, base: 0.4}
)";
  CHECK_THAT(read_error(plain, {"tolerance=0.01", "height=5"}),
             Catch::StartsWith("-D height=5: height: unknown key 'height' (expected one of: ") &&
                 Catch::EndsWith(")"));
  // A name the design does not declare is an unknown key, the parameters listed.
  try {
    read_text(kParamCup, {"heigth=5"});
    FAIL("no error");
  } catch (const UnknownKeyError& e) {
    CHECK(e.field() == "heigth");
    CHECK_THAT(std::string(e.what()),
               Catch::StartsWith("-D heigth=5: heigth: unknown key 'heigth'") &&
                   Catch::EndsWith(", or a parameter of the design: height, wall, base"));
  }
}

TEST_CASE("parameters: the canonical text changes with a parameter's value", "[io][design][parameters]") {
  const DesignSource source(kParamCup, "cup.yaml");
  const std::string plain = source.canonical({});
  const std::string taller = source.canonical({parse_override("height=5")});
  CHECK(taller != plain);
  CHECK(source.canonical({parse_override("height=5")}) == taller);
  CHECK(source.canonical({parse_override("height=6")}) != taller);
  std::string canonical;
  const Design d = source.resolve({parse_override("height=5")}, &canonical);
  CHECK(canonical == taller);
  CHECK(d.common.parameters[0].value == 5.0);
}

TEST_CASE("parameters: designs read on several threads at once give identical results",
          "[io][design][parameters]") {
  const DesignSource source(kParamCup, "cup.yaml");
  auto facts = [](const Design& d) {
    std::vector<double> out;
    for (const Vec2& p : vessel(d).profile.bspline_points) {
      out.push_back(p.x());
      out.push_back(p.y());
    }
    out.push_back(vessel(d).wall);
    out.push_back(vessel(d).base);
    for (const DesignParameter& p : d.common.parameters) out.push_back(p.value);
    return out;
  };
  constexpr int kThreads = 4;
  constexpr int kRounds = 25;
  std::vector<std::vector<double>> expected;
  for (int t = 0; t < kThreads; ++t) {
    expected.push_back(facts(read_text(kParamCup, {"height=" + std::to_string(3 + t)})));
  }
  std::vector<int> mismatches(kThreads, 0);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      const std::string height = "height=" + std::to_string(3 + t);
      for (int i = 0; i < kRounds; ++i) {
        // Every other round from the shared source, as a batch resolves its variants.
        const Design d =
            i % 2 == 0 ? read_text(kParamCup, {height}) : source.resolve({parse_override(height)});
        if (facts(d) != expected[static_cast<std::size_t>(t)]) ++mismatches[static_cast<std::size_t>(t)];
      }
    });
  }
  for (std::thread& t : threads) t.join();
  for (int t = 0; t < kThreads; ++t) CHECK(mismatches[static_cast<std::size_t>(t)] == 0);
  CHECK(expected[0] != expected[1]);
}
