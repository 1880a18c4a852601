// Issue 24: the real executable against hostile output folders, batch
// folders, manifest names and input files, under the time and memory bounds
// the test enforces (tests/pipeline/limited_run.h). Links inside an output
// folder are never followed, a batch reads and writes only regular files of
// its own, the Slurm script runs nothing but its own lines, a byte order mark
// loses no point, and a tiny mesh file cannot make `check` work for weeks or
// take gigabytes.

#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "io/design/points_csv.h"
#include "io/file.h"
#include "tests/pipeline/batch/batch_fixture.h"
#include "tests/pipeline/cli_harness.h"
#include "tests/pipeline/hostile_files.h"
#include "tests/pipeline/limited_run.h"

using namespace fabmesh;
using namespace fabmesh::testing;
namespace fs = std::filesystem;

namespace {

// Refusals must be immediate: generous bounds for a loaded machine, far
// below what waiting on a FIFO or expanding 20^10 components would take.
constexpr double kQuickSeconds = 20.0;
constexpr double kBuildSeconds = 120.0;
constexpr std::size_t kSmallMemory = 256 * kMiB;
constexpr std::size_t kBuildMemory = 2048 * kMiB;

const char* const kWallGrid = "design: cup.yaml\nname: cup_{body.wall}\ngrid:\n  body.wall: [0.3, 5]\n";

// A folder `victim` beside the batch holding the user's files.
fs::path victim_folder(const fs::path& dir) {
  const fs::path victim = dir / "victim";
  fs::create_directories(victim);
  write_text(victim / "important.txt", "the user's own words\n");
  write_text(victim / "notes.md", "# notes\n");
  return victim;
}

void check_victim_untouched(const fs::path& victim) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(victim)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  CHECK(names == std::vector<std::string>{"important.txt", "notes.md"});
  CHECK(file_text(victim / "important.txt") == "the user's own words\n");
  CHECK(file_text(victim / "notes.md") == "# notes\n");
}

bool is_link(const fs::path& path) {
  std::error_code ec;
  return fs::is_symlink(fs::symlink_status(path, ec));
}

// The report `run --json` prints for `design`, after checking the run ended with exit 0.
nlohmann::json run_report(const fs::path& design, const fs::path& out) {
  const LimitedRun r =
      run_limited({"run", "--json", "-q", design.string(), "-o", out.string()}, kBuildSeconds, kBuildMemory);
  INFO(r.describe());
  REQUIRE(r.code == 0);
  return nlohmann::json::parse(r.out).at(0);  // an array, one entry per design
}

}  // namespace

TEST_CASE("batch: a variant folder that is a link is refused and its target left alone",
          "[pipeline][batch][hostile]") {
  const fs::path dir = batch_folder("hostile_variant_link", kWallGrid);
  const fs::path victim = victim_folder(dir);
  const fs::path out = dir / "out";
  fs::create_directories(out);
  fs::create_directory_symlink(victim, out / "cup_5");
  fs::create_directory_symlink(victim, out / "cup_0.3");
  const LimitedRun r = run_limited({"batch", (dir / "m.yaml").string(), "-o", out.string()}, kBuildSeconds,
                                   kBuildMemory, dir.string());
  INFO(r.describe());
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains((out / "cup_0.3").string()) && Catch::Contains("link"));
  check_victim_untouched(victim);
  CHECK(is_link(out / "cup_5"));
  CHECK(is_link(out / "cup_0.3"));

  // Once the links are gone the same folder runs.
  fs::remove(out / "cup_5");
  fs::remove(out / "cup_0.3");
  const LimitedRun again = run_limited({"batch", (dir / "m.yaml").string(), "-o", out.string()},
                                       kBuildSeconds, kBuildMemory, dir.string());
  INFO(again.describe());
  CHECK(fs::is_regular_file(out / "cup_0.3" / "cup_0.3.stl"));
}

TEST_CASE("batch: a .batch folder that is a link is refused, a file link in a variant folder is replaced",
          "[pipeline][batch][hostile]") {
  const fs::path dir = batch_folder("hostile_batch_link", kWallGrid);
  const fs::path victim = victim_folder(dir);
  const fs::path out = dir / "out";
  fs::create_directories(out);
  fs::create_directory_symlink(victim, out / ".batch");
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"batch", (dir / "m.yaml").string(), "-o", out.string()},
        std::vector<std::string>{"batch", "--merge", out.string()},
        std::vector<std::string>{"batch", (dir / "m.yaml").string(), "-o", out.string(), "--slurm"}}) {
    INFO(args[1]);
    const LimitedRun r = run_limited(args, kBuildSeconds, kBuildMemory, dir.string());
    INFO(r.describe());
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Catch::Contains((out / ".batch").string()) && Catch::Contains("link"));
    check_victim_untouched(victim);
  }
  CHECK_FALSE(fs::exists(out / "cup_0.3"));
  fs::remove(out / ".batch");

  // A variant's file that is a link is replaced by the file itself; a foreign
  // link in its folder is left as it is; neither target changes.
  fs::create_directories(out / "cup_0.3");
  fs::create_symlink(victim / "important.txt", out / "cup_0.3" / "cup_0.3.stl");
  fs::create_symlink(victim / "notes.md", out / "cup_0.3" / "old.stl");
  const LimitedRun r = run_limited({"batch", (dir / "m.yaml").string(), "-o", out.string()}, kBuildSeconds,
                                   kBuildMemory, dir.string());
  INFO(r.describe());
  CHECK(fs::is_regular_file(fs::symlink_status(out / "cup_0.3" / "cup_0.3.stl")));
  check_victim_untouched(victim);
}

