// Outputs are byte-for-byte deterministic: two separate runs of the real
// executable (different processes, so different addresses and uninitialised
// memory) write identical files, for every format of every bundled example.

#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <map>
#include <set>

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
  // The examples `run` accepts, grouped by the formats they can make (their kind's, with the
  // content each needs: a mould, a router path): one invocation per group asks for all of them.
  std::map<std::string, std::vector<std::string>> by_formats;
  std::set<std::string> kinds_seen;
  std::vector<std::string> paths;
  for (const auto& e : fs::directory_iterator(std::string(FABMESH_SOURCE_DIR) + "/configs/examples"))
    if (e.path().extension() == ".yaml") paths.push_back(e.path().string());
  std::sort(paths.begin(), paths.end());
  const std::vector<std::string> kinds = kind_names();
  for (const std::string& path : paths) {
    Design design;
    try {
      design = read_design(path);
    } catch (const FileError&) {
      continue;  // not a runnable design (a batch manifest): `run` refuses it, there is nothing to compare
    }
    if (std::holds_alternative<CurveDesign>(design.body)) continue;  // drawings are compared by the DXF test
    kinds_seen.insert(kind_name(design));
    std::string formats;
    for (const OutputFormat& f : output_formats()) {
      if (!f.kinds.test(design.body.index()) || !has_content(design, f.content)) continue;
      formats += (formats.empty() ? "" : ",") + std::string(f.name);
    }
    by_formats[formats].push_back(path);
  }
  for (const char* kind : {"vessel", "countertop", "surface"}) CHECK(kinds_seen.count(kind) == 1);

  const fs::path dir = fresh_dir("determinism");
  std::size_t compared = 0, group = 0;
  for (const auto& [formats, designs] : by_formats) {
    const std::string sub = "group" + std::to_string(group++);
    const auto format_count = static_cast<std::size_t>(std::count(formats.begin(), formats.end(), ',') + 1);
    for (const char* round : {"a", "b"}) {
      std::vector<std::string> args{"run", "-q",
                                    "-o",  (dir / round / sub).string(),
                                    "-D",  "outputs=[" + formats + "]",
                                    "-D",  "on_output_error=fail"};
      args.insert(args.end(), designs.begin(), designs.end());
      const LimitedRun r = run_limited(args, 600.0, 4096 * kMiB);
      INFO(formats << " round " << round << ": " << r.describe());
      REQUIRE(r.code == 0);
    }
    const std::vector<std::string> a = files_in(dir / "a" / sub), b = files_in(dir / "b" / sub);
    INFO(designs.size() << " designs, formats " << formats);
    CHECK(a.size() >= designs.size() * format_count);  // a mould writes a file per part
    REQUIRE(a == b);
    for (const std::string& name : a) {
      INFO(name);
      CHECK(read_file((dir / "a" / sub / name).string()) == read_file((dir / "b" / sub / name).string()));
      ++compared;
    }
  }
  CHECK(compared > 0);
}
