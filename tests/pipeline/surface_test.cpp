#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "geometry/core/errors.h"
#include "geometry/mesh/weld.h"
#include "geometry/validation/validate.h"
#include "io/design/read_design.h"
#include "io/file.h"
#include "io/mesh/draco.h"
#include "io/mesh/stl.h"
#include "pipeline/build_design.h"
#include "pipeline/cli/commands.h"
#include "pipeline/job.h"
#include "tests/pipeline/cli_harness.h"
#include "tests/pipeline/limited_run.h"

using namespace fabmesh;
using fabmesh::testing::verdict;
namespace fs = std::filesystem;

namespace {

using testing::example;
using testing::fresh_dir;
using testing::run_cli;
using testing::run_cli_json;

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The shell example with `replace` substituted for `find` (one occurrence).
std::string edited_shell(const std::string& find, const std::string& replace) {
  std::string text = read_text(example("surface_basin_shell.yaml"));
  const auto at = text.find(find);
  REQUIRE(at != std::string::npos);
  return text.replace(at, find.size(), replace);
}

}  // namespace

TEST_CASE("surface run: the thickened basin is a valid closed solid written as STL, Draco and STEP",
          "[pipeline][surface]") {
  const fs::path dir = fresh_dir("surface_shell");
  const Design design = read_design(example("surface_basin_shell.yaml"));
  const Result r = run_job(design, testing::into(dir));
  REQUIRE(written_paths(r).size() == 3);
  CHECK(fs::exists(dir / "surface_basin_shell.step"));  // its solid: tests/pipeline/step_output_test.cpp
  CHECK(verdict(r).valid());
  CHECK(verdict(r).self_intersection == IntersectionCheck::Tested);  // the 3D test, not a proof
  REQUIRE(verdict(r).genus);
  CHECK(*verdict(r).genus == 0);
  CHECK(verdict(r).volume > 0.0);
  CHECK(r.max_deviation <= design.common.tolerance);
  REQUIRE(r.facts.contains("joints"));
  const auto& joints = std::get<std::vector<Facts>>(*r.facts.find("joints"));
  CHECK(joints.size() == 4);
  for (const Facts& j : joints) CHECK(j.number("normal_angle") < 1e-6);

  const TriangleSoup stl = weld(parse_stl(read_file((dir / "surface_basin_shell.stl").string()), "stl")).soup;
  const ValidationReport from_stl = validate(stl);
  CHECK(from_stl.valid());
  CHECK(from_stl.volume == Approx(verdict(r).volume).epsilon(1e-5));
  CHECK(validate(parse_draco(read_file((dir / "surface_basin_shell.drc").string()), "drc")).valid());
}

TEST_CASE("surface run: an open surface is refused for fabrication and written only for viewing",
          "[pipeline][surface]") {
  const fs::path dir = fresh_dir("surface_open");
  std::string out;
  // Without purpose: view it is not a success: exit 1, nothing written, and the message says what to do.
  CHECK(run_cli({"run", example("surface_basin_open.yaml"), "-o", dir.string(), "-D", "purpose=fabrication",
                 "-D", "outputs=[stl]"},
                &out) == 1);
  CHECK_THAT(out, Catch::Contains("not fit for fabrication") && Catch::Contains("purpose: view"));
  CHECK(fs::is_empty(dir));
  // The example says it is for viewing: exit 0, glTF written, the report says it is not valid for
  // fabrication.
  REQUIRE(run_cli_json({"run", example("surface_basin_open.yaml"), "-o", dir.string(), "--json"}, &out) == 0);
  const nlohmann::json j = nlohmann::json::parse(out).at(0);
  CHECK(j["valid"] == false);
  CHECK(j["purpose"] == "viewing");
  CHECK(j["fabrication"].get<std::string>().find("not valid: open surface") != std::string::npos);
  CHECK(j["watertight"] == false);
  CHECK(fs::exists(dir / "surface_basin_open.glb"));
  CHECK(fs::exists(dir / "surface_basin_open.draco.glb"));
  std::string human;
  CHECK(run_cli({"run", example("surface_basin_open.yaml"), "-o", dir.string()}, &human) == 0);
  CHECK(human.find("for viewing only, not valid for fabrication") != std::string::npos);
}