TEST_CASE("run: a file of -o DIR that is a link is replaced, its target left alone",
          "[pipeline][run][hostile]") {
  const fs::path dir = batch_folder("hostile_run_link", kWallGrid);
  const fs::path victim = victim_folder(dir);
  const fs::path out = dir / "out";
  fs::create_directories(out);
  fs::create_symlink(victim / "important.txt", out / "cup.stl");
  const LimitedRun r = run_limited({"run", (dir / "cup.yaml").string(), "-o", out.string(), "-q"},
                                   kBuildSeconds, kBuildMemory);
  INFO(r.describe());
  CHECK(r.code == 0);
  CHECK(fs::is_regular_file(fs::symlink_status(out / "cup.stl")));
  check_victim_untouched(victim);
}

TEST_CASE("batch: a ledger that is a link or a FIFO is refused at once, its target untouched",
          "[pipeline][batch][hostile]") {
  const fs::path dir = batch_folder("hostile_ledger", kWallGrid);
  const fs::path out = dir / "out";
  fs::create_directories(out / ".batch");
  write_text(dir / "outside.txt", "not a ledger\n");
  const fs::path ledger = out / ".batch" / "ledger-0-of-1.jsonl";
  fs::create_symlink(dir / "outside.txt", ledger);
  const LimitedRun linked = run_limited({"batch", (dir / "m.yaml").string(), "-o", out.string()},
                                        kQuickSeconds, kBuildMemory, dir.string());
  INFO(linked.describe());
  CHECK(linked.code == 2);
  CHECK_THAT(linked.err, Catch::Contains(ledger.string()) && Catch::Contains("not a regular file"));
  CHECK(file_text(dir / "outside.txt") == "not a ledger\n");
  CHECK(is_link(ledger));
  fs::remove(ledger);

  // A FIFO no writer opens: reading it would wait forever.
  const fs::path fifo = out / ".batch" / "ledger-1-of-2.jsonl";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"batch", (dir / "m.yaml").string(), "-o", out.string()},
        std::vector<std::string>{"batch", (dir / "m.yaml").string(), "-o", out.string(), "--shard", "1/2"},
        std::vector<std::string>{"batch", "--merge", out.string()}}) {
    INFO(args.back());
    const LimitedRun r = run_limited(args, kQuickSeconds, kBuildMemory, dir.string());
    INFO(r.describe());
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Catch::Contains(fifo.string()) && Catch::Contains("FIFO"));
  }
}

TEST_CASE("batch --slurm: a manifest path with a newline and shell syntax runs no line but ours",
          "[pipeline][batch][hostile]") {
  const fs::path dir = batch_folder("hostile_slurm",
                                    "design: cup.yaml\nname: cup_{body.wall}\ngrid:\n"
                                    "  body.wall: [0.3]\n");
  const std::string name = "m\ntouch PWNED\n$(touch PWNED2)`touch PWNED3`'\".yaml";
  fs::copy_file(dir / "m.yaml", dir / name);
  const fs::path out = dir / "out";
  const LimitedRun r =
      run_limited({"batch", name, "-o", "out", "--slurm"}, kQuickSeconds, kSmallMemory, dir.string());
  INFO(r.describe());
  REQUIRE(r.code == 0);
  const std::string script = file_text(out / "slurm.sbatch");
  INFO(script);
  // Every line is a comment, an #SBATCH line before any command, or one of the two commands.
  std::istringstream lines(script);
  std::string line;
  int commands = 0;
  while (std::getline(lines, line)) {
    if (line.rfind("#SBATCH ", 0) == 0) {
      CHECK(commands == 0);
    } else if (line.rfind("#", 0) == 0) {
      continue;
    } else if (line == "set -euo pipefail" || line.rfind("exec '", 0) == 0) {
      ++commands;
    } else {
      FAIL_CHECK("a line that is not the script's own: " << line);
    }
  }
  CHECK(commands == 2);
  // bash reads it, and running it builds the manifest, nothing else.
  CHECK(std::system(fmt::format("bash -n '{}'", (out / "slurm.sbatch").string()).c_str()) == 0);
  const std::string run =
      fmt::format("cd '{}' && SLURM_ARRAY_TASK_ID=0 bash out/slurm.sbatch >/dev/null 2>&1", dir.string());
  CHECK(std::system(run.c_str()) == 0);
  CHECK(fs::is_regular_file(out / "cup_0.3" / "cup_0.3.stl"));
  for (const char* planted : {"PWNED", "PWNED2", "PWNED3"}) CHECK_FALSE(fs::exists(dir / planted));
  for (const char* planted : {"PWNED", "PWNED2", "PWNED3"}) CHECK_FALSE(fs::exists(out / planted));
}

