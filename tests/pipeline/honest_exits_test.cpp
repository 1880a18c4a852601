// Issue 24, round three: the real executable tells the truth about what it
// did. A run that writes nothing it was asked for fails with the reasons, two
// designs never write one file, an environment failure (disk full, I/O,
// permission) is not bad input, and messages name the user's own values at
// their place. Each under the time and memory bounds the test enforces
// (tests/pipeline/limited_run.h).

#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <tuple>

#include "io/file.h"
#include "tests/pipeline/batch/batch_fixture.h"
#include "tests/pipeline/cli_harness.h"
#include "tests/pipeline/limited_run.h"

using namespace fabmesh;
using namespace fabmesh::testing;
namespace fs = std::filesystem;

namespace {

constexpr double kSeconds = 60.0;
constexpr std::size_t kMemory = 2048 * kMiB;

// Runs the program with files limited to 8 KiB (16 blocks of 512 bytes, or
// 16 KiB where the shell counts kilobytes) and SIGXFSZ ignored, so that
// writing past it fails with EFBIG, as a full disk fails with ENOSPC.
// Messages and the batch's own small files fit; a cup's STL does not.
const char* const kSmallFiles = "ulimit -f 16; trap '' XFSZ;";

// A 10 x 10 x 1 mm slab 100 m from the origin held within 1 um: float32
// (STL, glTF) moves its vertices by 10 um, so those outputs are skipped.
const char* const kFarSlab = R"(name: far
kind: countertop
units: mm
tolerance: 0.001
thickness: 1
outline:
  family: tbezier
  closed: true
  segments:
    - polyline: [[100000, 0], [100010, 0], [100010, 10], [100000, 10], [100000, 0]]
outputs: [stl]
)";

// A small slab at the origin named NAME writing OUTPUTS.
std::string slab(const std::string& name, const std::string& outputs) {
  return fmt::format(R"(name: {}
kind: countertop
units: mm
tolerance: 0.05
thickness: 10
outline:
  family: tbezier
  closed: true
  segments:
    - polyline: [[0, 0], [100, 0], [100, 60], [0, 60], [0, 0]]
outputs: {}
)",
                     name, outputs);
}

}  // namespace

TEST_CASE("run: -o FILE.stl, -o - and a list of outputs that are all skipped fail with the reasons",
          "[pipeline][run][honest]") {
  const fs::path dir = fresh_dir("honest_all_skipped");
  write_text(dir / "far.yaml", kFarSlab);
  const std::string design = (dir / "far.yaml").string();
  const std::vector<std::vector<std::string>> runs{
      {"run", design, "-o", (dir / "out/x.stl").string()},
      {"run", design, "-o", "-", "--export-format", "stl"},
      {"run", design, "-D", "outputs=[stl, glb, glb_draco]", "-o", (dir / "out").string()},
      {"run", design, "--json", "-o", (dir / "out").string()}};
  for (const std::vector<std::string>& args : runs) {
    INFO(fmt::format("{}", fmt::join(args, " ")));
    const LimitedRun r = run_limited(args, kSeconds, kMemory);
    INFO(r.describe());
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Catch::Contains("every output was skipped, so nothing is written") &&
                          Catch::Contains("stl: writing moves vertices by up to"));
    if (args[3] == "-") CHECK(r.out.empty());  // not a byte on the pipe
    CHECK_FALSE(fs::exists(dir / "out"));
  }
}

