// fabmesh batch end to end, in-process: failures, names, resume, --jobs, shards and merges.

#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

#include "tests/pipeline/batch/batch_fixture.h"
#include "tests/pipeline/limited_run.h"

using namespace fabmesh;
using namespace fabmesh::testing;
namespace fs = std::filesystem;

namespace {

const std::string kSweep = R"(design: cup.yaml
name: cup_w{body.wall}_l{profile.lambdas[0]}
grid:
  body.wall: {from: 0.2, to: 0.35, steps: 4}
  profile.lambdas[0]: [-1, 0.5]
)";

}  // namespace

TEST_CASE("batch: a bad variant does not stop the others and sets the batch's exit code",
          "[pipeline][batch]") {
  const fs::path dir = batch_folder("bad_variant", R"(design: cup.yaml
name: cup_{body.wall}
grid:
  body.wall: [0.2, -1, 0.3, "thick"]
)");
  int code = -1;
  std::string err;
  const nlohmann::json report =
      batch_json({(dir / "m.yaml").string(), "-o", (dir / "out").string()}, &code, &err);
  CHECK(code == 2);
  CHECK(report["ok"] == 2);
  CHECK(report["bad_input"] == 2);
  CHECK(report["exit_code"] == 2);
  const std::vector<nlohmann::json> rows = summary_rows(dir / "out");
  REQUIRE(rows.size() == 4);
  CHECK(rows[0]["status"] == "ok");
  CHECK(rows[1]["status"] == "bad input");
  CHECK(rows[1]["exit_code"] == 2);
  // The message names the value that is bad, as `-D body.wall=-1` would be named.
  CHECK_THAT(rows[1]["message"].get<std::string>(), Catch::Contains("body.wall=-1"));
  CHECK(rows[2]["status"] == "ok");
  CHECK(rows[3]["status"] == "bad input");
  CHECK(fs::is_regular_file(dir / "out" / "cup_0.2" / "cup_0.2.stl"));
  CHECK(fs::is_regular_file(dir / "out" / "cup_0.3" / "cup_0.3.stl"));
  CHECK_FALSE(fs::exists(dir / "out" / "cup_-1"));
  CHECK_THAT(err, Catch::Contains("cup_-1") && Catch::Contains("cup_thick"));
  // The ok rows carry the mesh facts of the summary's columns.
  CHECK(rows[0]["valid"] == true);
  CHECK(rows[0]["volume"].get<double>() > 0.0);
  CHECK(rows[0]["files"][0]["path"] == "cup_0.2/cup_0.2.stl");
  CHECK(rows[0]["files"][0]["bytes"] == fs::file_size(dir / "out" / "cup_0.2" / "cup_0.2.stl"));
}

TEST_CASE("batch: two variants with one name are exit 2 before anything runs", "[pipeline][batch]") {
  const fs::path dir = batch_folder("name_clash",
                                    "design: cup.yaml\nname: cup_{body.base}\ngrid:\n  body.wall: [0.2, "
                                    "0.3]\n  body.base: [0.4]\n");
  std::string text;
  const int code = run_cli({"batch", (dir / "m.yaml").string(), "-o", (dir / "out").string()}, &text);
  CHECK(code == 2);
  CHECK_THAT(text, Catch::Contains("m.yaml:2:") && Catch::Contains("both named 'cup_0.4'"));
  CHECK_FALSE(fs::exists(dir / "out"));
}

