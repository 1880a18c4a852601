#pragma once
// Runs the real `fabmesh` binary in a child process with an address-space
// limit and a wall-clock deadline enforced here, so a regression that would
// take minutes or gigabytes fails the test quickly instead of hanging it.

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace fabmesh::testing {

struct ChildResult {
  int code = -1;           ///< exit code; -1 when killed or signalled
  bool timed_out = false;  ///< killed at the deadline
  bool signalled = false;  ///< ended by a signal (e.g. out of memory under the limit)
  double seconds = 0.0;    ///< wall time
  std::string output;      ///< standard output and error
};

/// Runs FABMESH_BINARY with `args`, at most `memory_bytes` of address space
/// (RLIMIT_AS) and `seconds` of wall time (then SIGKILL), output to `log`.
inline ChildResult run_limited(const std::vector<std::string>& args, std::size_t memory_bytes, double seconds,
                               const std::string& log) {
  ChildResult r;
  const auto start = std::chrono::steady_clock::now();
  std::fflush(stdout);  // the child must not repeat what the test runner buffered
  std::fflush(stderr);
  const pid_t pid = fork();
  if (pid == 0) {
    const rlimit limit{memory_bytes, memory_bytes};
    setrlimit(RLIMIT_AS, &limit);
    std::FILE* out = std::freopen(log.c_str(), "w", stdout);
    if (out == nullptr || dup2(fileno(stdout), fileno(stderr)) < 0) _exit(126);
    std::vector<char*> argv;
    std::string binary = FABMESH_BINARY;
    argv.push_back(binary.data());
    std::vector<std::string> copies = args;
    for (std::string& a : copies) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(binary.c_str(), argv.data());
    _exit(127);
  }
  if (pid < 0) return r;
  int status = 0;
  for (;;) {
    const pid_t done = waitpid(pid, &status, WNOHANG);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (done == pid) break;
    if (r.seconds > seconds) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      r.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (WIFEXITED(status) && !r.timed_out) r.code = WEXITSTATUS(status);
  r.signalled = WIFSIGNALED(status) && !r.timed_out;
  std::ifstream in(log);
  std::ostringstream text;
  text << in.rdbuf();
  r.output = text.str();
  return r;
}

}  // namespace fabmesh::testing