TEST_CASE("run: a mould or cnc block that no output uses is a warning naming the outputs that would",
          "[pipeline][run][honest]") {
  const fs::path dir = fresh_dir("honest_unused_block");
  write_text(dir / "cut.yaml", slab("cut", "[stl]") + "cnc: {tool_diameter: 6}\n");
  write_text(dir / "cup.yaml", R"(name: cup
kind: vessel
units: cm
tolerance: 0.05
profile:
  family: quasi_bspline
  points: [[1.5, 6], [1, 5], [2, 4], [3, 3], [1.5, 2]]
body: {mode: solid}
outputs: [stl]
mould: {parts: 2, wall: 3, spare: 2.5, key_radius: 0.6, key_clearance: 0.02}
)");
  for (const auto& [name, place, users] :
       {std::tuple<std::string, std::string, std::string>{"cut", ":12:6: cnc", "add nc or toolpath_svg"},
        {"cup", ":10:8: mould",
         "add mould_stl, mould_3mf, mould_step, master_stl, master_3mf, master_step, case_stl, case_3mf or "
         "case_step"}}) {
    const std::string design = (dir / (name + ".yaml")).string();
    const std::string key = design + place;
    const LimitedRun text = run_limited({"run", design, "-o", (dir / "out").string()}, kSeconds, kMemory);
    INFO(text.describe());
    CHECK(text.code == 0);
    // Warnings go to standard error, in text as in JSON, never onto the summary's lines.
    CHECK_THAT(text.err, Catch::Contains("fabmesh: warning: " + key) && Catch::Contains(users));
    CHECK_THAT(text.out, !Catch::Contains("warning"));
    const LimitedRun json =
        run_limited({"run", design, "--json", "-o", (dir / "out").string()}, kSeconds, kMemory);
    INFO(json.describe());
    REQUIRE(json.code == 0);
    const nlohmann::json report = nlohmann::json::parse(json.out).at(0);
    REQUIRE(report.contains("warnings"));
    REQUIRE(report["warnings"].size() == 1);
    CHECK_THAT(report["warnings"][0].get<std::string>(), Catch::StartsWith(key) && Catch::Contains(users));
    CHECK_THAT(json.err, Catch::Contains("fabmesh: warning: " + key));
    // Asked for on the command line: no warning.
    const LimitedRun asked = run_limited(
        {"run", design, "--export-format", "stl", "--json", "-o", (dir / "out").string()}, kSeconds, kMemory);
    REQUIRE(asked.code == 0);
    CHECK_FALSE(nlohmann::json::parse(asked.out).at(0).contains("warnings"));
  }
}

TEST_CASE("run: outputs of two designs that resolve to one file are refused before anything runs",
          "[pipeline][run][honest]") {
  const fs::path dir = fresh_dir("honest_collide");
  write_text(dir / "a.yaml", slab("x", "[stl, glb_draco]"));
  write_text(dir / "b.yaml", slab("x.draco", "[glb]"));
  write_text(dir / "c.yaml", slab("y.mould", "[3mf]"));
  write_text(dir / "d.yaml", slab("y", "[toolpath_svg]") + "cnc: {tool_diameter: 6}\n");
  write_text(dir / "e.yaml", slab("y.toolpath", "[svg]"));
  const std::string out = (dir / "out").string();
  const LimitedRun r = run_limited({"run", (dir / "a.yaml").string(), (dir / "b.yaml").string(), "-o", out},
                                   kSeconds, kMemory);
  INFO(r.describe());
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("a.yaml (glb_draco output) and ") &&
                        Catch::Contains("b.yaml (glb output) would both write " + out + "/x.draco.glb") &&
                        Catch::Contains("nothing was run"));
  CHECK_FALSE(fs::exists(dir / "out"));
  const LimitedRun svg = run_limited(
      {"run", (dir / "c.yaml").string(), (dir / "d.yaml").string(), (dir / "e.yaml").string(), "-o", out},
      kSeconds, kMemory);
  INFO(svg.describe());
  CHECK(svg.code == 2);
  CHECK_THAT(svg.err, Catch::Contains("would both write " + out + "/y.toolpath.svg"));
  CHECK_FALSE(fs::exists(dir / "out"));
  // Apart, each writes its own files.
  CHECK(
      run_limited({"run", (dir / "a.yaml").string(), (dir / "c.yaml").string(), "-o", out}, kSeconds, kMemory)
          .code == 0);
}

TEST_CASE("run: a file size limit met while writing is an environment failure, exit 5, nothing left",
          "[pipeline][run][honest]") {
  const fs::path dir = fresh_dir("honest_environment_run");
  write_text(dir / "cup.yaml", kBatchCup);
  const fs::path out = dir / "out";
  const LimitedRun r = run_limited({"run", (dir / "cup.yaml").string(), "-o", out.string()}, kSeconds,
                                   kMemory, "", kSmallFiles);
  INFO(r.describe());
  CHECK(r.code == 5);
  CHECK_THAT(r.err, Catch::Contains("fabmesh: environment error: " + (out / "cup.stl").string()) &&
                        Catch::Contains("File too large") && Catch::Contains("not of the input"));
  CHECK(fs::is_empty(out));  // no file, no temporary
}

