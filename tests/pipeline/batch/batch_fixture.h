#pragma once
// Shared by the batch tests: a scratch folder with a small cup design and a
// manifest, the files a batch wrote, and its summaries without their timings.

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "pipeline/batch/ledger.h"
#include "tests/pipeline/cli_harness.h"

namespace fabmesh::testing {

/// The golden shell cup, small and quick to build (about 5000 triangles).
inline const std::string kBatchCup = R"(name: cup
kind: vessel
units: cm
tolerance: 0.02
profile:
  family: quasi_bspline
  points: [[1.5, 6], [1, 5], [2, 4], [3, 3], [1.5, 2]]
  lambdas: [0, 0, 0]
body: {mode: shell, wall: 0.3, base: 0.4}
outputs: [stl]
)";

/// A fresh folder holding cup.yaml and m.yaml (the manifest `manifest_text`).
inline std::filesystem::path batch_folder(const std::string& name, const std::string& manifest_text) {
  const std::filesystem::path dir = fresh_dir("batch/" + name);
  std::ofstream(dir / "cup.yaml") << kBatchCup;
  std::ofstream(dir / "m.yaml") << manifest_text;
  return dir;
}

/// The whole content of a file.
inline std::string file_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Every file under `dir` but the batch's own (.batch/, summary.*): relative path -> bytes.
inline std::map<std::string, std::string> output_tree(const std::filesystem::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    const std::string rel = std::filesystem::relative(e.path(), dir).generic_string();
    if (rel.rfind(".batch", 0) == 0 || rel.rfind("summary.", 0) == 0) continue;
    if (e.is_regular_file()) files[rel] = file_text(e.path());
  }
  return files;
}

/// summary.jsonl and summary.csv of `dir` without their timing fields (the last three CSV columns).
inline std::string summary_without_timings(const std::filesystem::path& dir) {
  std::string out;
  std::istringstream jsonl(file_text(dir / "summary.jsonl"));
  for (std::string line; std::getline(jsonl, line);) {
    nlohmann::ordered_json j = nlohmann::ordered_json::parse(line);
    j.erase("timings_ms");
    out += j.dump() + "\n";
  }
  std::istringstream csv(file_text(dir / "summary.csv"));
  for (std::string line; std::getline(csv, line);) {
    for (int k = 0; k < 3; ++k) line.erase(line.rfind(','));
    out += line + "\n";
  }
  return out;
}

/// The summary.jsonl rows of `dir`.
inline std::vector<nlohmann::json> summary_rows(const std::filesystem::path& dir) {
  std::vector<nlohmann::json> rows;
  std::istringstream jsonl(file_text(dir / "summary.jsonl"));
  for (std::string line; std::getline(jsonl, line);) rows.push_back(nlohmann::json::parse(line));
  return rows;
}

/// The committed rows (not the header) of a shard's ledger in out/.batch.
inline std::size_t committed_rows(const std::filesystem::path& out,
                                  const std::string& ledger = "ledger-0-of-1.jsonl") {
  const std::filesystem::path path = out / ".batch" / ledger;
  if (!std::filesystem::exists(path)) return 0;
  std::size_t n = 0;
  for_each_row({path.string(), true, std::nullopt}, [&](std::string_view, std::uint64_t) { ++n; });
  return n;
}

/// `fabmesh batch ARGS... --json -q`, in-process; the parsed JSON report.
inline nlohmann::json batch_json(std::vector<std::string> args, int* code = nullptr,
                                 std::string* err = nullptr) {
  args.insert(args.begin(), "batch");
  args.push_back("--json");
  args.push_back("-q");
  const CliResult r = run_fabmesh(args);
  if (code) *code = r.code;
  if (err) *err = r.err;
  INFO(r.out << r.err);
  REQUIRE_FALSE(r.out.empty());
  return only_item(r.out);
}

}  // namespace fabmesh::testing
