// The design-level face of the fidelity checks: what a user sees when a
// base leaves no cavity, holes come too close, or fairing loses continuity.

#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "io/file.h"
#include "tests/pipeline/cli_harness.h"

using namespace fabmesh;
using namespace fabmesh::testing;
namespace fs = std::filesystem;

namespace {

std::string edited(const std::string& example_name, const std::string& find, const std::string& replace) {
  std::string text = read_file(example(example_name));
  const auto at = text.find(find);
  REQUIRE(at != std::string::npos);
  return text.replace(at, find.size(), replace);
}

}  // namespace

TEST_CASE("vessel run: a base as tall as the golden cup or taller is bad input and writes nothing",
          "[pipeline][vessel][errors]") {
  const fs::path dir = fresh_dir("fidelity_base");
  for (const char* base : {"100", "5"}) {
    INFO("base " << base);
    write_file_atomically((dir / "cup.yaml").string(),
                          edited("vessel_golden_shell.yaml", "base: 0.4", std::string("base: ") + base));
    std::string out;
    CHECK(run_cli({"run", (dir / "cup.yaml").string(), "-o", (dir / "out").string()}, &out) == 2);
    CHECK_THAT(out, Catch::Contains(std::string("base ") + base + " leaves no cavity") &&
                        Catch::Contains("rises only 4.13416"));
    CHECK((!fs::exists(dir / "out") || fs::is_empty(dir / "out")));
  }
  // The example itself: the report's bounding box is the object written.
  std::string out;
  REQUIRE(run_cli_json({"run", example("vessel_golden_shell.yaml"), "-o", (dir / "out").string(), "--json"},
                       &out) == 0);
  const nlohmann::json j = nlohmann::json::parse(out).at(0);
  CHECK(j["bounding_box"]["max"][2].get<double>() == Approx(6.134164).margin(1e-4));
  CHECK(j["bounding_box"]["min"][2].get<double>() == 2.0);
  CHECK(j["build"]["min_clearance"].get<double>() == Approx(0.3).margin(1e-5));
}

TEST_CASE("countertop run: holes closer than the tolerance are bad input located at the hole",
          "[pipeline][countertop][errors]") {
  const fs::path dir = fresh_dir("fidelity_clearance");
  // The oval sink (x 390..910) moved to within 0.02 of the cooktop (x 1370..1930).
  write_file_atomically(
      (dir / "near.yaml").string(),
      edited("countertop_g2.yaml", "center: [650, 330], a: 260", "center: [1109.98, 330], a: 260"));
  std::string out;
  CHECK(run_cli({"run", (dir / "near.yaml").string(), "-o", (dir / "out").string()}, &out) == 2);
  CHECK_THAT(out, Catch::Contains("near.yaml:") && Catch::Contains("comes within") &&
                      Catch::Contains("closer than the 0.045 the mesh is built within"));
  CHECK((!fs::exists(dir / "out") || fs::is_empty(dir / "out")));
  // The example: its smallest clearance is reported with where it is.
  REQUIRE(run_cli_json({"run", example("countertop_g2.yaml"), "-o", (dir / "out").string(), "--json"},
                       &out) == 0);
  const nlohmann::json j = nlohmann::json::parse(out).at(0);
  CHECK(j["build"]["min_clearance"].get<double>() > 50.0);
  CHECK_THAT(j["build"]["min_clearance_where"].get<std::string>(), Catch::Contains("holes["));
}

TEST_CASE("curve designs: fairing that loses declared G2 is bad input unless fair_keeps accepts it",
          "[pipeline][fairing][errors]") {
  const fs::path dir = fresh_dir("fidelity_fairing");
  const std::string faired =
      edited("tbezier_outline_g2.yaml", "  closed: true\n", "  closed: true\n  fair: curvature_variation\n");
  write_file_atomically((dir / "strict.yaml").string(), faired);
  const CliResult strict = run_fabmesh({"sample", (dir / "strict.yaml").string()});
  CHECK(strict.code == 2);
  CHECK_THAT(strict.err, Catch::Contains("strict.yaml:") && Catch::Contains("joint 1 (segments 1 -> 2)") &&
                             Catch::Contains("declared G2") && Catch::Contains("fair_keeps"));
  write_file_atomically((dir / "keeps.yaml").string(),
                        edited("tbezier_outline_g2.yaml", "  closed: true\n",
                               "  closed: true\n  fair: curvature_variation\n  fair_keeps: G1\n"));
  const CliResult keeps = run_fabmesh({"sample", (dir / "keeps.yaml").string()});
  CHECK(keeps.code == 0);
  CHECK_THAT(keeps.out, Catch::Contains("declared G2, measured G1"));
  // fair_keeps without fairing says what it is for.
  write_file_atomically((dir / "lonely.yaml").string(), edited("tbezier_outline_g2.yaml", "  closed: true\n",
                                                               "  closed: true\n  fair_keeps: G1\n"));
  const CliResult lonely = run_fabmesh({"sample", (dir / "lonely.yaml").string()});
  CHECK(lonely.code == 2);
  CHECK_THAT(lonely.err, Catch::Contains("lonely.yaml:") && Catch::Contains("needs fair"));
}