TEST_CASE("points csv: a byte order mark loses no point, and a skipped header row is reported",
          "[pipeline][design][hostile]") {
  const fs::path dir = fresh_dir("hostile_bom");
  // A vase turned from a digitised profile (radius, height): losing its first
  // point builds it from z = 10, silently.
  const std::string top =
      "kind: vessel\nunits: mm\ntolerance: 0.05\nprofile:\n  family: tbezier\n  segments:\n"
      "    - polyline: {file: FILE}\nbody:\n  mode: solid\n";
  const std::string points = "30,0\n40,10\n35,40\n20,60\n";
  const auto design = [&](const std::string& name, const std::string& csv) {
    write_text(dir / (name + ".csv"), csv);
    std::string text = top;
    text.replace(text.find("FILE"), 4, name + ".csv");
    write_text(dir / (name + ".yaml"), text);
    return dir / (name + ".yaml");
  };
  const nlohmann::json plain = run_report(design("plain", points), dir / "out");
  const nlohmann::json bom = run_report(design("bom", "\xEF\xBB\xBF" + points), dir / "out");
  CHECK(plain["bounding_box"]["min"][2] == 0.0);
  CHECK(bom["bounding_box"] == plain["bounding_box"]);
  CHECK(bom["volume"] == plain["volume"]);
  CHECK_FALSE(bom.contains("notes"));
  // A header (with or without a byte order mark) is skipped, and the report says so.
  for (const std::string& head : {std::string("x,y\n"), std::string("\xEF\xBB\xBFx,y\n")}) {
    const nlohmann::json headed = run_report(design("headed", head + points), dir / "out");
    CHECK(headed["volume"] == plain["volume"]);
    REQUIRE(headed.contains("notes"));
    CHECK_THAT(headed["notes"].dump(), Catch::Contains("headed.csv:1") && Catch::Contains("header"));
  }
  // The CSV fuzzer starts from such a file too: all four points read.
  int header_line = -1;
  CHECK(read_points_csv(std::string(FABMESH_SOURCE_DIR) + "/tests/data/fuzz-seeds/csv/byte_order_mark.csv",
                        &header_line)
            .size() == 4);
  CHECK(header_line == 0);
}

TEST_CASE("check: a 3MF of 20^10 component instances of an empty mesh is refused at once",
          "[pipeline][check][hostile]") {
  const fs::path dir = fresh_dir("hostile_3mf");
  write_text(dir / "nested.3mf", threemf_package(nested_components_model()));
  CHECK(fs::file_size(dir / "nested.3mf") < 8192);
  const LimitedRun r = run_limited({"check", (dir / "nested.3mf").string()}, kQuickSeconds, kSmallMemory);
  INFO(r.describe());
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("nested.3mf") && Catch::Contains("component"));
  // The fuzzers start from the same file.
  CHECK(read_file(std::string(FABMESH_SOURCE_DIR) +
                  "/tests/data/fuzz-seeds/3mf/regression-components-20-pow-10.model") ==
        nested_components_model());
}

TEST_CASE("check: a glTF accessor of 60 million positions without data is refused in little memory",
          "[pipeline][check][hostile]") {
  const fs::path dir = fresh_dir("hostile_gltf");
  write_text(dir / "empty.glb", glb_of(unbacked_positions_gltf()));
  write_text(dir / "empty.gltf", unbacked_positions_gltf());
  CHECK(fs::file_size(dir / "empty.glb") < 512);
  for (const char* name : {"empty.glb", "empty.gltf"}) {
    INFO(name);
    const LimitedRun r = run_limited({"check", (dir / name).string()}, kQuickSeconds, kSmallMemory);
    INFO(r.describe());
    CHECK(r.code == 2);
    CHECK_THAT(r.err,
               Catch::Contains(name) && Catch::Contains("accessors[0]") && Catch::Contains("bufferView"));
  }
  CHECK(read_file(std::string(FABMESH_SOURCE_DIR) +
                  "/tests/data/fuzz-seeds/gltf/regression-unbacked-60m-positions.gltf") ==
        unbacked_positions_gltf());
}
