// A vessel printed upright: the print checks in the report, as warnings at
// the `print:` keys, as bad input with `print.strict`, flagged on the plot,
// and the keys' own errors.

#include <catch2/catch.hpp>
#include <filesystem>
#include <sstream>

#include "geometry/core/errors.h"
#include "io/design/read_design.h"
#include "io/file.h"
#include "pipeline/summary.h"
#include "tests/pipeline/cli_harness.h"

using namespace fabmesh;
using namespace fabmesh::testing;
namespace fs = std::filesystem;

namespace {

Design golden_shell(const std::string& print) {
  const std::string path = example("vessel_golden_shell.yaml");  // cm; flares out at 56 degrees from its foot
  std::vector<Override> overrides;
  if (!print.empty()) overrides.push_back({"print", print, "print=" + print});
  return parse_design(read_file(path), path, overrides);
}

}  // namespace

TEST_CASE("print checks: every vessel reports them, only `print:` makes warnings", "[pipeline][print]") {
  Design plain = golden_shell("");
  plain.common.outputs = {{"stl", "test", 0, 0}};
  const Result r = run_job(plain, into(fresh_dir("print_plain")));
  const Facts& p = r.facts.group("print");
  CHECK(p.number("max_overhang_deg") == 45.0);
  // The foot flares out along a straight span: atan(3 / 2) from vertical, from the bed.
  CHECK(p.group("outer").number("angle_deg") == Approx(56.309932474020215).epsilon(1e-9));
  CHECK(p.number("widest_ledge") > 0.8);
  CHECK(p.number("min_wall") == Approx(0.3).epsilon(1e-4));  // the 3 mm wall, in cm
  CHECK(p.number("min_wall_limit") == Approx(0.12));         // 1.2 mm, in cm
  CHECK_FALSE(std::get<bool>(*p.find("checked")));
  CHECK(std::get<std::vector<std::string>>(*p.find("findings")).size() == 1);
  CHECK(r.warnings.empty());  // reported, not warned of
  std::ostringstream summary;
  print_summary(r, summary);
  CHECK(summary.str().find("printed upright") == std::string::npos);
}

TEST_CASE("print checks: findings are warnings at their keys, the plot flags the overhang",
          "[pipeline][print]") {
  Design d = golden_shell("{bed: [22, 22, 3], min_wall: 0.35}");
  d.common.outputs = {{"stl", "test", 0, 0}, {"plot", "test", 0, 0}};
  const fs::path dir = fresh_dir("print_warnings");
  const Result r = run_job(d, into(dir));
  REQUIRE(r.warnings.size() == 3);
  CHECK(r.warnings[0].find("print.max_overhang_deg (default): the outer wall overhangs 56.31 degrees") !=
        std::string::npos);
  CHECK(r.warnings[1].find("print.min_wall: the wall is 0.3 cm thick (normal to the wall)") !=
        std::string::npos);
  CHECK(r.warnings[2].find(
            "print.bed: the vessel (5.19257 cm across, 4.13416 cm tall) does not fit the bed 22 x "
            "22 x 3 cm") != std::string::npos);
  const Facts& p = r.facts.group("print");
  CHECK_FALSE(std::get<bool>(*p.find("fits_bed")));
  std::ostringstream summary;
  print_summary(r, summary);
  CHECK(summary.str().find("printed upright: outer wall overhangs at most 56.3") != std::string::npos);
  // The plot: one flag, drawn along the foot's flare.
  const std::string svg = read_file((dir / "vessel_golden_shell.plot.svg").string());
  CHECK(svg.find("class=\"flag\"") != std::string::npos);
  CHECK(svg.find("overhang beyond 45\u00b0 from vertical") != std::string::npos);
  // A generous limit finds nothing to flag.
  Design lenient = golden_shell("{max_overhang_deg: 60}");
  lenient.common.outputs = {{"plot", "test", 0, 0}};
  const fs::path dir2 = fresh_dir("print_lenient");
  const Result l = run_job(lenient, into(dir2));
  CHECK(l.warnings.empty());
  CHECK(read_file((dir2 / "vessel_golden_shell.plot.svg").string()).find("class=\"flag\"") ==
        std::string::npos);
}

TEST_CASE("print checks: strict makes them bad input, exit 2 and nothing written", "[pipeline][print]") {
  const fs::path dir = fresh_dir("print_strict");
  const std::string design =
      edited_example(dir, "vessel_golden_shell.yaml",
                     "body:", "print:\n  bed: [22, 22, 25]\n  strict: true\nbody:", "cup.yaml");
  std::string text;
  CHECK(run_cli({"run", design, "-o", (dir / "out").string()}, &text) == 2);
  CHECK(!fs::exists(dir / "out" / "vessel_golden_shell.stl"));
  INFO(text);
  // At the limit's key (the default's, in the design's print map), naming the place.
  CHECK(
      text.find("print.max_overhang_deg (default): the vessel does not print upright within print's limits: "
                "the outer wall overhangs 56.31 degrees from vertical at (r 1.5, z 2)") != std::string::npos);
}

TEST_CASE("print checks: the example vase prints, and bad keys are placed", "[pipeline][print]") {
  Design vase = read_design(example("vessel_print.yaml"));
  vase.common.outputs = {{"stl", "test", 0, 0}};
  const Result r = run_job(vase, into(fresh_dir("print_vase")));
  CHECK(r.warnings.empty());
  const Facts& p = r.facts.group("print");
  CHECK(std::get<bool>(*p.find("fits_bed")));
  CHECK(p.group("outer").number("angle_deg") < 45.0);
  CHECK(p.group("inner").number("angle_deg") < 45.0);
  CHECK(p.number("min_wall") >= 1.2);
  // The steepest point is refined to within 1e-7 of the foot: the line says z 0, to its digits.
  CHECK(p.text("summary").find("outer wall overhangs at most 26.6 degrees (at r 35, z 0)") !=
        std::string::npos);

  const fs::path dir = fresh_dir("print_bad_keys");
  const auto fails_at = [&](const std::string& find, const std::string& replace, const std::string& words) {
    std::string text;
    const std::string design = edited_example(dir, "vessel_print.yaml", find, replace, "vase.yaml");
    CHECK(run_cli({"run", design, "-o", (dir / "out").string()}, &text) == 2);
    INFO(text);
    CHECK(text.find(words) != std::string::npos);
  };
  fails_at("max_overhang_deg: 45", "max_overhang_deg: 90",
           "vase.yaml:20:21: print.max_overhang_deg: max_overhang_deg = 90 must be in (0, 90)");
  fails_at("min_wall: 1.2", "min_wall: 0", "vase.yaml:21:13: print.min_wall: min_wall = 0 must be > 0");
  fails_at("min_wall: 1.2", "nozzle: 0.4", "nozzle");
  fails_at("bed: [220, 220, 250]", "bed: [220, 220]",
           "vase.yaml:19:8: print.bed: expected the printer's build volume [X, Y, Z]");
  fails_at("bed: [220, 220, 250]", "bed: [220, 0, 250]", "print.bed: bed = [220, 0, 250]");
  CHECK(!fs::exists(dir / "out"));
}