TEST_CASE("batch: variants the machine failed are recorded as environment and run again without --force",
          "[pipeline][batch][honest]") {
  const fs::path dir = batch_folder("honest_environment",
                                    "design: cup.yaml\nname: cup_{body.wall}\n"
                                    "grid:\n  body.wall: [0.3, 0.35]\n");
  const std::string manifest = (dir / "m.yaml").string(), out = (dir / "out").string();
  const LimitedRun limited =
      run_limited({"batch", manifest, "-o", out, "--json", "-q"}, kSeconds, kMemory, "", kSmallFiles);
  INFO(limited.describe());
  CHECK(limited.code == 5);
  const nlohmann::json first = only_item(limited.out);
  CHECK(first["environment"] == 2);
  CHECK(first["bad_input"] == 0);
  CHECK(first["exit_code"] == 5);
  CHECK_THAT(limited.err,
             Catch::Contains("fabmesh: environment: cup_0.3: ") && Catch::Contains("File too large"));
  const std::vector<nlohmann::json> rows = summary_rows(out);
  REQUIRE(rows.size() == 2);
  for (const nlohmann::json& row : rows) {
    CHECK(row["status"] == "environment");
    CHECK(row["exit_code"] == 5);
  }
  CHECK_FALSE(fs::exists(dir / "out" / "cup_0.3"));
  // Once the machine is fixed, a plain rerun builds them.
  int code = -1;
  const nlohmann::json second = batch_json({manifest, "-o", out}, &code);
  CHECK(code == 0);
  CHECK(second["ran"] == 2);
  CHECK(second["ok"] == 2);
  CHECK(fs::exists(dir / "out" / "cup_0.3" / "cup_0.3.stl"));
}

TEST_CASE("batch: a reused variant whose file changed but kept its size is built again, and said so",
          "[pipeline][batch][honest]") {
  const fs::path dir = batch_folder("honest_digest",
                                    "design: cup.yaml\nname: cup_{body.wall}\n"
                                    "grid:\n  body.wall: [0.3, 0.35]\n");
  const std::string manifest = (dir / "m.yaml").string(), out = (dir / "out").string();
  int code = -1;
  batch_json({manifest, "-o", out}, &code);
  REQUIRE(code == 0);
  const fs::path stl = dir / "out" / "cup_0.35" / "cup_0.35.stl";
  const std::string good = file_text(stl);
  std::string bad = good;
  bad[100] = static_cast<char>(bad[100] ^ 0x55);  // a flipped byte in the first triangle
  write_text(stl, bad);
  const LimitedRun rerun = run_limited({"batch", manifest, "-o", out, "--json", "-q"}, kSeconds, kMemory);
  INFO(rerun.describe());
  CHECK(rerun.code == 0);
  const nlohmann::json again = only_item(rerun.out);
  const std::string& err = rerun.err;
  CHECK(again["ran"] == 1);
  CHECK(again["reused"] == 1);
  REQUIRE(again["rebuilt"].size() == 1);
  CHECK(again["rebuilt"][0]["name"] == "cup_0.35");
  CHECK_THAT(err,
             Catch::Contains("fabmesh: note: cup_0.35: its file cup_0.35/cup_0.35.stl no longer matches the "
                             "digest recorded: built again"));
  CHECK(file_text(stl) == good);
}

TEST_CASE("batch: a ledger line longer than any row is reported as corruption, in bounded memory",
          "[pipeline][batch][honest]") {
  const fs::path dir = batch_folder("honest_long_ledger",
                                    "design: cup.yaml\nname: cup_{body.wall}\n"
                                    "grid:\n  body.wall: [0.3]\n");
  const std::string manifest = (dir / "m.yaml").string(), out = (dir / "out").string();
  int code = -1;
  batch_json({manifest, "-o", out}, &code);
  REQUIRE(code == 0);
  const fs::path ledger = dir / "out" / ".batch" / "ledger-0-of-1.jsonl";
  const std::string before = file_text(ledger);
  std::ofstream(ledger, std::ios::app | std::ios::binary) << std::string(6u << 20, 'x');  // no line end
  for (const std::vector<std::string>& args : {std::vector<std::string>{"batch", manifest, "-o", out},
                                               std::vector<std::string>{"batch", "--merge", out}}) {
    INFO(args[1]);
    const LimitedRun r = run_limited(args, kSeconds, 256 * kMiB);
    INFO(r.describe());
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Catch::Contains(ledger.string() + ": the ledger is corrupt: the line at byte " +
                                      std::to_string(before.size())) &&
                          Catch::Contains("longer than any ledger line can be"));
  }
  CHECK(fs::file_size(ledger) == before.size() + (6u << 20));  // reported, not cut
}