TEST_CASE(
    "batch: a rerun reuses the variants whose key and files stand, --force and changed values redo them",
    "[pipeline][batch]") {
  const fs::path dir = batch_folder("resume", kSweep);
  const std::string out = (dir / "out").string();
  const nlohmann::json first = batch_json({(dir / "m.yaml").string(), "-o", out});
  CHECK(first["ran"] == 8);
  const auto tree = output_tree(out);
  const auto summary = summary_without_timings(out);
  const auto stamp = fs::last_write_time(dir / "out" / "cup_w0.2_l-1" / "cup_w0.2_l-1.stl");

  const nlohmann::json again = batch_json({(dir / "m.yaml").string(), "-o", out});
  CHECK(again["ran"] == 0);
  CHECK(again["reused"] == 8);
  CHECK(fs::last_write_time(dir / "out" / "cup_w0.2_l-1" / "cup_w0.2_l-1.stl") == stamp);
  CHECK(output_tree(out) == tree);
  CHECK(summary_without_timings(out) == summary);

  // A lost output file: its variant runs again, the others do not.
  fs::remove(dir / "out" / "cup_w0.3_l0.5" / "cup_w0.3_l0.5.stl");
  const nlohmann::json repaired = batch_json({(dir / "m.yaml").string(), "-o", out});
  CHECK(repaired["ran"] == 1);
  CHECK(output_tree(out) == tree);

  // The same names with other content: a changed base value changes every key.
  std::ofstream(dir / "cup.yaml") << kBatchCup << "# a comment changes no key\n";
  CHECK(batch_json({(dir / "m.yaml").string(), "-o", out})["ran"] == 0);
  std::string cup = kBatchCup;
  cup.replace(cup.find("base: 0.4"), 9, "base: 0.5");
  std::ofstream(dir / "cup.yaml") << cup;
  const nlohmann::json changed = batch_json({(dir / "m.yaml").string(), "-o", out});
  CHECK(changed["ran"] == 8);
  CHECK(output_tree(out) != tree);
  std::ofstream(dir / "cup.yaml") << kBatchCup;
  CHECK(batch_json({(dir / "m.yaml").string(), "-o", out})["ran"] == 8);
  CHECK(output_tree(out) == tree);

  const nlohmann::json forced = batch_json({(dir / "m.yaml").string(), "-o", out, "--force"});
  CHECK(forced["ran"] == 8);
  CHECK(forced["reused"] == 0);
  CHECK(output_tree(out) == tree);
  CHECK(summary_without_timings(out) == summary);
}

TEST_CASE("batch: --jobs 1 and --jobs 2 write byte-identical outputs and summaries apart from timings",
          "[pipeline][batch]") {
  const fs::path dir = batch_folder("jobs", kSweep);
  int code = -1;
  batch_json({(dir / "m.yaml").string(), "-o", (dir / "one").string(), "--jobs", "1"}, &code);
  CHECK(code == 0);
  batch_json({(dir / "m.yaml").string(), "-o", (dir / "two").string(), "--jobs", "2"}, &code);
  CHECK(code == 0);
  const auto one = output_tree(dir / "one");
  CHECK(one.size() == 8);
  CHECK(one == output_tree(dir / "two"));
  CHECK(summary_without_timings(dir / "one") == summary_without_timings(dir / "two"));
}

TEST_CASE("batch: the shards' union is the whole batch, --merge reports missing shards and is idempotent",
          "[pipeline][batch]") {
  const fs::path dir = batch_folder("shards", kSweep);
  const std::string m = (dir / "m.yaml").string();
  batch_json({m, "-o", (dir / "whole").string()});
  const std::string out = (dir / "sharded").string();
  const nlohmann::json s0 = batch_json({m, "-o", out, "--shard", "0/3"});
  CHECK(s0["in_shard"] == 3);
  CHECK(s0["summary"].is_null());
  batch_json({m, "-o", out, "--shard", "2/3"});

  std::string text;
  CHECK(run_cli({"batch", "--merge", out}, &text) == 4);
  CHECK_THAT(text, Catch::Contains("shard 1/3 never ran (3 of its 3 variants missing)"));
  const std::vector<nlohmann::json> partial = summary_rows(out);
  REQUIRE(partial.size() == 8);
  CHECK(partial[1]["status"] == "missing");
  CHECK(partial[0]["status"] == "ok");

  batch_json({m, "-o", out, "--shard", "1/3"});
  CHECK(run_cli({"batch", "--merge", out}, &text) == 0);
  const std::string merged = file_text(dir / "sharded" / "summary.jsonl");
  const std::string merged_csv = file_text(dir / "sharded" / "summary.csv");
  CHECK(run_cli({"batch", "--merge", out}, &text) == 0);
  CHECK(file_text(dir / "sharded" / "summary.jsonl") == merged);
  CHECK(file_text(dir / "sharded" / "summary.csv") == merged_csv);
  CHECK(summary_without_timings(out) == summary_without_timings(dir / "whole"));
  CHECK(output_tree(out) == output_tree(dir / "whole"));
  // A whole run over the shards' folder reuses all their work.
  CHECK(batch_json({m, "-o", out})["reused"] == 8);
}

