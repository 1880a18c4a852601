// Parameterised designs through every command that reads designs: run,
// plot, optimize, sample and batch (docs/design-files.md, "Parameters and
// expressions"; docs/batch.md).

#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/pipeline/batch/batch_fixture.h"
#include "tests/pipeline/cli_harness.h"

using namespace fabmesh;
using namespace fabmesh::testing;
namespace fs = std::filesystem;

namespace {

// The golden profile of configs/examples/golden_profile.yaml, its top point's
// height a parameter (line 9, column 23: the expression).
const std::string kCurve = R"(name: golden_profile
kind: curve
units: cm
tolerance: 0.001
parameters:
  height: {value: 4, min: 2, max: 10}
curve:
  family: quasi_bspline
  points: [["=6 / 4", "=2 + height"], [1, 5], [2, 4], [3, 3], [1.5, 2]]
  lambdas: [0, 0, 0]
)";

// The batch tests' cup (batch_fixture.h), its height and wall parameters.
const std::string kCup = R"(name: cup
kind: vessel
units: cm
tolerance: 0.02
parameters:
  height: {value: 4, min: 2, max: 10}
  wall: 0.3
profile:
  family: quasi_bspline
  points: [[1.5, "=2 + height"], [1, 5], [2, 4], [3, 3], [1.5, 2]]
  lambdas: [0, 0, 0]
body: {mode: shell, wall: "=wall", base: 0.4}
outputs: [stl]
)";

std::string written(const fs::path& dir, const std::string& name, const std::string& text) {
  write_text(dir / name, text);
  return (dir / name).string();
}

}  // namespace

TEST_CASE("parameters: run --json lists the values used, -D NAME=VALUE sets one", "[pipeline][parameters]") {
  const fs::path dir = fresh_dir("parameters_run");
  const std::string cup = written(dir, "cup.yaml", kCup);
  CliResult r = run_fabmesh({"run", cup, "-o", (dir / "a").string() + "/", "--json", "-q"});
  INFO(r.err);
  REQUIRE(r.code == 0);
  nlohmann::json item = only_item(r.out);
  CHECK(item["parameters"] == nlohmann::json{{"height", 4.0}, {"wall", 0.3}});
  // The golden shell's height (vessel_golden_shell.yaml: the rim cut square stands above the profile).
  const double height = item["bounding_box"]["size"][2].get<double>();
  CHECK(height == Approx(4.1342).margin(0.01));
  r = run_fabmesh({"run", cup, "-o", (dir / "b").string() + "/", "--json", "-q", "-D", "height=5"});
  REQUIRE(r.code == 0);
  item = only_item(r.out);
  CHECK(item["parameters"]["height"] == 5.0);
  CHECK(item["bounding_box"]["size"][2].get<double>() > height + 0.5);
  // The parameters are listed in the order declared.
  CHECK(item["parameters"].begin().key() == "height");
  // The text summary says them too.
  r = run_fabmesh({"run", cup, "-o", (dir / "d").string() + "/", "-D", "height=5"});
  REQUIRE(r.code == 0);
  CHECK_THAT(r.out, Catch::Contains("\n  parameters: height = 5, wall = 0.3\n"));
  // A design without parameters has no such key.
  r = run_fabmesh(
      {"run", example("vessel_golden_shell.yaml"), "-o", (dir / "c").string() + "/", "--json", "-q"});
  REQUIRE(r.code == 0);
  CHECK_FALSE(only_item(r.out).contains("parameters"));
}