TEST_CASE("run -D kind=... and a table column kind say a variant cannot change the kind",
          "[pipeline][honest][messages]") {
  const fs::path dir = batch_folder("honest_kind", "design: cup.yaml\ntable: t.csv\n");
  write_text(dir / "t.csv", "body.wall,kind\n0.3,countertop\n");
  const LimitedRun run =
      run_limited({"run", (dir / "cup.yaml").string(), "-D", "kind=countertop", "-o", (dir / "out").string()},
                  kSeconds, kMemory);
  INFO(run.describe());
  CHECK(run.code == 2);
  CHECK_THAT(run.err, Catch::Contains("-D kind=countertop: kind: an override cannot change the design's kind "
                                      "(vessel)"));
  CHECK_THAT(run.err, !Catch::Contains("unknown key"));
  const LimitedRun batch =
      run_limited({"batch", (dir / "m.yaml").string(), "-o", (dir / "out").string()}, kSeconds, kMemory);
  INFO(batch.describe());
  CHECK(batch.code == 2);
  CHECK_THAT(batch.err, Catch::Contains((dir / "t.csv").string() +
                                        ":1:11: column 'kind': a variant cannot change the design's kind"));
  CHECK_FALSE(fs::exists(dir / "out"));
}

TEST_CASE("batch: a NUL byte in a table cell is refused at its place, the message whole",
          "[pipeline][honest][messages]") {
  const fs::path dir = batch_folder("honest_nul", "design: cup.yaml\ntable: t.csv\nname: v{index}\n");
  write_text(dir / "t.csv", std::string("body.wall\n0.3\0zz\n", 17));
  const LimitedRun r =
      run_limited({"batch", (dir / "m.yaml").string(), "-o", (dir / "out").string()}, kSeconds, kMemory);
  INFO(r.describe());
  CHECK(r.code == 2);
  CHECK_THAT(r.err,
             Catch::Contains((dir / "t.csv").string() + ":2:4: a NUL byte in a cell: a table is text"));
  CHECK_FALSE(fs::exists(dir / "out"));
}

TEST_CASE("batch --merge: a message of several lines prints them as lines, indented",
          "[pipeline][honest][messages]") {
  const fs::path dir = batch_folder("honest_lines",
                                    "design: cup.yaml\nname: cup_{body.wall}\n"
                                    "grid:\n  body.wall: [0.3, 0.35]\n");
  const std::string manifest = (dir / "m.yaml").string(), out = (dir / "out").string();
  int code = -1;
  batch_json({manifest, "-o", out, "--shard", "0/2"}, &code);
  REQUIRE(code == 0);
  write_text(dir / "m.yaml", "design: cup.yaml\nname: cup_{body.wall}\ngrid:\n  body.wall: [0.3, 0.4]\n");
  batch_json({manifest, "-o", out, "--shard", "1/2"}, &code);
  REQUIRE(code == 0);
  const LimitedRun r = run_limited({"batch", "--merge", out}, kSeconds, kMemory);
  INFO(r.describe());
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("the shards here ran different plans") &&
                        Catch::Contains("\n    plan ") && Catch::Contains("\n  rerun every shard"));
  CHECK_THAT(r.err, !Catch::Contains("\\x0a"));
}

TEST_CASE("check --weld-tolerance -1 names the value, not the largest double",
          "[pipeline][honest][messages]") {
  const LimitedRun r = run_limited({"check", "--weld-tolerance", "-1", example("vessel_golden_shell.yaml")},
                                   kSeconds, kMemory);
  INFO(r.describe());
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("--weld-tolerance") && Catch::Contains("-1 is below 0"));
  CHECK_THAT(r.err, !Catch::Contains("17976931348623157"));
  CHECK(r.err.size() < 300);
}

