// Printer- and web-ready outputs through the command line: units, 3MF read by
// PrusaSlicer, GLB accepted by the Khronos validator, Draco at real sizes, and
// the peers' conventions for -o, --export-format, --version, -q.

#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "geometry/mesh/weld.h"
#include "geometry/validation/validate.h"
#include "io/design/read_design.h"
#include "io/file.h"
#include "io/mesh/draco.h"
#include "io/mesh/gltf.h"
#include "io/mesh/read_mesh.h"
#include "io/mesh/stl.h"
#include "pipeline/output_table.h"
#include "tests/io/mesh/external_tool.h"
#include "tests/pipeline/cli_harness.h"

using namespace fabmesh;
using namespace fabmesh::testing;
namespace fs = std::filesystem;

namespace {

// The whole file, for tests that compare bytes.
std::string bytes_of(const fs::path& p) { return read_file(p.string()); }

// A 2400 x 650 x 30 mm countertop whose outline is exact lines and arcs.
const char* kLongCountertop = R"(name: long_top
kind: countertop
units: mm
tolerance: 0.01
thickness: 30
outline:
  family: tbezier
  closed: true
  segments:
    - line: {from: [0, 0], to: [2350, 0]}
    - circle_arc: {center: [2350, 50], radius: 50, from_deg: -90, to_deg: 0}
      continuity: G1
    - line: {to: [2400, 650]}
    - polyline: [[0, 650], [0, 0]]
holes:
  - rounded_rect: {center: [600, 330], size: [500, 400], radius: 40}
outputs: [stl, drc]
)";

}  // namespace

TEST_CASE("units: a design in cm is written to STL in mm unless asked otherwise, and the report says so",
          "[pipeline][outputs][units]") {
  const fs::path dir = fresh_dir("units_cm");
  std::string out;
  REQUIRE(
      run_cli_json({"run", example("vessel_golden_solid.yaml"), "-o", (dir / "mm").string() + "/", "--json"},
                   &out) == 0);
  const auto j = nlohmann::json::parse(out).at(0);
  CHECK(j["units"] == "cm");
  CHECK(j["export_units"] == "mm");
  CHECK(j["files"][0]["units"] == "mm");
  const auto size = j["bounding_box"]["size"];
  CHECK(j["bounding_box"]["units"] == "cm");
  const ValidationReport mm =
      validate(weld(parse_stl(bytes_of(dir / "mm" / "vessel_golden_solid.stl"), "stl")).soup);
  CHECK(mm.valid());
  CHECK(mm.volume == Approx(1000.0 * j["volume"].get<double>()).epsilon(1e-6));

  REQUIRE(run_cli({"run", example("vessel_golden_solid.yaml"), "-o", (dir / "cm").string() + "/",
                   "--export-units", "cm"}) == 0);
  const TriangleSoup cm = weld(parse_stl(bytes_of(dir / "cm" / "vessel_golden_solid.stl"), "stl")).soup;
  CHECK(validate(cm).volume == Approx(j["volume"].get<double>()).epsilon(1e-6));
  Vec3 lo = cm.vertices.front(), hi = lo;
  for (const Vec3& p : cm.vertices) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  CHECK((hi - lo).z() == Approx(size[2].get<double>()).epsilon(1e-6));
  // The design key does the same as the option.
  REQUIRE(run_cli({"run", example("vessel_golden_solid.yaml"), "-o", (dir / "key").string() + "/", "-D",
                   "export_units=cm"}) == 0);
  CHECK(bytes_of(dir / "key" / "vessel_golden_solid.stl") ==
        bytes_of(dir / "cm" / "vessel_golden_solid.stl"));
}

TEST_CASE("3mf: PrusaSlicer reads fabmesh's 3MF of a cm design at its size in mm, manifold, and slices it",
          "[pipeline][outputs][3mf][prusaslicer]") {
  REQUIRE_PROGRAM("prusa-slicer");
  const fs::path dir = fresh_dir("prusa_3mf");
  std::string out;
  REQUIRE(
      run_cli_json({"run", example("vessel_golden_shell.yaml"), "-o", (dir / "cup.3mf").string(), "--json"},
                   &out) == 0);
  const auto j = nlohmann::json::parse(out).at(0);
  REQUIRE(fs::exists(dir / "cup.3mf"));
  test::ToolRun run;
  auto info = test::prusa_info((dir / "home").string(), (dir / "cup.3mf").string(), &run);
  INFO(run.output);
  REQUIRE(run.code == 0);
  CHECK(info["manifold"] == "yes");
  const auto size = j["bounding_box"]["size"];  // cm
  CHECK(std::stod(info["size_x"]) == Approx(10.0 * size[0].get<double>()).margin(0.01));
  CHECK(std::stod(info["size_z"]) == Approx(10.0 * size[2].get<double>()).margin(0.01));
  const test::ToolRun slice = test::prusa_slicer(
      (dir / "home").string(), "--export-gcode " + test::quoted((dir / "cup.3mf").string()) + " --output " +
                                   test::quoted((dir / "cup.gcode").string()));
  INFO(slice.output);
  CHECK(slice.code == 0);
  CHECK(fs::file_size(dir / "cup.gcode") > 10000);
  // fabmesh check reads its own 3MF back, unit and all.
  REQUIRE(run_cli_json({"check", (dir / "cup.3mf").string(), "--json"}, &out) == 0);
  const auto c = only_item(out);
  CHECK(c["format"] == "3MF");
  CHECK(c["units"] == "mm");
  CHECK(c["valid"] == true);
}

