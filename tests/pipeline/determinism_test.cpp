// Outputs are byte-for-byte deterministic: two separate runs of the real
// executable (different processes, so different addresses and uninitialised
// memory) write identical files, for every format of every bundled example.

#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <map>

#include "geometry/core/errors.h"
#include "io/design/read_design.h"
#include "io/file.h"
#include "pipeline/outputs.h"
#include "tests/pipeline/cli_harness.h"
#include "tests/pipeline/limited_run.h"

using namespace fabmesh;
using namespace fabmesh::testing;
namespace fs = std::filesystem;

namespace {

// The file names in `dir`, sorted.
std::vector<std::string> files_in(const fs::path& dir) {
  std::vector<std::string> names;
  if (!fs::exists(dir)) return names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

TEST_CASE("run: two runs write byte-identical files for every format of every example",
          "[pipeline][run][determinism]") {
  // The examples `run` accepts, grouped by kind: one invocation per kind asks for all of its formats.
  std::map<std::string, std::vector<std::string>> by_kind;
  std::vector<std::string> paths;
  for (const auto& e : fs::directory_iterator(std::string(FABMESH_SOURCE_DIR) + "/configs/examples"))
    if (e.path().extension() == ".yaml") paths.push_back(e.path().string());
  std::sort(paths.begin(), paths.end());
  for (const std::string& path : paths) {
    Design design;
    try {
      design = read_design(path);
    } catch (const FileError&) {
      continue;  // not a runnable design (yet): `run` refuses it, there is nothing to compare
    }
    if (std::holds_alternative<CurveDesign>(design.body)) continue;  // no mesh, no files
    by_kind[kind_name(design)].push_back(path);
  }
  for (const char* kind : {"vessel", "countertop", "surface"}) CHECK(by_kind.count(kind) == 1);

  const fs::path dir = fresh_dir("determinism");
  std::size_t compared = 0;
  for (const auto& [kind, designs] : by_kind) {
    std::string formats;
    std::size_t format_count = 0;
    const std::vector<std::string> kinds = kind_names();
    const auto index = static_cast<std::size_t>(std::find(kinds.begin(), kinds.end(), kind) - kinds.begin());
    for (const OutputFormat& f : output_formats()) {
      if (!f.kinds.test(index)) continue;
      formats += (formats.empty() ? "" : ",") + std::string(f.name);
      ++format_count;
    }
    for (const char* round : {"a", "b"}) {
      std::vector<std::string> args{"run", "-q",
                                    "-o",  (dir / round / kind).string(),
                                    "-D",  "outputs=[" + formats + "]",
                                    "-D",  "on_output_error=fail"};
      args.insert(args.end(), designs.begin(), designs.end());
      const LimitedRun r = run_limited(args, 600.0, 4096 * kMiB);
      INFO(kind << " round " << round << ": " << r.describe());
      REQUIRE(r.code == 0);
    }
    const std::vector<std::string> a = files_in(dir / "a" / kind), b = files_in(dir / "b" / kind);
    INFO(kind << ": " << designs.size() << " designs, formats " << formats);
    CHECK(a.size() == designs.size() * format_count);
    REQUIRE(a == b);
    for (const std::string& name : a) {
      INFO(name);
      CHECK(read_file((dir / "a" / kind / name).string()) == read_file((dir / "b" / kind / name).string()));
      ++compared;
    }
  }
  CHECK(compared > 0);
}