TEST_CASE("check: a glTF whose nodes form a cycle and no scene is bad input, exit 2",
          "[pipeline][honest][messages]") {
  const fs::path dir = fresh_dir("honest_gltf_cycle");
  // A triangle's mesh on node 0, whose child's child is node 0 again: no node is a root.
  write_text(dir / "cycle.gltf", R"({"asset": {"version": "2.0"},
 "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
 "bufferViews": [{"buffer": 0, "byteLength": 36}],
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
 "nodes": [{"children": [1], "mesh": 0}, {"children": [0]}]})");
  const LimitedRun r = run_limited({"check", (dir / "cycle.gltf").string()}, kSeconds, 256 * kMiB);
  INFO(r.describe());
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("cycle.gltf") && Catch::Contains("nodes[0] lies on a cycle of children"));
}

TEST_CASE("optimize and CNC errors name the file, line and column of their key",
          "[pipeline][honest][messages]") {
  const fs::path dir = fresh_dir("honest_located");
  write_text(dir / "h.yaml", R"(kind: curve
curve:
  family: hbezier
  segments:
    - points: [[0, 0], [1, 2], [3, 3], [4, 1]]
)");
  const LimitedRun opt = run_limited({"optimize", (dir / "h.yaml").string()}, kSeconds, kMemory);
  INFO(opt.describe());
  CHECK(opt.code == 2);
  CHECK(names_place(opt.err, (dir / "h.yaml").string(), "curve"));
  // A 12 mm tool cannot cut the 5 mm corners of a hole.
  write_text(dir / "sink.yaml",
             slab("sink", "[nc]") +
                 "holes:\n  - rounded_rect: {center: [50, 30], size: [40, 20], radius: 5}\n"
                 "cnc: {tool_diameter: 12}\n");
  const LimitedRun cnc =
      run_limited({"run", (dir / "sink.yaml").string(), "-o", (dir / "out").string()}, kSeconds, kMemory);
  INFO(cnc.describe());
  CHECK(cnc.code == 2);
  CHECK(names_place(cnc.err, (dir / "sink.yaml").string(), "holes[0] (rounded_rect)"));
  CHECK_THAT(cnc.err, Catch::Contains("below the tool radius 6"));
  // The ways out: a smaller tool, a larger radius, or a sharp corner with relief.
  CHECK_THAT(cnc.err, Catch::Contains("tool of diameter at most 10") &&
                          Catch::Contains("radius of at least 6") && Catch::Contains("relief: dogbone"));
  CHECK_FALSE(fs::exists(dir / "out"));
}

TEST_CASE("a design nested 1000 lists deep says how deep, at its place", "[pipeline][honest][messages]") {
  const fs::path dir = fresh_dir("honest_deep");
  write_text(dir / "deep.yaml",
             "kind: curve\ncurve: " + std::string(1000, '[') + std::string(1000, ']') + "\n");
  write_text(dir / "m.yaml", "design: " + std::string(1000, '[') + std::string(1000, ']') + "\n");
  const LimitedRun design = run_limited({"sample", (dir / "deep.yaml").string()}, kSeconds, 256 * kMiB);
  INFO(design.describe());
  CHECK(design.code == 2);
  CHECK_THAT(design.err, Catch::Contains((dir / "deep.yaml").string() + ":2:71: lists and maps nested more "
                                                                        "than 64 deep"));
  const LimitedRun manifest = run_limited({"batch", (dir / "m.yaml").string()}, kSeconds, 256 * kMiB);
  INFO(manifest.describe());
  CHECK(manifest.code == 2);
  CHECK_THAT(manifest.err, Catch::Contains("invalid YAML: lists and maps nested more than") &&
                               !Catch::Contains("bad file"));
}

