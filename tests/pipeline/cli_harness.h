#pragma once
// Shared by the pipeline tests: run the command line in-process, find the
// bundled examples, and get a fresh scratch folder per test.

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/file.h"
#include "pipeline/cli/commands.h"
#include "pipeline/job.h"
#include "tests/pipeline/json_item.h"

namespace fabmesh::testing {

/// The path of a bundled example design.
inline std::string example(const std::string& name) {
  return std::string(FABMESH_SOURCE_DIR) + "/configs/examples/" + name;
}

/// Writes `text` to `path` as it is (binary: no line-end translation).
inline void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

/// An empty folder under the test build folder, named for the test: ctest
/// runs test cases as parallel processes, so no two may share a name.
inline std::filesystem::path fresh_dir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(FABMESH_TEST_TMP) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// Job options that write into `dir`.
inline JobOptions into(const std::filesystem::path& dir) {
  JobOptions options;
  options.out_dir = dir.string();
  return options;
}

/// The verdict on a result's own mesh (its product part).
inline const ValidationReport& verdict(const Result& result) {
  const Part* part = product(result);
  REQUIRE(part != nullptr);
  return part->validation;
}

/// What one run of the command line did.
struct CliResult {
  int code = 0;
  std::string out, err;
};

/// Runs `fabmesh args...` in-process and captures both streams.
inline CliResult run_fabmesh(std::vector<std::string> args) {
  args.insert(args.begin(), "fabmesh");
  std::vector<const char*> argv;
  for (const auto& a : args) argv.push_back(a.c_str());
  std::ostringstream out, err;
  const int code = cli::run_app(static_cast<int>(argv.size()), argv.data(), {out, err});
  return {code, out.str(), err.str()};
}

/// The same, with standard output then standard error in `*combined`.
inline int run_cli(std::vector<std::string> args, std::string* combined = nullptr) {
  const CliResult r = run_fabmesh(std::move(args));
  if (combined) *combined = r.out + r.err;
  return r.code;
}

/// The same for a `--json` run: standard output alone in `*json_text`, since a
/// long run also writes progress lines on standard error (every 5 s when it
/// is not a terminal; a sanitized build is slow enough to get them). On a
/// failure standard error follows, for the test's message.
inline int run_cli_json(std::vector<std::string> args, std::string* json_text) {
  const CliResult r = run_fabmesh(std::move(args));
  *json_text = r.code == 0 ? r.out : r.out + r.err;
  return r.code;
}

/// The bundled example `example_name` with `find` replaced by `replace`,
/// written to `dir/name`; its path.
inline std::string edited_example(const std::filesystem::path& dir, const std::string& example_name,
                                  const std::string& find, const std::string& replace,
                                  const std::string& name) {
  std::string text = read_file(example(example_name));
  const auto at = text.find(find);
  REQUIRE(at != std::string::npos);
  text.replace(at, find.size(), replace);
  const std::filesystem::path path = dir / name;
  write_file_atomically(path.string(), text);
  return path.string();
}

/// Whether `text` names `file:LINE:COLUMN: key: ` (a message located at a design's key).
inline bool names_place(const std::string& text, const std::string& file, const std::string& key) {
  for (std::size_t at = text.find(file + ":"); at != std::string::npos; at = text.find(file + ":", at + 1)) {
    std::size_t i = at + file.size() + 1;
    int numbers = 0;
    while (numbers < 2) {
      const std::size_t digits = i;
      while (i < text.size() && text[i] >= '0' && text[i] <= '9') ++i;
      if (i == digits || i >= text.size() || text[i] != ':') break;
      ++i;
      ++numbers;
    }
    if (numbers == 2 && text.compare(i, key.size() + 3, " " + key + ": ") == 0) return true;
  }
  return false;
}

}  // namespace fabmesh::testing
