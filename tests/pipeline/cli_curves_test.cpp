#include <catch2/catch.hpp>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

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
