// Every mesh file `run` writes is valid as the file stores it, and the Draco
// search is bounded: the real executable under enforced time and memory
// limits (tests/pipeline/limited_run.h), its files judged by `check`.

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/pipeline/cli_harness.h"
#include "tests/pipeline/limited_run.h"

using namespace fabmesh;
using testing::fresh_dir;
using testing::LimitedRun;
using testing::run_limited;
namespace fs = std::filesystem;

namespace {

constexpr std::size_t kMemory = std::size_t{1} << 30;  // 1 GiB

fs::path write_design(const fs::path& dir, const std::string& name, const std::string& yaml) {
  const fs::path path = dir / (name + ".yaml");
  std::ofstream(path) << yaml;
  return path;
}

// A vessel whose first control points lie 1 um apart: float32 rounding at
// radius 10 mm (steps of 0.95 um) puts rings of vertices on one another.
const char* kMicronVessel = R"(name: micron
kind: vessel
units: mm
tolerance: 0.01
profile:
  family: quasi_bspline
  points: [[10,0],[10.000001,0],[10.000002,0],[12,20],[11,30]]
body:
  mode: solid
outputs: [stl, ply, glb, 3mf, obj]
)";

// Each mesh file written, judged by `check`: valid.
void require_written_files_valid(const nlohmann::json& report) {
  for (const auto& file : report["files"]) {
    const std::string format = file["format"];
    if (!file.contains("valid_as_written")) continue;  // a drawing
    INFO(file.dump());
    CHECK(file["valid_as_written"] == true);
    const LimitedRun check = run_limited({"check", file["path"]}, 60, kMemory);
    CHECK(check.code == 0);
  }
}

// Runs a 30 mm slab whose outline is the polyline `points`, at tolerance
// 1e-5 mm, asking for OBJ and Draco, under 256 MiB: its report (exit 0).
nlohmann::json run_slab_with_draco(const std::string& folder, const std::string& points) {
  const fs::path dir = fresh_dir(folder);
  const fs::path design = write_design(dir, "slab", R"(name: slab
kind: countertop
units: mm
tolerance: 0.00001
thickness: 30
outline:
  family: tbezier
  closed: true
  segments:
    - polyline: )" + points + R"(
outputs: [obj, drc]
)");
  const LimitedRun run = run_limited({"run", design.string(), "-o", (dir / "out/").string(), "--json"}, 20,
                                     std::size_t{256} << 20);
  INFO(run.describe());
  REQUIRE(run.code == 0);
  return nlohmann::json::parse(run.out).at(0);
}

}  // namespace

TEST_CASE("run: float32 files that rounding breaks are skipped with the reason, never written",
          "[pipeline][outputs][cli]") {
  const fs::path dir = fresh_dir("stored_micron");
  const fs::path design = write_design(dir, "micron", kMicronVessel);
  const LimitedRun run =
      run_limited({"run", design.string(), "-o", (dir / "out/").string(), "--json"}, 60, kMemory);
  INFO(run.describe());
  REQUIRE(run.code == 0);  // the OBJ (exact decimals) is written
  const auto report = nlohmann::json::parse(run.out).at(0);
  std::vector<std::string> skipped;
  for (const auto& s : report["skipped_outputs"]) {
    skipped.push_back(s["format"]);
    CHECK(s["reason"].get<std::string>().find("no longer valid") != std::string::npos);
    CHECK(s["reason"].get<std::string>().find("degenerate faces") != std::string::npos);
  }
  CHECK(skipped == std::vector<std::string>{"stl", "ply", "glb", "3mf"});
  for (const char* ext : {"stl", "ply", "glb", "3mf"})
    CHECK_FALSE(fs::exists(dir / "out" / ("micron." + std::string(ext))));
  REQUIRE(fs::exists(dir / "out" / "micron.obj"));
  require_written_files_valid(report);
}

TEST_CASE("run: a countertop outline that nearly touches itself is refused at its key",
          "[pipeline][outputs][cli]") {
  // The outline runs out to (500, 900) and back 1 um beside itself: float32
  // rounding would fold every file, so the design is refused, as a hole that
  // close to the outline is.
  const fs::path dir = fresh_dir("stored_touch");
  const fs::path design = write_design(dir, "touch", R"(name: touch
kind: countertop
units: mm
tolerance: 0.05
thickness: 30
outline:
  family: tbezier
  closed: true
  segments:
    - polyline: [[0,0],[1000,0],[1000,600],[500.000001,600],[500,900],[500,600],[0,600],[0,0]]
outputs: [stl, ply, glb, 3mf]
)");
  const LimitedRun run = run_limited({"run", design.string(), "-o", (dir / "out/").string()}, 60, kMemory);
  INFO(run.describe());
  CHECK(run.code == 2);
  CHECK(run.err.find("touch.yaml:7:3: outline") != std::string::npos);  // at the outline
  CHECK(run.err.find("comes within 1e-06 of itself") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "out"));
}

