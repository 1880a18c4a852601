#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "geometry/core/errors.h"
#include "geometry/core/soup.h"
#include "geometry/mesh/weld.h"
#include "geometry/validation/validate.h"
#include "io/design/read_design.h"
#include "io/file.h"
#include "io/mesh/draco.h"
#include "io/mesh/stl.h"
#include "pipeline/cli/commands.h"
#include "pipeline/job.h"
#include "tests/pipeline/cli_harness.h"

using namespace fabmesh;
using namespace fabmesh::testing;
namespace fs = std::filesystem;

TEST_CASE("run: a shell vessel is written as STL and Draco in millimetres that both read back valid",
          "[pipeline][run]") {
  const fs::path dir = fresh_dir("run_shell");
  const Design design = read_design(example("vessel_golden_shell.yaml"));
  REQUIRE(design.common.units == "cm");
  const Result r = run_job(design, into(dir));
  REQUIRE(written_paths(r).size() == 4);  // the mesh (STL, Draco) and the profile template (DXF, SVG)
  CHECK(verdict(r).valid());
  CHECK(r.max_deviation <= design.common.tolerance);
  CHECK(r.export_units == "mm");
  for (const OutputFile& f : r.files) {
    CHECK(f.units == (f.format == "dxf" || f.format == "svg" ? "cm" : "mm"));
    // The vessel's embedding margin covers float32 rounding; Draco's decoding is validated.
    if (f.format == "stl" || f.format == "drc") {
      CHECK(f.valid_as_written == std::optional<bool>(true));
    } else {
      CHECK_FALSE(f.valid_as_written.has_value());
    }
  }
  CHECK(verdict(r).embedding_margin > 0.0);

  // The design is in cm, the files in mm: 10 times the lengths, 1000 times the volume.
  const TriangleSoup stl = weld(parse_stl(read_file((dir / "vessel_golden_shell.stl").string()), "stl")).soup;
  const ValidationReport from_stl = validate(stl);
  CHECK(from_stl.valid());
  CHECK(from_stl.triangles == verdict(r).triangles);
  CHECK(from_stl.volume == Approx(1000.0 * verdict(r).volume).epsilon(1e-6));
  // The job proved the connectivity by construction; the file's analysis finds the same.
  CHECK_FALSE(verdict(r).topology_proof.empty());
  CHECK(from_stl.topology_proof.empty());
  CHECK(from_stl.components == verdict(r).components);
  CHECK(from_stl.euler_characteristics == verdict(r).euler_characteristics);
  CHECK(from_stl.genus == verdict(r).genus);

  const TriangleSoup drc = parse_draco(read_file((dir / "vessel_golden_shell.drc").string()), "drc");
  const ValidationReport from_drc = validate(drc);
  CHECK(from_drc.valid());
  CHECK(from_drc.triangles == verdict(r).triangles);
  // Every decoded vertex lies within the tolerance the build left unused of a built vertex.
  const TriangleSoup built = stl;
  double worst = 0.0;
  for (const Vec3& p : drc.vertices) {
    double best = INFINITY;
    for (const Vec3& q : built.vertices) best = std::min(best, (p - q).norm());
    worst = std::max(worst, best);
  }
  CHECK(worst <= 10.0 * (design.common.tolerance - r.max_deviation));  // mm
}