TEST_CASE("surface run: a shell too thick for its curvature fails validation and writes nothing",
          "[pipeline][surface]") {
  // A half cylinder of radius 10 whose normals point to its axis: a 25 mm shell crosses the axis.
  const fs::path dir = fresh_dir("surface_too_thick");
  const std::string half_cylinder = R"(kind: surface
tolerance: 0.05
patches:
  - name: trough
    points:
      - [[10, 0, 0], [10, 10, 0], [10, 20, 0], [10, 30, 0]]
      - [[10, 0, 13.333333], [10, 10, 13.333333], [10, 20, 13.333333], [10, 30, 13.333333]]
      - [[-10, 0, 13.333333], [-10, 10, 13.333333], [-10, 20, 13.333333], [-10, 30, 13.333333]]
      - [[-10, 0, 0], [-10, 10, 0], [-10, 20, 0], [-10, 30, 0]]
)";
  write_file_atomically((dir / "thin.yaml").string(), half_cylinder + "thickness: 1\n");
  write_file_atomically((dir / "too_thick.yaml").string(), half_cylinder + "thickness: 25\n");
  std::string out;
  CHECK(run_cli({"run", (dir / "thin.yaml").string(), "-o", (dir / "out").string()}, &out) == 0);
  CHECK(fs::exists(dir / "out" / "thin.stl"));
  CHECK(run_cli({"run", (dir / "too_thick.yaml").string(), "-o", (dir / "out").string()}, &out) == 1);
  CHECK(out.find("self-intersect") != std::string::npos);
  // It says the thickness the curvature allows (radius of curvature about 7.5 here, at most 10).
  CHECK_THAT(out, Catch::Contains("the largest thickness that could pass is below") &&
                      Catch::Contains("cannot fold anywhere"));
  CHECK_FALSE(fs::exists(dir / "out" / "too_thick.stl"));
  CHECK_FALSE(fs::exists(dir / "out" / "too_thick.drc"));
}

TEST_CASE("surface designs: bad values are reported with file, line and column", "[pipeline][surface]") {
  const fs::path dir = fresh_dir("surface_bad");
  struct Case {
    std::string find, replace, expect;
  };
  const Case cases[] = {
      {"thickness: 6\n", "thickness: -2\n", "thickness = -2 must be > 0"},
      {"to: back_left,", "to: nowhere,", "no earlier patch is named 'nowhere'"},
      {"side: u_max", "side: top", "side"},
      {"gamma: 1}", "gamma: 0}", "gamma = 0 must be > 0"},
      {"lambda: 0, mu: 0}", "lambda: -4, mu: 0}", "lambda = -4 is outside"},
      {"alpha: 1, lambda", "alpha: 11, lambda", "alpha = 11"},
      {"      - [[-150, 142.5, 0]", "      - [[-150, 142.5]", "point"},
      {"  - name: back_left", "  - nam: back_left", "nam"},
  };
  for (const Case& c : cases) {
    const fs::path design = dir / "bad.yaml";
    write_file_atomically(design.string(), edited_shell(c.find, c.replace));
    std::string out;
    INFO(c.replace);
    CHECK(run_cli({"run", design.string(), "-o", (dir / "out").string()}, &out) == 2);
    CHECK(out.find(c.expect) != std::string::npos);
    CHECK(out.find("bad.yaml:") != std::string::npos);
    CHECK_FALSE(fs::exists(dir / "out" / "bad.stl"));
  }
  // A wrong number of free columns, at the patch.
  write_file_atomically(
      (dir / "rows.yaml").string(),
      edited_shell("      - [[150, 0, 0], [150, 75, 0], [150, 142.5, 0], [146.25, 146.25, 0]]\n", ""));
  std::string out;
  CHECK(run_cli({"run", (dir / "rows.yaml").string(), "-o", (dir / "out").string()}, &out) == 2);
  CHECK(out.find("rows.yaml:") != std::string::npos);
  CHECK(out.find("leaves 2 free columns") != std::string::npos);
}

TEST_CASE("surface sample: a surface has no curves to sample and says so", "[pipeline][surface]") {
  std::string out;
  CHECK(run_cli({"sample", example("surface_basin_shell.yaml")}, &out) == 0);
  CHECK(out.find("no curves") != std::string::npos);
}

