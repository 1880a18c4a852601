#include "pipeline/batch/ledger.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <string>

#include "geometry/core/errors.h"
#include "pipeline/batch/merge.h"
#include "pipeline/batch/progress.h"
#include "pipeline/batch/sha256.h"
#include "pipeline/batch/shard.h"
#include "pipeline/batch/slurm_script.h"
#include "tests/pipeline/batch/batch_fixture.h"

using namespace fabmesh;
namespace fs = std::filesystem;

TEST_CASE("batch: SHA-256 gives the FIPS 180-2 digests, in one piece or many", "[pipeline][batch]") {
  CHECK(sha256_hex("") == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  CHECK(sha256_hex("abc") == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  const std::string two_blocks = "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq";
  CHECK(sha256_hex(two_blocks) == "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  Sha256 pieces;
  const std::string million(1000000, 'a');
  for (std::size_t i = 0; i < million.size(); i += 999)
    pieces.update(std::string_view(million).substr(i, 999));
  CHECK(pieces.hex_digest() == "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST_CASE("batch: SHA-256 with the SHA extensions gives the portable code's digests", "[pipeline][batch]") {
  // The processor's own word: the extensions are used exactly where /proc/cpuinfo lists sha_ni.
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string text((std::istreambuf_iterator<char>(cpuinfo)), std::istreambuf_iterator<char>());
  const bool listed = text.find(" sha_ni") != std::string::npos;
#if defined(__x86_64__)
  CHECK(sha256_hardware() == listed);
#endif
  INFO("SHA extensions used: " << sha256_hardware());
  for (const Sha256::Engine engine : {Sha256::Engine::Fastest, Sha256::Engine::Portable}) {
    CHECK(Sha256(engine).update("abc").hex_digest() ==
          "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  }
  // Every length up to five blocks and a megabyte of varied bytes, whole and in uneven pieces.
  std::string bytes(1 << 20, '\0');
  std::uint32_t x = 2463534242U;
  for (char& c : bytes) {
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    c = static_cast<char>(x & 0xFFU);
  }
  for (std::size_t n = 0; n <= 320; ++n) {
    const std::string_view m = std::string_view(bytes).substr(0, n);
    REQUIRE(Sha256(Sha256::Engine::Fastest).update(m).hex_digest() ==
            Sha256(Sha256::Engine::Portable).update(m).hex_digest());
  }
  Sha256 pieces;
  for (std::size_t at = 0, step = 1; at < bytes.size(); at += step, step = step * 7 % 1021 + 1)
    pieces.update(std::string_view(bytes).substr(at, step));
  CHECK(pieces.hex_digest() == Sha256(Sha256::Engine::Portable).update(bytes).hex_digest());
}

TEST_CASE("batch: a ledger line is committed only whole, with its check", "[pipeline][batch]") {
  const std::string line = ledger_line(R"({"name":"a"})");
  REQUIRE(committed_json(line));
  CHECK(*committed_json(line) == R"({"name":"a"})");
  for (std::size_t cut = 0; cut < line.size(); ++cut) CHECK_FALSE(committed_json(line.substr(0, cut)));
  std::string flipped = line;
  flipped[3] = 'b';
  CHECK_FALSE(committed_json(flipped));
}

TEST_CASE("batch: a reopened ledger cuts its torn end and keeps its rows, one writer at a time",
          "[pipeline][batch]") {
  const fs::path dir = fabmesh::testing::fresh_dir("batch/ledger");
  const LedgerHeader header{"p1", 4, {0, 1}};
  {
    LedgerWriter w(dir.string(), header);
    w.append(R"({"name":"a"})");
    w.append(R"({"name":"b"})");
    CHECK_THROWS_AS(LedgerWriter(dir.string(), header), InputError);  // locked
  }
  const fs::path path = dir / "ledger-0-of-1.jsonl";
  std::ofstream(path, std::ios::app) << R"({"name":"c"})"
                                     << "\t0123";  // torn by a kill
  {
    LedgerWriter w(dir.string(), header);
    w.append(R"({"name":"d"})");
  }
  std::vector<std::string> rows;
  for_each_row({path.string(), true, std::nullopt},
               [&](std::string_view json, std::uint64_t) { rows.emplace_back(json); });
  CHECK(rows == std::vector<std::string>{R"({"name":"a"})", R"({"name":"b"})", R"({"name":"d"})"});
  // A ledger of another plan is moved aside, not lost.
  { LedgerWriter w(dir.string(), {"p2", 4, {0, 1}}); }
  const std::vector<LedgerFile> files = list_ledgers(dir.string());
  REQUIRE(files.size() == 2);
  CHECK_FALSE(files[0].current);
  CHECK(files[0].header->plan == "p1");
  CHECK(files[1].header->plan == "p2");
}

TEST_CASE("batch: a ledger header with counts fabmesh never writes is no header", "[pipeline][batch]") {
  const fs::path dir = fabmesh::testing::fresh_dir("batch/ledger_header");
  const auto header_of = [&](const std::string& json) {
    std::ofstream(dir / "ledger-0-of-1.jsonl", std::ios::binary | std::ios::trunc) << ledger_line(json);
    const std::vector<LedgerFile> files = list_ledgers(dir.string());
    REQUIRE(files.size() == 1);
    return files[0].header;
  };
  const std::string head = R"({"fabmesh_batch_ledger":1,"plan":"p",)";
  const std::optional<LedgerHeader> good = header_of(head + R"("variants":4,"shard":1,"shards":3})");
  REQUIRE(good);
  CHECK(good->plan == "p");
  CHECK(good->variants == 4);
  CHECK(good->shard.index == 1);
  CHECK(good->shard.count == 3);
  CHECK(header_of(head + R"("variants":1000000,"shard":999999,"shards":1000000})"));
  // Found by fuzz_ledger: a count of 1e300 was undefined behaviour (a float
  // converted to a size out of range), and a merge sized its per-shard tallies
  // by "shards" (1e14 of them: out of memory).
  for (const char* counts :
       {R"("variants":4,"shard":0,"shards":100000000000000})", R"("variants":4,"shard":0,"shards":1000001})",
        R"("variants":1e300,"shard":0,"shards":1})", R"("variants":4,"shard":-1,"shards":3})",
        R"("variants":4,"shard":0,"shards":2.0})", R"("variants":4,"shard":"0","shards":1})",
        R"("variants":4,"shard":3,"shards":3})", R"("variants":1000001,"shard":0,"shards":1})"}) {
    INFO(counts);
    CHECK_FALSE(header_of(head + counts));
  }
  CHECK_FALSE(header_of(R"({"fabmesh_batch_ledger":1,"plan":5,"variants":4,"shard":0,"shards":1})"));
}

TEST_CASE("batch: a merge of a ledger whose header counts 1e14 shards finds no ledger", "[pipeline][batch]") {
  // Found by fuzz_ledger: the merge's per-shard tallies were one vector of that many entries.
  const fs::path out = fabmesh::testing::fresh_dir("batch/merge_shards");
  const fs::path folder = out / ".batch";
  fs::create_directories(folder);
  std::ofstream(folder / "plan-d.json")
      << R"({"fabmesh_batch_plan":1,"digest":"d","manifest":"m.yaml","parameters":[],"variants":[]})";
  std::ofstream(folder / "ledger-0-of-1.jsonl") << ledger_line(
      R"({"fabmesh_batch_ledger":1,"plan":"d","variants":0,"shard":0,"shards":100000000000000})");
  CHECK_THROWS_WITH(merge_batch(out.string()), Catch::Contains("no batch ledger here"));
}

TEST_CASE("batch: shards split the variants by index modulo their count", "[pipeline][batch]") {
  const Shard s = parse_shard("2/3");
  CHECK(s.owns(2));
  CHECK(s.owns(5));
  CHECK_FALSE(s.owns(3));
  CHECK(s.size_of(8) == 2);
  std::size_t total = 0;
  for (std::size_t i = 0; i < 7; ++i) total += Shard{i, 7}.size_of(100);
  CHECK(total == 100);
  CHECK_THROWS_AS(parse_shard("3/3"), InputError);
  CHECK_THROWS_AS(parse_shard("1of3"), InputError);
}

TEST_CASE("batch: progress lines count done, failed and reused variants with a rate and an ETA",
          "[pipeline][batch]") {
  BatchProgress p;
  p.total = 100;
  p.done = 30;
  p.reused = 10;
  p.failed = 2;
  p.elapsed_s = 4.0;
  CHECK(progress_line(p) == "batch: 30/100 done (30%), 2 failed, 10 reused, 5.0/s, ETA 0:14");
  p.done = 100;
  p.finished = true;
  CHECK(progress_line(p) == "batch: 100/100 done, 2 failed, 10 reused, 22.5/s, 4.0 s");
  // Not on a terminal: at most one line per interval, and always the last.
  std::ostringstream out;
  ProgressPrinter printer(out, {false, 5.0});
  p.finished = false;
  for (double t : {0.0, 1.0, 4.9, 5.1}) {
    p.elapsed_s = t;
    printer(p);
  }
  p.finished = true;
  printer(p);
  const std::string lines = out.str();
  CHECK(std::count(lines.begin(), lines.end(), '\n') == 3);
}

TEST_CASE("batch: the sbatch script runs shard SLURM_ARRAY_TASK_ID of N into one folder",
          "[pipeline][batch]") {
  SlurmScriptOptions o;
  o.program = "/opt/fab mesh/fabmesh";
  o.manifest = "/m/it's.yaml";
  o.out_dir = "/data/out";
  o.variants = 250;
  o.shards = 10;
  o.cpus_per_task = 2;
  const std::string s = slurm_script(o);
  CHECK_THAT(s, Catch::StartsWith("#!/bin/bash\n"));
  CHECK_THAT(s, Catch::Contains("#SBATCH --array=0-9\n") && Catch::Contains("#SBATCH --cpus-per-task=2\n"));
  CHECK_THAT(s,
             Catch::Contains("exec '/opt/fab mesh/fabmesh' batch '/m/it'\\''s.yaml' -o '/data/out' --shard "
                             "\"${SLURM_ARRAY_TASK_ID}/10\" --jobs 2 --quiet\n"));
  o.out_dir = "/data/with space";
  CHECK_THROWS_AS(slurm_script(o), InputError);
}
