#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "tests/pipeline/cli_harness.h"

using namespace fabmesh;
using namespace fabmesh::testing;

namespace {

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = std::string(FABMESH_TEST_TMP) + "/" + name;
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST_CASE("cli optimize --json: Example 4 strain lambdas", "[pipeline][cli]") {
  const CliResult r = run_fabmesh({"optimize", example("example4_profile.yaml"), "--json"});
  REQUIRE(r.code == 0);
  const auto j = only_item(r.out);  // one curve: one item, naming its design and curve
  CHECK(j["design"] == example("example4_profile.yaml"));
  CHECK(j["curve"] == "curve");
  CHECK(j["family"] == "quasi_bspline");
  CHECK(j["energy_kind"] == "strain");
  REQUIRE(j["lambdas"].size() == 3);
  CHECK(j["lambdas"][0].get<double>() == Approx(-1.9492).margin(5e-5));
  CHECK(j["energy"].get<double>() > 0.0);
}

TEST_CASE("cli optimize --json: T-Bezier segments with lambda, mu, energy", "[pipeline][cli]") {
  const CliResult r = run_fabmesh({"optimize", example("tbezier_outline_g2.yaml"), "--json"});
  REQUIRE(r.code == 0);
  const auto j = only_item(r.out);
  CHECK(j["family"] == "tbezier");
  REQUIRE(j["segments"].size() >= 4);
  for (const auto& s : j["segments"]) {
    CHECK(s["lambda"].get<double>() >= -2.0);
    CHECK(s["lambda"].get<double>() <= 1.0);
    CHECK(s["mu"].get<double>() >= -2.0);
    CHECK(s["mu"].get<double>() <= 1.0);
  }
  // G1 joins survive fairing (joined points stay on the tangent ray).
  for (const auto& jt : j["joints"]) {
    if (jt["declared"] == "G1") CHECK(jt["continuity_lost"] == false);
  }
}

TEST_CASE("cli sample --csv: every example samples within its tolerance", "[pipeline][cli]") {
  for (const char* name : {"example4_profile.yaml", "golden_profile.yaml", "tbezier_outline_g2.yaml",
                           "hbezier_composite.yaml", "countertop_outline_g1.yaml"}) {
    const CliResult r = run_fabmesh({"sample", example(name), "--csv"});
    INFO(name << ": " << r.err);
    REQUIRE(r.code == 0);
    CHECK(r.out.rfind("curve,x,y\n", 0) == 0);
    CHECK(std::count(r.out.begin(), r.out.end(), '\n') > 10);
  }
}

TEST_CASE("cli exit codes: bad input is 2 with a located message, --help is 0", "[pipeline][cli][errors]") {
  CHECK(run_fabmesh({"--help"}).code == 0);
  CHECK(run_fabmesh({"sample", "--help"}).code == 0);
  const CliResult missing = run_fabmesh({"sample", "/nonexistent/design.yaml"});
  CHECK(missing.code == 2);
  CHECK_THAT(missing.err, Catch::Contains("cannot open"));
  const std::string bad = write_temp("bad_lambda.yaml",
                                     "kind: curve\ncurve:\n  family: tbezier\n  segments:\n"
                                     "    - points: [[0,0],[1,1],[2,1],[3,0]]\n      lambda: 3\n");
  const CliResult r = run_fabmesh({"optimize", bad});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("bad_lambda.yaml:5:7") && Catch::Contains("lambda = 3"));
  CHECK(run_fabmesh({"sample"}).code == 2);
  CHECK(run_fabmesh({"frobnicate"}).code == 2);
}

TEST_CASE("cli sample: a closed outline that crosses itself is bad input naming the segments",
          "[pipeline][cli][errors]") {
  // A figure eight: two lines crossing at (1, 1), closed by two more.
  const std::string path = write_temp("eight.yaml",
                                      "kind: curve\ncurve:\n  family: tbezier\n  closed: true\n  segments:\n"
                                      "    - line: {from: [0, 0], to: [2, 2]}\n    - line: {to: [2, 0]}\n"
                                      "    - line: {to: [0, 2]}\n    - line: {to: [0, 0]}\n");
  const CliResult r = run_fabmesh({"sample", path});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("eight.yaml:3:3: curve") && Catch::Contains("crosses itself") &&
                        Catch::Contains("segments 1 and 3"));
}

TEST_CASE("cli optimize: a design without curves is bad input", "[pipeline][cli][errors]") {
  const CliResult r = run_fabmesh({"optimize", example("surface_basin_shell.yaml")});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("surface_basin_shell.yaml") && Catch::Contains("no curves to optimize"));
}

TEST_CASE("cli sample and plot: a profile through points", "[pipeline][cli][through]") {
  const std::string design = example("vessel_through_shell.yaml");
  const CliResult r = run_fabmesh({"sample", design});
  INFO(r.err);
  REQUIRE(r.code == 0);
  // The control points solved, each given exactly (the ends are the through points).
  CHECK_THAT(r.out, Catch::Contains("# profile: through 5 points; the control points solved from them") &&
                        Catch::Contains("#   p0 = [3.2, 22]") && Catch::Contains("#   p4 = [3.6, 0]") &&
                        Catch::Contains("#   p2 = ["));
  // The through points are on the sampled curve: the samples include the joints.
  const std::vector<std::pair<double, double>> through{{3.2, 22}, {2.6, 18}, {4.6, 13}, {5.8, 7}, {3.6, 0}};
  std::istringstream lines(r.out);
  std::vector<std::pair<double, double>> samples;
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream xy(line);
    double x = 0, y = 0;
    xy >> x >> y;
    samples.emplace_back(x, y);
  }
  for (const auto& [x, y] : through) {
    double nearest = 1e9;
    for (const auto& [sx, sy] : samples) nearest = std::min(nearest, std::hypot(sx - x, sy - y));
    CHECK(nearest < 1e-9);
  }
  // The plot draws them as dots on the curve.
  const auto dir = fresh_dir("through_plot");
  REQUIRE(run_fabmesh({"plot", design, "-o", (dir / "p.svg").string()}).code == 0);
  const std::string svg = read_file((dir / "p.svg").string());
  CHECK_THAT(svg, Catch::Contains("<g class=\"through-points\" data-name=\"profile\" data-points=\"5\"") &&
                      Catch::Contains("a point the curve is given to pass through"));
  // -D moves a through point; a singular system is bad input at its key.
  const CliResult moved = run_fabmesh({"sample", design, "-D", "profile.through[2]=[5, 13]"});
  CHECK(moved.code == 0);
  CHECK(moved.out != r.out);
  const CliResult singular = run_fabmesh({"sample", design, "-D", "profile.lambdas=[-8, -8, -8]"});
  CHECK(singular.code == 2);
  CHECK_THAT(singular.err,
             Catch::Contains("vessel_through_shell.yaml:13:") && Catch::Contains("profile.through"));
}