TEST_CASE("surface designs: thicken chooses the shell's side, and the report says where it went",
          "[pipeline][surface]") {
  const fs::path dir = fresh_dir("surface_thicken");
  struct Case {
    std::string side, thickness;
    double z_min;  // the basin is 120 deep; an outward shell hangs below it
  };
  // Inward, the rim's rounded corners allow little (their radius of curvature is about a millimetre).
  for (const Case& c :
       {Case{"outward", "6", -126.0}, Case{"inward", "0.5", -120.0}, Case{"centered", "1", -120.5}}) {
    INFO(c.side);
    write_file_atomically(
        (dir / "basin.yaml").string(),
        edited_shell("thickness: 6\noutputs: [stl, drc, step]\n",
                     "thickness: " + c.thickness + "\nthicken: " + c.side + "\noutputs: [stl]\n"));
    std::string out;
    REQUIRE(run_cli_json({"run", (dir / "basin.yaml").string(), "-o", (dir / "out").string(), "--json"},
                         &out) == 0);
    const nlohmann::json j = nlohmann::json::parse(out).at(0);
    CHECK(j["valid"] == true);
    CHECK(j["build"]["thicken"] == c.side);
    CHECK(j["bounding_box"]["min"][2].get<double>() == Approx(c.z_min).margin(0.1));
    CHECK(j["max_deviation"].get<double>() <= 0.5);
  }
  write_file_atomically((dir / "bad.yaml").string(), edited_shell("thickness: 6\n", "thicken: sideways\n"));
  std::string out;
  CHECK(run_cli({"run", (dir / "bad.yaml").string(), "-o", (dir / "out").string()}, &out) == 2);
  CHECK_THAT(out, Catch::Contains("bad.yaml:") && Catch::Contains("thicken"));
  write_file_atomically((dir / "lonely.yaml").string(), edited_shell("thickness: 6\n", "thicken: outward\n"));
  CHECK(run_cli({"run", (dir / "lonely.yaml").string(), "-o", (dir / "out").string()}, &out) == 2);
  CHECK_THAT(out, Catch::Contains("give a thickness too"));
}

TEST_CASE("surface run: a patch whose control points lie on one line is refused at once",
          "[pipeline][surface][cli]") {
  // It used to refine toward a zero normal for 25 s, then hit the triangle budget.
  const fs::path dir = fresh_dir("surface_on_a_line");
  const fs::path design = dir / "line.yaml";
  std::ofstream(design) << R"(name: line
kind: surface
units: mm
tolerance: 0.5
thickness: 2
patches:
  - name: flat
    u: {alpha: 1, lambda: 0, mu: 0}
    v: {alpha: 1, lambda: 0, mu: 0}
    points:
      - [[0,0,0],[1,1,1],[2,2,2],[3,3,3]]
      - [[4,4,4],[5,5,5],[6,6,6],[7,7,7]]
      - [[8,8,8],[9,9,9],[10,10,10],[11,11,11]]
      - [[12,12,12],[13,13,13],[14,14,14],[15,15,15]]
)";
  const testing::LimitedRun run =
      testing::run_limited({"run", design.string(), "-o", (dir / "out/").string()}, 20, std::size_t{1} << 30);
  INFO(run.describe());
  CHECK(run.code == 2);
  CHECK(run.err.find("line.yaml:7:5: patches[0] ('flat'): its 16 control points lie on one line") !=
        std::string::npos);
  CHECK_FALSE(fs::exists(dir / "out"));
}

TEST_CASE("surface draft: the studio's quick mesh is the same closed shell, coarser and unproven",
          "[pipeline][surface][studio]") {
  const fs::path dir = fresh_dir("surface_draft");
  const Design design = read_design(example("surface_basin_shell.yaml"));
  const auto& surface = std::get<SurfaceDesign>(design.body);
  const Result proven = run_job(design, testing::into(dir));
  REQUIRE(verdict(proven).valid());
  const Result draft = surface_draft(surface, 2.0 * design.common.tolerance);
  REQUIRE(product(draft) != nullptr);
  CHECK_FALSE(product(draft)->validated);  // not validated: no verdict
  CHECK(std::holds_alternative<SurfaceProducts>(draft.products));
  CHECK(product(draft)->mesh.triangles.size() * 5 < verdict(proven).triangles);
  // Closed and outward like the proven shell, and holding nearly its volume.
  const ValidationReport checked = validate(product(draft)->mesh);
  CHECK(checked.boundary_edges == 0);
  CHECK(checked.oriented_outward);
  CHECK(checked.valid());  // this one happens to be valid too, though nothing proved it
  CHECK(checked.volume == Approx(verdict(proven).volume).epsilon(0.02));
  // An open surface's draft is its sheet, for viewing.
  SurfaceDesign open = surface;
  open.thickness = 0.0;
  const Result sheet = surface_draft(open, 2.0 * design.common.tolerance);
  CHECK(sheet.purpose == MeshPurpose::Viewing);
  REQUIRE(product(sheet) != nullptr);
  CHECK(validate(product(sheet)->mesh).boundary_edges > 0);
}