TEST_CASE("run -o with an ending fabmesh does not write is exit 2 listing the endings it writes",
          "[pipeline][honest][files]") {
  const fs::path dir = fresh_dir("honest_endings");
  write_text(dir / "s.yaml", slab("s", "[stl]"));
  const std::string design = (dir / "s.yaml").string();
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"run", design, "-o", (dir / "x.xyz").string()},
        std::vector<std::string>{"run", design, "-o", (dir / "mug.gltf").string()},
        std::vector<std::string>{"plot", design, "-o", (dir / "mug.png").string()}}) {
    INFO(args[0] << " -o " << args[3]);
    const LimitedRun r = run_limited(args, kSeconds, kMemory);
    INFO(r.describe());
    CHECK(r.code == 2);
    CHECK_FALSE(fs::exists(args[3]));
    if (args[0] == "run") {
      CHECK_THAT(r.err, Catch::Contains("fabmesh writes no '") && Catch::Contains(".stl, .drc, .3mf, .glb") &&
                            Catch::Contains(".draco.glb"));
    } else {
      CHECK_THAT(r.err, Catch::Contains("plot writes SVG"));
    }
  }
  // Endings in any case: MUG.STL is an STL.
  const LimitedRun upper = run_limited({"run", design, "-o", (dir / "MUG.STL").string()}, kSeconds, kMemory);
  INFO(upper.describe());
  CHECK(upper.code == 0);
  REQUIRE(fs::is_regular_file(dir / "MUG.STL"));
  CHECK(fs::file_size(dir / "MUG.STL") == 84 + 50 * 12u);  // binary STL of the slab's 12 triangles
}

TEST_CASE("batch: a typo in an override path fails once, before any variant runs",
          "[pipeline][batch][honest]") {
  const fs::path dir = batch_folder("honest_typo",
                                    "design: cup.yaml\nname: cup_{body.wal}\n"
                                    "grid:\n  body.wal: [0.3, 0.35, 0.4]\n");
  const LimitedRun r =
      run_limited({"batch", (dir / "m.yaml").string(), "-o", (dir / "out").string()}, kSeconds, kMemory);
  INFO(r.describe());
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("body.wal=0.3 (" + (dir / "m.yaml").string() + ":4:14)") &&
                        Catch::Contains("unknown key 'wal'"));
  CHECK_THAT(r.err, !Catch::Contains("0.35"));  // once, not per variant
  CHECK_FALSE(fs::exists(dir / "out" / "cup_0.3"));
  CHECK_FALSE(fs::exists(dir / "out" / "summary.csv"));
}

TEST_CASE("check: a text file named .stl that is neither STL says so", "[pipeline][honest][messages]") {
  const fs::path dir = fresh_dir("honest_text_stl");
  write_text(dir / "notes.stl", "These are my notes about the mug.\nNot a mesh at all.\n");
  const LimitedRun r = run_limited({"check", (dir / "notes.stl").string()}, kSeconds, 256 * kMiB);
  INFO(r.describe());
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("a text file that is no STL") &&
                        Catch::Contains("starts with 'These are my notes about the mug.'"));
  CHECK_THAT(r.err, !Catch::Contains("binary STL header says"));
}

namespace {

// A small solid cup in cm with a mould of `mould` (its key sizes left to their defaults).
std::string cup_with_mould(const std::string& mould) {
  return R"(name: cup
kind: vessel
units: cm
tolerance: 0.05
profile:
  family: quasi_bspline
  points: [[1.5, 6], [1, 5], [2, 4], [3, 3], [1.5, 2]]
body: {mode: solid}
outputs: [mould_3mf]
mould: )" +
         mould + "\n";
}

}  // namespace

TEST_CASE("mould: three parts with the default keys build, and messages print numbers in shortest form",
          "[pipeline][honest][messages]") {
  const fs::path dir = fresh_dir("honest_three_parts");
  write_text(dir / "three.yaml", cup_with_mould("{parts: 3, wall: 3, spare: 2.5}"));
  const LimitedRun built =
      run_limited({"run", (dir / "three.yaml").string(), "-o", (dir / "out").string()}, kSeconds, kMemory);
  INFO(built.describe());
  CHECK(built.code == 0);
  CHECK(fs::is_regular_file(dir / "out" / "cup.mould.3mf"));
  // Too tight when given: the message names 6 mm as 0.6 cm, not 0.6000000000000001.
  write_text(dir / "tight.yaml", cup_with_mould("{parts: 3, wall: 3, spare: 2.5, key_clearance: 0.05}"));
  const LimitedRun tight =
      run_limited({"run", (dir / "tight.yaml").string(), "-o", (dir / "out2").string()}, kSeconds, kMemory);
  INFO(tight.describe());
  CHECK(tight.code == 2);
  CHECK_THAT(tight.err, Catch::Contains("a bump of radius 0.6 binds in a socket of radius 0.65") &&
                            Catch::Contains("key_clearance 0.05 must be >="));
  CHECK_THAT(tight.err, !Catch::Contains("00000000"));
}