TEST_CASE("parameters: a bad expression or value is exit 2 naming its place, nothing written",
          "[pipeline][parameters][errors]") {
  const fs::path dir = fresh_dir("parameters_errors");
  std::string text = kCup;
  text.replace(text.find("\"=2 + height\""), 13, "\"=2 + heigth\"");
  const std::string bad = written(dir, "bad.yaml", text);
  const std::string message = bad +
                              ":10:18: profile.points[0][1]: \"=2 + heigth\": unknown name 'heigth' (the "
                              "parameters are: height, wall)";
  CliResult r = run_fabmesh({"run", bad, "-o", (dir / "out").string() + "/"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains(message));
  CHECK_FALSE(fs::exists(dir / "out"));
  r = run_fabmesh({"plot", bad, "-o", (dir / "out").string() + "/"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains(message));
  CHECK_FALSE(fs::exists(dir / "out"));
  // Out of range by -D: the override is named.
  const std::string cup = written(dir, "cup.yaml", kCup);
  r = run_fabmesh({"run", cup, "-o", (dir / "out").string() + "/", "-D", "height=15"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("-D height=15: parameters.height: 15 is outside [2, 10]"));
  CHECK_FALSE(fs::exists(dir / "out"));
  // A division by zero in a -D value.
  r = run_fabmesh({"run", cup, "-o", (dir / "out").string() + "/", "-D", "wall==height / (height - 4)"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err,
             Catch::Contains("-D wall==height / (height - 4): parameters.wall: \"=height / (height - 4)\": "
                             "division by zero (4 / 0) (with height = 4)"));
  CHECK_FALSE(fs::exists(dir / "out"));
  // The curve commands read the same way.
  std::string curve_text = kCurve;
  curve_text.replace(curve_text.find("\"=2 + height\""), 13, "\"=ln(height)\"");
  const std::string bad_curve = written(dir, "bad_curve.yaml", curve_text);
  for (const char* command : {"optimize", "sample"}) {
    INFO(command);
    r = run_fabmesh({command, bad_curve});
    CHECK(r.code == 2);
    CHECK_THAT(r.err,
               Catch::Contains(bad_curve + ":9:23: curve.points[0][1]: \"=ln(height)\": the function 'ln' is "
                                           "not allowed"));
  }
}

TEST_CASE("parameters: optimize, sample and plot read a parameterised design as its literal twin",
          "[pipeline][parameters]") {
  const fs::path dir = fresh_dir("parameters_commands");
  const std::string curve = written(dir, "golden_profile.yaml", kCurve);
  const std::string literal = example("golden_profile.yaml");
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"optimize", "--json"}, std::vector<std::string>{"sample", "--csv"},
        std::vector<std::string>{"sample"}}) {
    INFO(args[0]);
    std::vector<std::string> with_parameters = args;
    with_parameters.insert(with_parameters.begin() + 1, curve);
    std::vector<std::string> with_literals = args;
    with_literals.insert(with_literals.begin() + 1, literal);
    const CliResult a = run_fabmesh(with_parameters);
    const CliResult b = run_fabmesh(with_literals);
    INFO(a.err);
    REQUIRE(a.code == 0);
    REQUIRE(b.code == 0);
    std::string out = a.out;
    for (std::size_t at; (at = out.find(curve)) != std::string::npos;) out.replace(at, curve.size(), literal);
    CHECK(out == b.out);
    CHECK_FALSE(a.out.empty());
  }
  REQUIRE(run_fabmesh({"plot", curve, "-o", (dir / "p.svg").string()}).code == 0);
  REQUIRE(run_fabmesh({"plot", literal, "-o", (dir / "l.svg").string()}).code == 0);
  CHECK(file_text(dir / "p.svg") == file_text(dir / "l.svg"));
  // plot takes -D by name: a taller profile draws differently.
  REQUIRE(run_fabmesh({"plot", curve, "-o", (dir / "t.svg").string(), "-D", "height=6"}).code == 0);
  CHECK(file_text(dir / "t.svg") != file_text(dir / "p.svg"));
}

TEST_CASE("parameters: a batch grid over a parameter, named by a template that uses it",
          "[pipeline][parameters][batch]") {
  const fs::path dir = batch_folder("parameters_grid", R"(design: pcup.yaml
name: cup_h{height}
set: {wall: 0.25}
grid:
  height: [4, 5]
)");
  write_text(dir / "pcup.yaml", kCup);
  int code = -1;
  const nlohmann::json report = batch_json({(dir / "m.yaml").string(), "-o", (dir / "out").string()}, &code);
  CHECK(code == 0);
  CHECK(report["ok"] == 2);
  const std::vector<nlohmann::json> rows = summary_rows(dir / "out");
  REQUIRE(rows.size() == 2);
  CHECK(rows[0]["name"] == "cup_h4");
  CHECK(rows[1]["name"] == "cup_h5");
  REQUIRE(fs::is_regular_file(dir / "out" / "cup_h5" / "cup_h5.stl"));
  // Each variant is what `run -D` makes of the same values.
  REQUIRE(run_fabmesh({"run", (dir / "pcup.yaml").string(), "-o", (dir / "run").string() + "/", "-D",
                       "wall=0.25", "-D", "height=5", "-D", "name=cup_h5", "-q"})
              .code == 0);
  CHECK(file_text(dir / "out" / "cup_h5" / "cup_h5.stl") == file_text(dir / "run" / "cup_h5.stl"));
  CHECK(file_text(dir / "out" / "cup_h4" / "cup_h4.stl") != file_text(dir / "out" / "cup_h5" / "cup_h5.stl"));
}

TEST_CASE("parameters: batch tables set parameters by name, a name the design lacks stops the batch",
          "[pipeline][parameters][batch]") {
  const fs::path dir = batch_folder("parameters_table", R"(design: pcup.yaml
table: t.csv
)");
  write_text(dir / "pcup.yaml", kCup);
  write_text(dir / "t.csv", "name,height,wall\nlow,3,0.2\nhigh,6,0.35\n");
  int code = -1;
  nlohmann::json report = batch_json({(dir / "m.yaml").string(), "-o", (dir / "out").string()}, &code);
  CHECK(code == 0);
  CHECK(report["ok"] == 2);
  CHECK(fs::is_regular_file(dir / "out" / "high" / "high.stl"));
  // A typo: refused before any variant runs, the design's parameters named.
  write_text(dir / "m2.yaml", "design: pcup.yaml\nname: cup_{heigth}\ngrid:\n  heigth: [4, 5]\n");
  const CliResult r = run_fabmesh({"batch", (dir / "m2.yaml").string(), "-o", (dir / "out2").string(), "-q"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("unknown key 'heigth'") &&
                        Catch::Contains("or a parameter of the design: height, wall") &&
                        Catch::Contains("every variant sets this path, so none was run"));
  CHECK_FALSE(fs::exists(dir / "out2" / "cup_4"));
}