TEST_CASE("glb: every GLB fabmesh writes, plain and Draco, passes the Khronos validator with no warnings",
          "[pipeline][outputs][gltf]") {
  REQUIRE(test::gltf_validator_installed());
  const fs::path dir = fresh_dir("glb_validator");
  for (const char* design : {"vessel_golden_shell.yaml", "countertop_g1.yaml", "surface_basin_shell.yaml",
                             "surface_basin_open.yaml"}) {
    INFO(design);
    std::string out;
    REQUIRE(run_cli({"run", example(design), "-o", dir.string(), "-D", "outputs=[glb, glb_draco]"}, &out) ==
            0);
    const std::string stem = fs::path(design).stem().string();
    for (const std::string& file : {stem + ".glb", stem + ".draco.glb"}) {
      INFO(file);
      const test::ToolRun v = test::run_tool(test::gltf_validator_command((dir / file).string()));
      INFO(v.output);
      CHECK(v.code == 0);
      // Metres, Y up: the countertop (mm) is 2.4 m long and 30 mm thick along y.
      const GltfContent g = parse_gltf(bytes_of(dir / file), file);
      Vec3 lo = g.soup.vertices.front(), hi = lo;
      for (const Vec3& p : g.soup.vertices) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
      if (stem == "countertop_g1") {
        CHECK((hi - lo).x() == Approx(2.4).margin(1e-4));
        CHECK((hi - lo).y() == Approx(0.03).margin(1e-5));
      }
    }
  }
}

TEST_CASE("draco: long designs at fine tolerances get their Draco file, its error measured",
          "[pipeline][outputs][draco]") {
  const fs::path dir = fresh_dir("draco_long");
  write_file_atomically((dir / "long_top.yaml").string(), kLongCountertop);
  std::string out;
  // A 2400 mm countertop at 0.01 mm: the old a-priori bound refused it; measured, 30 bits are plenty.
  REQUIRE(run_cli_json({"run", (dir / "long_top.yaml").string(), "-o", (dir / "out").string(), "--json"},
                       &out) == 0);
  const auto j = nlohmann::json::parse(out).at(0);
  REQUIRE(j["files"].size() == 2);
  CHECK(j["skipped_outputs"].empty());
  const double left = j["tolerance"].get<double>() - j["max_deviation"].get<double>();
  CHECK(j["files"][1]["format"] == "drc");
  CHECK(j["files"][1]["max_added_error"].get<double>() <= left);
  CHECK(validate(parse_draco(bytes_of(dir / "out" / "long_top.drc"), "drc")).valid());
  // A 520 mm vessel at 0.005 mm.
  REQUIRE(run_cli_json({"run", example("vessel_golden_solid.yaml"), "-o", (dir / "out").string(), "-D",
                        "units=mm", "-D", "tolerance=0.005", "-D",
                        "profile.points=[[75, 520], [50, 400], [100, 300], [150, 150], [75, 0]]", "--json"},
                       &out) == 0);
  CHECK(nlohmann::json::parse(out).at(0)["skipped_outputs"].empty());
}

TEST_CASE(
    "draco: an output that cannot meet the tolerance is skipped with a reason, or fails the job if asked",
    "[pipeline][outputs][draco][errors]") {
  const fs::path dir = fresh_dir("draco_impossible");
  // A 10 mm plate 1e6 mm from the origin at a 1e-5 mm tolerance: float32 positions there are 0.06 mm apart.
  const std::string far =
      "name: far\nkind: countertop\ntolerance: 0.00001\noutputs: [obj, drc]\nthickness: 1\n"
      "outline: {family: tbezier, closed: true, segments: [{polyline: [[1000000.3, 0.3], [1000010.3, 0.3], "
      "[1000010.3, 10.3], "
      "[1000000.3, 10.3], [1000000.3, 0.3]]}]}\n";
  write_file_atomically((dir / "far.yaml").string(), far);
  std::string out;
  REQUIRE(run_cli({"run", (dir / "far.yaml").string(), "-o", (dir / "out").string()}, &out) == 0);
  CHECK_THAT(out, Catch::Contains("fabmesh: warning: " + (dir / "far.yaml").string() + ": skipped drc") &&
                      Catch::Contains("raise the tolerance"));
  CHECK(fs::exists(dir / "out" / "far.obj"));
  CHECK_FALSE(fs::exists(dir / "out" / "far.drc"));
  fs::remove_all(dir / "out");
  CHECK(run_cli(
            {"run", (dir / "far.yaml").string(), "-o", (dir / "out").string(), "-D", "on_output_error=fail"},
            &out) == 2);
  CHECK_THAT(out, Catch::Contains("drc: Draco cannot keep every vertex"));
  CHECK((!fs::exists(dir / "out") || fs::is_empty(dir / "out")));
}