TEST_CASE("batch: --merge of a folder without ledgers is exit 2", "[pipeline][batch]") {
  const fs::path dir = fresh_dir("batch/merge_empty");
  std::string text;
  CHECK(run_cli({"batch", "--merge", dir.string()}, &text) == 2);
  CHECK_THAT(text, Catch::Contains("no batch ledger"));
}

TEST_CASE("batch: progress goes to stderr (none with -q) and --slurm writes a job array of the shards",
          "[pipeline][batch]") {
  const fs::path dir = batch_folder("cli", kSweep);
  const std::string m = (dir / "m.yaml").string();
  const CliResult plain = run_fabmesh({"batch", m, "-o", (dir / "out").string()});
  CHECK(plain.code == 0);
  // Not a terminal: plain lines, the last one always.
  CHECK_THAT(plain.err, Catch::Contains("batch: 8/8 done, 0 failed, 0 reused"));
  CHECK_THAT(plain.out, Catch::Contains("8 ok") && Catch::Contains("summary.csv"));
  const CliResult quiet = run_fabmesh({"batch", m, "-o", (dir / "out").string(), "-q"});
  CHECK(quiet.code == 0);
  CHECK(quiet.err.empty());

  const std::string out = (dir / "array").string();
  const CliResult slurm = run_fabmesh({"batch", m, "-o", out, "--slurm", "--array-size", "3", "--jobs", "2"});
  INFO(slurm.err);
  REQUIRE(slurm.code == 0);
  const std::string script = file_text(dir / "array" / "slurm.sbatch");
  CHECK_THAT(script, Catch::Contains("#SBATCH --array=0-2\n") && Catch::Contains("--cpus-per-task=2\n"));
  CHECK_THAT(script, Catch::Contains("--shard \"${SLURM_ARRAY_TASK_ID}/3\" --jobs 2"));
  CHECK(fs::is_directory(dir / "array" / ".batch" / "slurm"));
  CHECK(fs::status(dir / "array" / "slurm.sbatch").permissions() != fs::perms::none);
  // Nothing ran: the tasks do.
  CHECK_FALSE(fs::exists(dir / "array" / "summary.csv"));
  // Run as the array would, each shard, then merged: the same summary as a whole run.
  for (const char* shard : {"0/3", "1/3", "2/3"}) batch_json({m, "-o", out, "--shard", shard, "--jobs", "2"});
  CHECK(run_cli({"batch", "--merge", out}) == 0);
  CHECK(summary_without_timings(out) == summary_without_timings(dir / "out"));
}

TEST_CASE("batch: a million-variant manifest is planned for Slurm in bounded memory", "[pipeline][batch]") {
  // Its variants are made from the grid's value lists on demand: expanded up
  // front they took 1.07 GB and 3.2 s; now about 27 MB and 0.3 s.
  const fs::path dir = batch_folder("million_slurm", R"(design: cup.yaml
name: cup_w{body.wall}_b{body.base}
grid:
  body.wall: {from: 0.2, to: 0.3, steps: 1000}
  body.base: {from: 0.1, to: 0.4, steps: 1000}
)");
  const LimitedRun r = run_limited(
      {"batch", (dir / "m.yaml").string(), "-o", (dir / "out").string(), "--slurm", "--array-size", "100"},
      60.0, std::size_t{256} << 20);
  INFO(r.describe() << "\n" << r.out << r.err);
  REQUIRE_FALSE(r.timed_out);
  CHECK(r.code == 0);
  CHECK_THAT(r.out + r.err, Catch::Contains("1000000 variants"));
}
