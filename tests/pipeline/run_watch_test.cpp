// `fabmesh run --watch` as a designer uses it: a real process that runs
// again when the design or a file it reads changes, keeps the last good
// files when an edit breaks the design, and ends cleanly on Ctrl-C.

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "io/file.h"
#include "tests/pipeline/cli_harness.h"

extern char** environ;

using namespace fabmesh;
using namespace fabmesh::testing;
namespace fs = std::filesystem;

namespace {

// Starts `fabmesh run --watch DESIGN -o OUT/` with its streams in files.
pid_t start_watch(const fs::path& dir) {
  const std::vector<std::string> args{
      FABMESH_BINARY, "run", "--watch", (dir / "edge.yaml").string(), "-o", (dir / "out").string() + "/"};
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const std::string out = (dir / "stdout.txt").string(), err = (dir / "stderr.txt").string();
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, FABMESH_BINARY, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  REQUIRE(rc == 0);
  return pid;
}

std::string text_of(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return "";
  return read_file(path.string(), 64u << 20, "test");
}

std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

// Waits (a hang guard, not a timing requirement) until `ready` holds while the process runs.
void wait_until(pid_t pid, const std::function<bool()>& ready, const std::string& what) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!ready()) {
    int status = 0;
    INFO("waiting for " << what);
    REQUIRE(waitpid(pid, &status, WNOHANG) == 0);  // it must still be watching
    REQUIRE(std::chrono::steady_clock::now() < deadline);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

constexpr const char* kDesign = R"(# An edge profile from digitised points.
name: edge
kind: curve
tolerance: 0.01
outputs: [dxf]
curve:
  family: tbezier
  segments:
    - polyline: {file: points.csv}
)";

}  // namespace

TEST_CASE("run --watch: runs again on edits of the design and its files, keeps the last good files",
          "[pipeline][watch]") {
  const fs::path dir = fresh_dir("run_watch");
  write_text(dir / "edge.yaml", kDesign);
  write_text(dir / "points.csv", "0,0\n10,0\n10,5\n");
  const pid_t pid = start_watch(dir);
  const fs::path dxf = dir / "out" / "edge.dxf";
  const fs::path out = dir / "stdout.txt";
  wait_until(
      pid, [&] { return count_of(text_of(out), "watching 2 files") == 1; }, "the first run");
  const std::string first = text_of(dxf);
  REQUIRE_FALSE(first.empty());

  // An edit of the file the design reads: a new drawing.
  write_text(dir / "points.csv", "0,0\n10,0\n10,5\n20,5\n");
  wait_until(
      pid, [&] { return count_of(text_of(out), "watching 2 files") == 2; }, "the run after the CSV edit");
  CHECK(text_of(out).find("points.csv changed; running again") != std::string::npos);
  const std::string second = text_of(dxf);
  CHECK(second != first);
  CHECK(second.find("20.0") != std::string::npos);

  // An edit that breaks the design: its error, located, and the last good file kept.
  std::string broken = kDesign;
  broken.replace(broken.find("tolerance: 0.01"), 15, "tolerance: -1");
  write_text(dir / "edge.yaml", broken);
  wait_until(
      pid, [&] { return text_of(out).find("failed, the last good files stay") != std::string::npos; },
      "the failed run");
  const std::string errors = text_of(dir / "stderr.txt");
  CHECK(errors.find("edge.yaml:4:") != std::string::npos);
  CHECK(errors.find("tolerance") != std::string::npos);
  CHECK(text_of(dxf) == second);

  // Fixed again: written again.
  write_text(dir / "edge.yaml", kDesign);
  wait_until(
      pid, [&] { return count_of(text_of(out), "done; watching") == 3; }, "the run after the fix");
  CHECK(text_of(dxf) == second);

  ::kill(pid, SIGINT);
  int status = 0;
  REQUIRE(waitpid(pid, &status, 0) == pid);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 0);
  CHECK(text_of(out).find("stopped watching") != std::string::npos);
}

TEST_CASE("run --watch refuses -o -", "[pipeline][watch]") {
  std::string output;
  CHECK(run_cli({"run", "--watch", example("vessel_golden_solid.yaml"), "-o", "-"}, &output) == 2);
  CHECK(output.find("--watch") != std::string::npos);
}
