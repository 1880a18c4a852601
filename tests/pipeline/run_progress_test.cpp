// A long `fabmesh run` shows which stage each design has finished: a live
// line on a terminal, plain lines every few seconds otherwise, none for a run
// shorter than that (and none with -q).

#include "pipeline/cli/run_progress.h"

#include <catch2/catch.hpp>
#include <sstream>
#include <string>

#include "io/design/read_design.h"
#include "tests/pipeline/cli_harness.h"

using namespace fabmesh;
using namespace fabmesh::testing;

namespace {

// Runs the golden shell with every stage reported to `progress`.
void run_reported(cli::RunProgress& progress, const std::string& dir) {
  const Design design = read_design(example("vessel_golden_shell.yaml"));
  JobOptions options = into(fresh_dir(dir));
  options.on_stage = [&](const std::string& stage, double ms) {
    progress.stage(design.common.name, stage, ms);
  };
  run_job(design, options);
  progress.design_done();
  progress.finish();
}

}  // namespace

TEST_CASE("run progress: every stage of a job is reported, in order, as plain lines",
          "[pipeline][progress]") {
  std::ostringstream err;
  cli::RunProgress progress(err, 1, false, 0.0);
  run_reported(progress, "progress_plain");
  const std::string text = err.str();
  INFO(text);
  const std::size_t curve = text.find("run: 0/1 designs done, vessel_golden_shell: curve done in ");
  const std::size_t build = text.find("vessel_golden_shell: build done in ");
  const std::size_t validate = text.find("vessel_golden_shell: validate done in ");
  const std::size_t write = text.find("vessel_golden_shell: write done in ");
  REQUIRE(curve != std::string::npos);
  REQUIRE(build != std::string::npos);
  REQUIRE(validate != std::string::npos);
  REQUIRE(write != std::string::npos);
  CHECK((curve < build && build < validate && validate < write));
  CHECK(text.find('\r') == std::string::npos);
  CHECK(text.back() == '\n');
}

TEST_CASE("run progress: on a terminal one line is redrawn and cleared before the results",
          "[pipeline][progress]") {
  std::ostringstream err;
  cli::RunProgress progress(err, 1, true, 0.0);
  run_reported(progress, "progress_terminal");
  const std::string text = err.str();
  CHECK(text.find('\n') == std::string::npos);
  CHECK(text.rfind("\r\x1b[K") == text.size() - 4);  // cleared
  CHECK_THAT(text, Catch::Contains("\rrun: 0/1 designs done, vessel_golden_shell: validate done in "));
}

TEST_CASE("run progress: a run shorter than the interval prints no progress line", "[pipeline][progress]") {
  const auto dir = fresh_dir("progress_short");
  const CliResult r = run_fabmesh({"run", example("vessel_golden_shell.yaml"), "-o", (dir / "out").string()});
  CHECK(r.code == 0);
  CHECK_THAT(r.err, !Catch::Contains("run: "));
}