TEST_CASE("surface: a shell over its budget is told the design's max_triangles",
          "[pipeline][honest][messages]") {
  const fs::path dir = fresh_dir("honest_budget");
  write_text(dir / "lid.yaml", R"(name: lid
kind: surface
units: mm
tolerance: 0.2
max_triangles: 1000
patches:
  - name: lid
    points:
      - [[0, 0, 0], [33, 0, 0], [67, 0, 0], [100, 0, 0]]
      - [[0, 33, 0], [33, 33, 12], [67, 33, 12], [100, 33, 0]]
      - [[0, 67, 0], [33, 67, 12], [67, 67, 12], [100, 67, 0]]
      - [[0, 100, 0], [33, 100, 0], [67, 100, 0], [100, 100, 0]]
thickness: 3
)");
  const LimitedRun r =
      run_limited({"run", (dir / "lid.yaml").string(), "-o", (dir / "out").string()}, kSeconds, kMemory);
  INFO(r.describe());
  CHECK(r.code == 2);
  CHECK(names_place(r.err, (dir / "lid.yaml").string(), "tolerance"));
  CHECK_THAT(r.err, Catch::Contains("tolerance: 0.2 mm: a sheet of the shell needs") &&
                        Catch::Contains("of the budget of 1000 (max_triangles"));
}

TEST_CASE("a NUL byte in a points CSV cell is shown escaped, the message whole",
          "[pipeline][honest][messages]") {
  const fs::path dir = fresh_dir("honest_points_nul");
  write_text(dir / "p.csv", std::string("0,0\n1\0x,2\n3,3\n", 14));
  write_text(dir / "c.yaml",
             "kind: curve\ncurve:\n  family: tbezier\n  segments:\n    - polyline: {file: p.csv}\n");
  const LimitedRun r = run_limited({"sample", (dir / "c.yaml").string()}, kSeconds, 256 * kMiB);
  INFO(r.describe());
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("p.csv:2:1: '1\\x00x' is not a number"));
}

TEST_CASE("vessel: a shell whose profile crosses itself says so, as the solid does",
          "[pipeline][honest][messages]") {
  const fs::path dir = fresh_dir("honest_crossing_shell");
  // The third stretch crosses the first near (2.5, 1.5): no wall, however thin, can follow it.
  write_text(dir / "x.yaml", R"(name: x
kind: vessel
tolerance: 0.01
profile:
  family: tbezier
  segments:
    - polyline: [[2, 0], [3, 3], [1, 3], [3, 1], [2, 5]]
body: {mode: shell, wall: 0.1}
)");
  for (const char* body : {"body={mode: shell, wall: 0.1}", "body={mode: solid}"}) {
    INFO(body);
    const LimitedRun r = run_limited(
        {"run", (dir / "x.yaml").string(), "-D", body, "-o", (dir / "out").string()}, kSeconds, kMemory);
    INFO(r.describe());
    CHECK(r.code == 2);
    CHECK(names_place(r.err, (dir / "x.yaml").string(), "profile"));
    CHECK_THAT(r.err, Catch::Contains("the profile crosses itself") && !Catch::Contains("too thick"));
  }
  CHECK_FALSE(fs::exists(dir / "out"));
}

TEST_CASE("run and sample both refuse a closed curve that crosses itself", "[pipeline][honest][messages]") {
  const fs::path dir = fresh_dir("honest_figure8");
  write_text(dir / "f.yaml", R"(name: f
kind: curve
tolerance: 0.01
curve:
  family: tbezier
  closed: true
  segments:
    - polyline: [[0, 0], [2, 2], [2, 0], [0, 2], [0, 0]]
)");
  const std::string design = (dir / "f.yaml").string();
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"sample", design},
        std::vector<std::string>{"run", design, "-o", (dir / "out").string()}}) {
    INFO(args[0]);
    const LimitedRun r = run_limited(args, kSeconds, kMemory);
    INFO(r.describe());
    CHECK(r.code == 2);
    CHECK(names_place(r.err, design, "curve"));
    CHECK_THAT(r.err, Catch::Contains("the closed curve crosses itself near (1, 1) (segments 1 and 3)"));
  }
  CHECK_FALSE(fs::exists(dir / "out"));
}
