// Issue 43: under a file size limit (`ulimit -f`, RLIMIT_FSIZE) a write past
// it raised SIGXFSZ, which killed fabmesh with no message. The program
// ignores the signal: the write fails with EFBIG and the run exits 5 (an
// environment failure, docs/commands.md), nothing half-written left.

#include <catch2/catch.hpp>
#include <filesystem>

#include "tests/pipeline/cli_harness.h"
#include "tests/pipeline/limited_run.h"

using namespace fabmesh;
using namespace fabmesh::testing;
namespace fs = std::filesystem;

TEST_CASE("run: a file size limit is an environment failure (exit 5), not a kill by SIGXFSZ",
          "[pipeline][run][honest]") {
  const fs::path dir = fresh_dir("file_size_limit");
  // The child's shell sets the limit (16 blocks); SIGXFSZ is left at its default.
  const LimitedRun r = run_limited({"run", example("vessel_golden_solid.yaml"), "-o", (dir / "out").string()},
                                   120.0, 2048 * kMiB, "", "ulimit -f 16;");
  INFO(r.describe());
  CHECK(r.signal == 0);
  CHECK(r.code == 5);
  CHECK_THAT(r.err, Catch::Contains("File too large") && Catch::Contains("vessel_golden_solid"));
  // Nothing under the outputs' names, and no temporary left.
  if (fs::exists(dir / "out")) CHECK(fs::is_empty(dir / "out"));
}