TEST_CASE("draco: the default 11 bits collapse a fine mesh but fabmesh's choice keeps it valid",
          "[pipeline][draco]") {
  // Rings next to a pole are short: their vertices are far closer than 11-bit steps of the bounding box.
  const fs::path dir = fresh_dir("run_fine");
  const Design design = parse_design(
      "name: ball\nkind: vessel\ntolerance: 0.005\n"
      "profile: {family: tbezier, segments: [{circle_arc: {center: [0, 0], radius: 20, from_deg: -90, "
      "to_deg: 90}}]}\n"
      "body: {mode: solid}\n",
      "ball.yaml");
  const Result r = run_job(design, into(dir));
  REQUIRE(verdict(r).valid());
  const TriangleSoup soup = weld(parse_stl(read_file((dir / "ball.stl").string()), "stl")).soup;
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (const Vec3& v : soup.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  DracoOptions eleven;
  eleven.tolerance = draco_max_error(lo, hi, 11);
  REQUIRE(draco_quantization(lo, hi, eleven.tolerance).bits == 11);
  const ValidationReport coarse = validate(parse_draco(encode_draco(soup, eleven), "11 bits"));
  CHECK_FALSE(coarse.valid());
  CHECK(coarse.degenerate_faces > 0);
  CHECK(validate(parse_draco(read_file((dir / "ball.drc").string()), "drc")).valid());
}

TEST_CASE("run --json: one array, an object per design with the documented fields", "[pipeline][run]") {
  const fs::path dir = fresh_dir("run_json");
  std::string out;
  REQUIRE(run_cli_json({"run", example("vessel_golden_solid.yaml"), "-o", dir.string(), "--json"}, &out) ==
          0);
  const auto all = nlohmann::json::parse(out);
  REQUIRE(all.is_array());
  REQUIRE(all.size() == 1);
  const auto& j = all[0];
  for (const char* key : {"units", "export_units", "bounding_box", "files", "skipped_outputs"})
    CHECK(j.contains(key));
  CHECK(j["bounding_box"]["units"] == "cm");
  for (const char* key : {"name", "kind", "outputs", "vertices", "triangles", "volume", "area", "watertight",
                          "manifold", "self_intersecting", "max_deviation", "timings_ms"}) {
    CHECK(j.contains(key));
  }
  CHECK(j["watertight"] == true);
  CHECK(j["manifold"] == true);
  CHECK(j["self_intersecting"] == false);
  CHECK(j["topology"] == "proven by construction");
  CHECK(j["embedding_margin"].get<double>() > 0.0);
  CHECK(j["topology_proof"].get<std::string>().find("revolution grid") != std::string::npos);
  CHECK(j["outputs"].size() == 4);  // STL, Draco, and the profile template as DXF and SVG
  CHECK(j["max_deviation"].get<double>() <= 0.005);
}

TEST_CASE("run: bad input exits 2 and writes no file", "[pipeline][run][errors]") {
  const fs::path dir = fresh_dir("run_bad");
  const fs::path design = dir / "thick.yaml";
  std::string text = read_file(example("vessel_lambdas_shell.yaml"));
  text.replace(text.find("wall: 0.2"), 9, "wall: 0.3");
  std::ofstream(design) << text;
  const fs::path out_dir = dir / "out";
  std::string out;
  CHECK(run_cli({"run", design.string(), "-o", out_dir.string()}, &out) == 2);
  CHECK_THAT(out, Catch::Contains("thick.yaml") && Catch::Contains("too thick"));
  CHECK((!fs::exists(out_dir) || fs::is_empty(out_dir)));

  std::ofstream(dir / "budget.yaml")
      << "kind: vessel\ntolerance: 0.000001\nmax_triangles: 1000\n"
         "profile: {family: quasi_bspline, points: [[1.5, 6], [1, 5], [2, 4]]}\n"
         "body: {mode: solid}\n";
  CHECK(run_cli({"run", (dir / "budget.yaml").string(), "-o", out_dir.string()}, &out) == 2);
  CHECK_THAT(out, Catch::Contains("budget"));
  std::ofstream(dir / "few.yaml")
      << "kind: vessel\nprofile: {family: quasi_bspline, points: [[1.5, 6], [1, 5]]}\n"
         "body: {mode: solid}\n";
  CHECK(run_cli({"run", (dir / "few.yaml").string(), "-o", out_dir.string()}, &out) == 2);
  CHECK_THAT(out, Catch::Contains("few.yaml:2:") && Catch::Contains("at least 3 points"));
  CHECK((!fs::exists(out_dir) || fs::is_empty(out_dir)));
}

TEST_CASE("run: a batch reports every design and exits with the worst code", "[pipeline][run]") {
  const fs::path dir = fresh_dir("run_batch");
  // A curve with a lambda out of range: bad input, while the vessel beside it is built.
  std::ofstream(dir / "curve.yaml")
      << "kind: curve\ncurve: {family: quasi_bspline, points: [[0,0],[1,1],[2,0],[3,1]], lambdas: [0, 7]}\n";
  const CliResult r = run_fabmesh({"run", example("vessel_golden_solid.yaml"), (dir / "curve.yaml").string(),
                                   "-o", dir.string(), "--json"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("curve.yaml") && Catch::Contains("lambda"));
  const auto j = nlohmann::json::parse(r.out);
  REQUIRE(j.size() == 2);
  CHECK(j[0]["name"] == "vessel_golden_solid");
  CHECK(j[1]["exit_code"] == 2);
}

TEST_CASE("fabmesh with no arguments runs the bundled example into ./out", "[pipeline][run]") {
  const fs::path dir = fresh_dir("run_default");
  const std::string cmd = "cd '" + dir.string() + "' && '" + FABMESH_BINARY + "' > log.txt 2>&1";
  REQUIRE(std::system(cmd.c_str()) == 0);
  CHECK(fs::exists(dir / "out" / "vessel_golden_shell.stl"));
  CHECK(fs::exists(dir / "out" / "vessel_golden_shell.drc"));
  const std::string log = read_file((dir / "log.txt").string());
  CHECK_THAT(log, Catch::Contains("Files are in"));
  // Found beside the program (build/share/fabmesh/examples), not in the sources.
  CHECK_THAT(log, Catch::Contains("share/fabmesh/examples/vessel_golden_shell.yaml"));
}

TEST_CASE("fabmesh with no arguments and no examples beside it says where it looked (exit 2)",
          "[pipeline][run]") {
  const fs::path dir = fresh_dir("run_default_alone");
  fs::create_directories(dir / "bin");
  fs::copy_file(FABMESH_BINARY, dir / "bin" / "fabmesh");
  const std::string cmd = "cd '" + dir.string() + "' && bin/fabmesh > log.txt 2>&1";
  const int status = std::system(cmd.c_str());
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 2);
  const std::string log = read_file((dir / "log.txt").string());
  CHECK_THAT(log, Catch::Contains("bundled example is not at " +
                                  (dir / "share/fabmesh/examples/vessel_golden_shell.yaml").string()));
  CHECK_FALSE(fs::exists(dir / "out"));
}

TEST_CASE("run: a job written straight to its files has the bytes of the same job prepared in memory",
          "[pipeline][run][determinism]") {
  const fs::path dir = fresh_dir("run_streamed");
  Design design = read_design(example("vessel_golden_shell.yaml"));
  design.common.outputs = {{"stl", "outputs", 0, 0}, {"obj", "outputs", 0, 0}, {"dxf", "outputs", 0, 0}};
  const EncodedJob prepared = prepare_job(design, into(dir / "prepared")).second;
  const Result written = run_job(design, into(dir / "written"));
  REQUIRE(prepared.files.size() == 3);
  REQUIRE(written_paths(written).size() == 3);
  for (std::size_t k = 0; k < prepared.files.size(); ++k) {
    const fs::path name = fs::path(prepared.files[k].file.path).filename();
    CHECK(fs::path(written_paths(written)[k]).filename() == name);
    CHECK(read_file(written_paths(written)[k]) == prepared.files[k].encoded.bytes);
  }
  // Only the outputs: no temporary is left beside them.
  std::size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir / "written")) entries += e.is_regular_file() ? 1 : 0;
  CHECK(entries == 3);
  // In the design's own unit the exported mesh is the built one itself: same bytes too.
  JobOptions same_unit = into(dir / "cm");
  same_unit.export_units = "cm";
  design.common.outputs = {{"stl", "outputs", 0, 0}};
  const EncodedJob prepared_cm = prepare_job(design, same_unit).second;
  const Result written_cm = run_job(design, same_unit);
  CHECK(read_file(written_paths(written_cm).at(0)) == prepared_cm.files.at(0).encoded.bytes);
  CHECK(prepared_cm.files.at(0).encoded.bytes != prepared.files.at(0).encoded.bytes);  // cm, not mm
}