TEST_CASE(
    "command line: -o FILE.ext picks the format, -o DIR/ a folder, -o - standard output, --export-format",
    "[pipeline][outputs][cli]") {
  const fs::path dir = fresh_dir("cli_outputs");
  const std::string design = example("vessel_golden_solid.yaml");
  REQUIRE(run_cli({"run", design, "-o", (dir / "one.stl").string()}) == 0);
  CHECK(fs::is_regular_file(dir / "one.stl"));
  CHECK(fs::directory_iterator(dir) != fs::directory_iterator());
  REQUIRE(run_cli({"run", design, "-o", (dir / "one.draco.glb").string()}) == 0);
  CHECK(bytes_of(dir / "one.draco.glb").substr(0, 4) == "glTF");
  REQUIRE(run_cli({"run", design, "-o", (dir / "folder").string() + "/"}) == 0);
  CHECK(fs::exists(dir / "folder" / "vessel_golden_solid.stl"));
  CHECK(fs::exists(dir / "folder" / "vessel_golden_solid.drc"));
  REQUIRE(run_cli({"run", design, "-o", (dir / "fmt").string(), "--export-format", "ply"}) == 0);
  CHECK(fs::exists(dir / "fmt" / "vessel_golden_solid.ply"));
  CHECK_FALSE(fs::exists(dir / "fmt" / "vessel_golden_solid.stl"));
  // Standard output: the file's bytes, and nothing else, on stdout.
  const CliResult piped = run_fabmesh({"run", design, "-o", "-", "--export-format", "stl"});
  REQUIRE(piped.code == 0);
  CHECK(piped.out == bytes_of(dir / "one.stl"));
  CHECK_THAT(piped.err, Catch::Contains("vessel_golden_solid: vessel"));
  // A single file takes one design and one format.
  CHECK(run_cli({"run", design, example("vessel_golden_shell.yaml"), "-o", (dir / "two.stl").string()}) == 2);
  const CliResult two_formats = run_fabmesh({"run", design, "-o", "-"});
  CHECK(two_formats.code == 2);
  CHECK_THAT(two_formats.err, Catch::Contains("--export-format"));
}

TEST_CASE("command line: --version, -q and -v", "[pipeline][cli]") {
  const CliResult version = run_fabmesh({"--version"});
  CHECK(version.code == 0);
  CHECK_THAT(version.out, Catch::StartsWith("fabmesh 0.") || Catch::Contains("fabmesh 0."));
  const fs::path dir = fresh_dir("cli_quiet");
  const CliResult quiet = run_fabmesh({"run", example("vessel_golden_solid.yaml"), "-o", dir.string(), "-q"});
  CHECK(quiet.code == 0);
  CHECK(quiet.out.empty());
  const CliResult verbose =
      run_fabmesh({"-v", "run", example("vessel_golden_solid.yaml"), "-o", dir.string()});
  CHECK(verbose.code == 0);
  CHECK_THAT(verbose.out, Catch::Contains("encode_stl") && Catch::Contains("validate"));
  // Errors still reach standard error with -q.
  const CliResult bad = run_fabmesh({"run", "-q", "/nonexistent.yaml"});
  CHECK(bad.code == 2);
  CHECK_THAT(bad.err, Catch::Contains("/nonexistent.yaml"));
}

TEST_CASE("run: two designs with one name, or two outputs of one file, stop before anything runs",
          "[pipeline][run][errors]") {
  const fs::path dir = fresh_dir("same_name");
  std::string text = read_file(example("vessel_golden_solid.yaml"));
  write_file_atomically((dir / "a.yaml").string(), text);
  write_file_atomically((dir / "b.yaml").string(), text);
  std::string out;
  CHECK(run_cli({"run", (dir / "a.yaml").string(), (dir / "b.yaml").string(), "-o", (dir / "out").string()},
                &out) == 2);
  CHECK_THAT(out, Catch::Contains("both named 'vessel_golden_solid'"));
  CHECK_FALSE(fs::exists(dir / "out"));
  CHECK(run_cli({"run", (dir / "a.yaml").string(), "-o", (dir / "out").string(), "-D", "outputs=[stl, stl]"},
                &out) == 2);
  CHECK_THAT(out, Catch::Contains("stl is listed twice"));
}