TEST_CASE("run: a job whose every output rounding breaks writes nothing and fails",
          "[pipeline][outputs][cli]") {
  const fs::path dir = fresh_dir("stored_all_skipped");
  std::string yaml = kMicronVessel;
  yaml.replace(yaml.find("outputs: [stl, ply, glb, 3mf, obj]"), 34, "outputs: [stl, ply]");
  const fs::path design = write_design(dir, "micron", yaml);
  const LimitedRun run = run_limited({"run", design.string(), "-o", (dir / "out/").string()}, 60, kMemory);
  INFO(run.describe());
  CHECK(run.code == 2);
  CHECK(run.err.find("every output was skipped, so nothing is written") != std::string::npos);
  CHECK(run.err.find("no longer valid") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "out"));
}

TEST_CASE("run: every mesh file of a countertop is proven valid as written", "[pipeline][outputs][cli]") {
  const fs::path dir = fresh_dir("stored_countertop");
  const LimitedRun run = run_limited({"run", testing::example("countertop_symmetric_ellipse.yaml"),
                                      "--export-format", "stl", "-o", (dir / "out/").string(), "--json"},
                                     60, kMemory);
  INFO(run.describe());
  REQUIRE(run.code == 0);
  require_written_files_valid(nlohmann::json::parse(run.out).at(0));
}

TEST_CASE("run: Draco that needs more quantization than memory allows is skipped at once",
          "[pipeline][outputs][draco][cli]") {
  // Coordinates up to 1000 mm held within 9e-6 mm: 27 bits, whose encoding
  // takes about 430 MB whatever the mesh (24 triangles here).
  const nlohmann::json report =
      run_slab_with_draco("stored_draco_bits", "[[0,0],[1000,0],[1000,600],[0,600],[0,0]]");
  REQUIRE(report["skipped_outputs"].size() == 1);
  CHECK(report["skipped_outputs"][0]["format"] == "drc");
  CHECK(report["skipped_outputs"][0]["reason"].get<std::string>().find("bits of Draco quantization") !=
        std::string::npos);
}

TEST_CASE("run: Draco that float32 alone cannot hold is skipped without a try",
          "[pipeline][outputs][draco][cli]") {
  const nlohmann::json report = run_slab_with_draco(
      "stored_draco_floor", "[[0,0],[1000.00001,0],[1000.00001,600.00001],[0,600.00001],[0,0]]");
  REQUIRE(report["skipped_outputs"].size() == 1);
  CHECK(report["skipped_outputs"][0]["reason"].get<std::string>().find("at any quantization") !=
        std::string::npos);
}

TEST_CASE("run: the outputs keep what float32 needs, so a fine tolerance far from the origin writes its STL",
          "[pipeline][outputs][budget][cli]") {
  // 2400 mm at tolerance 0.001 mm: float32 moves vertices by up to 2.5e-4 mm,
  // more than the tenth kept by default: the build gets the rest instead.
  const fs::path dir = fresh_dir("stored_budget");
  const LimitedRun run =
      run_limited({"run", testing::example("countertop_symmetric_ellipse.yaml"), "-D", "tolerance=0.001",
                   "--export-format", "stl", "-o", (dir / "out/").string(), "--json"},
                  120, kMemory);
  INFO(run.describe());
  REQUIRE(run.code == 0);
  const auto report = nlohmann::json::parse(run.out).at(0);
  CHECK(report["skipped_outputs"].empty());
  const double tolerance = report["tolerance"], deviation = report["max_deviation"];
  const double build = report["tolerance_split"]["build"], outputs = report["tolerance_split"]["outputs"];
  CHECK(outputs > 0.1 * tolerance);
  CHECK(build + outputs == Approx(tolerance));
  CHECK(deviation <= build);
  REQUIRE(report["files"].size() == 1);
  CHECK(deviation + report["files"][0]["max_added_error"].get<double>() <= tolerance);
  require_written_files_valid(report);
}

TEST_CASE("run: a platter whose profile leaves the axis tangent to it writes its Draco file, valid",
          "[pipeline][outputs][draco][cli]") {
  // Its first samples lay micrometres from the axis: rings of vertices 7e-6
  // mm apart around the pole, an embedding margin of 3.3e-6 mm, and every
  // Draco quantization within the tolerance broke the mesh (the output was
  // skipped). Rings now keep a tenth of the tolerance from the axis.
  const fs::path dir = fresh_dir("stored_platter");
  const fs::path design = write_design(dir, "platter", R"(name: platter
kind: vessel
units: mm
tolerance: 0.05
profile:
  family: quasi_bspline
  points: [[0, 0], [0, 35], [40, 45], [110, 20], [150, 15], [170, 22]]
body:
  mode: shell
  wall: 2.5
outputs: [stl, drc]
)");
  const LimitedRun run =
      run_limited({"run", design.string(), "-o", (dir / "out/").string(), "--json"}, 60, kMemory);
  INFO(run.describe());
  REQUIRE(run.code == 0);
  const auto report = nlohmann::json::parse(run.out).at(0);
  CHECK(report["skipped_outputs"].empty());
  REQUIRE(report["files"].size() == 2);
  CHECK(report["embedding_margin"].get<double>() > 1e-5);
  CHECK(report["max_deviation"].get<double>() <= report["tolerance_split"]["build"].get<double>());
  require_written_files_valid(report);
}
