// A real `fabmesh batch` process killed with SIGKILL mid-run, then run again,
// ends as an uninterrupted run does: nothing lost, corrupt, or done twice.

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "tests/pipeline/batch/batch_fixture.h"

extern char** environ;

using namespace fabmesh;
using namespace fabmesh::testing;
namespace fs = std::filesystem;

namespace {

// Starts `fabmesh batch MANIFEST -o OUT --jobs 1 -q` in a child process.
pid_t start_batch(const fs::path& manifest, const fs::path& out) {
  const std::vector<std::string> args{
      FABMESH_BINARY, "batch", manifest.string(), "-o", out.string(), "--jobs", "1", "-q"};
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, FABMESH_BINARY, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  REQUIRE(rc == 0);
  return pid;
}

// Kills the batch with SIGKILL once its ledger holds `rows` committed rows; the rows it then holds.
std::size_t kill_after(pid_t pid, const fs::path& out, std::size_t rows) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (committed_rows(out) < rows && std::chrono::steady_clock::now() < deadline) {
    int status = 0;
    REQUIRE(waitpid(pid, &status, WNOHANG) == 0);  // it must still run: the batch is long enough
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ::kill(pid, SIGKILL);
  int status = 0;
  REQUIRE(waitpid(pid, &status, 0) == pid);
  REQUIRE(WIFSIGNALED(status));
  CHECK(WTERMSIG(status) == SIGKILL);
  return committed_rows(out);
}

}  // namespace

TEST_CASE("batch: killed with SIGKILL twice, a rerun ends as an uninterrupted run with nothing done twice",
          "[pipeline][batch][slow]") {
  const fs::path dir = batch_folder("kill", R"(design: cup.yaml
name: cup_w{body.wall}_b{body.base}
set: {outputs: [stl, 3mf]}
grid:
  body.wall: {from: 0.2, to: 0.4, steps: 6}
  body.base: {from: 0.3, to: 0.6, steps: 6}
)");
  const fs::path out = dir / "killed";
  // First kill early, then again later; the kill lands wherever the child is
  // (in a job, writing files, appending to its ledger).
  const std::size_t first = kill_after(start_batch(dir / "m.yaml", out), out, 3);
  CHECK(first >= 3);
  const std::size_t second = kill_after(start_batch(dir / "m.yaml", out), out, first + 10);
  CHECK(second >= first + 10);
  REQUIRE(second < 36);

  // The rerun redoes only what no committed row stands for (one variant runs at a time: --jobs 1).
  const nlohmann::json rerun = batch_json({(dir / "m.yaml").string(), "-o", out.string(), "--jobs", "1"});
  CHECK(rerun["reused"] == second);
  CHECK(rerun["ran"] == 36 - second);
  CHECK(rerun["ok"] == 36);

  const nlohmann::json whole = batch_json({(dir / "m.yaml").string(), "-o", (dir / "whole").string()});
  CHECK(whole["ok"] == 36);
  // Same files, byte for byte, and no stray temporary or partial file anywhere.
  CHECK(output_tree(out) == output_tree(dir / "whole"));
  CHECK(summary_without_timings(out) == summary_without_timings(dir / "whole"));
  // Every row of the ledger is whole (a torn line was cut when the ledger was reopened).
  const std::string ledger = file_text(out / ".batch" / "ledger-0-of-1.jsonl");
  std::size_t lines = 0;
  for (std::size_t start = 0; start < ledger.size();) {
    const std::size_t end = ledger.find('\n', start);
    REQUIRE(end != std::string::npos);
    CHECK(committed_json(std::string_view(ledger).substr(start, end - start + 1)));
    start = end + 1;
    ++lines;
  }
  CHECK(lines == 1 + 36);
}
