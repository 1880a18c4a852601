#pragma once
// Runs the real `fabmesh` executable (FABMESH_BINARY) in a child process
// under limits the test enforces, not luck: a wall-clock deadline (the child
// is killed with SIGKILL when it passes) and a memory bound (RLIMIT_AS, or
// under AddressSanitizer, whose shadow memory needs terabytes of address
// space, ASan's own hard_rss_limit_mb). A test that hangs or blows memory
// then fails with a clear result instead of stalling the suite.

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#if defined(__SANITIZE_ADDRESS__)
#define FABMESH_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define FABMESH_TEST_ASAN 1
#endif
#endif

namespace fabmesh::testing {

/// How a limited run ended.
struct LimitedRun {
  int code = -1;           ///< exit status, -1 when killed by a signal
  int signal = 0;          ///< the signal that ended it (0 when it exited)
  bool timed_out = false;  ///< killed at the deadline
  double seconds = 0.0;    ///< wall time until it ended (or was killed)
  std::string out, err;    ///< standard output and error

  /// "exit 2", "killed by signal 9 (timed out)": for failure messages.
  std::string describe() const {
    std::ostringstream s;
    if (timed_out) {
      s << "timed out after " << seconds << " s";
    } else if (signal != 0) {
      s << "killed by signal " << signal;
    } else {
      s << "exit " << code << " after " << seconds << " s";
    }
    s << "\nstdout: " << out.substr(0, 2000) << "\nstderr: " << err.substr(0, 2000);
    return s.str();
  }
};

namespace detail {
inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}
}  // namespace detail

/// The deadline of a limited run is a hang guard, not a speed claim: under
/// AddressSanitizer, which runs the program several times slower, it is
/// four times as long (the suite without sanitizers keeps the figures given).
#ifdef FABMESH_TEST_ASAN
constexpr double kHangGuardScale = 4.0;
#else
constexpr double kHangGuardScale = 1.0;
#endif

/// Runs `FABMESH_BINARY args...` with at most `seconds` of wall time and
/// `bytes` of memory, in working directory `cwd` (empty: the test's), with
/// standard input from /dev/null. `shell_prefix`, when given, runs the program through `sh -c 'PREFIX "$@"'`
/// (e.g. "umask 027;").
inline LimitedRun run_limited(const std::vector<std::string>& args, double seconds, std::size_t bytes,
                              const std::string& cwd = "", const std::string& shell_prefix = "") {
  static int counter = 0;
  const std::string base = std::filesystem::path(FABMESH_TEST_TMP) /
                           ("limited-run-" + std::to_string(::getpid()) + "-" + std::to_string(++counter));
  const std::string out_path = base + ".out", err_path = base + ".err";
  std::vector<std::string> argv_text;
  if (!shell_prefix.empty()) {
    argv_text = {"/bin/sh", "-c", shell_prefix + " exec \"$0\" \"$@\"", FABMESH_BINARY};
  } else {
    argv_text = {FABMESH_BINARY};
  }
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);
  // The environment is made before fork: the child only calls async-signal-safe functions.
  std::vector<std::string> env_text;
  for (char** e = environ; *e != nullptr; ++e) env_text.emplace_back(*e);
#ifdef FABMESH_TEST_ASAN
  env_text.push_back("ASAN_OPTIONS=hard_rss_limit_mb=" + std::to_string(bytes >> 20));
#endif
  std::vector<char*> envp;
  for (std::string& e : env_text) envp.push_back(e.data());
  envp.push_back(nullptr);
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid == 0) {
    // The child: only async-signal-safe calls until exec.
    const int in = ::open("/dev/null", O_RDONLY);
    const int out = ::open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = ::open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (in < 0 || out < 0 || err < 0) ::_exit(126);
    ::dup2(in, 0);
    ::dup2(out, 1);
    ::dup2(err, 2);
    if (!cwd.empty() && ::chdir(cwd.c_str()) != 0) ::_exit(126);
#ifndef FABMESH_TEST_ASAN
    const rlimit limit{bytes, bytes};
    if (::setrlimit(RLIMIT_AS, &limit) != 0) ::_exit(126);
#endif
    ::execve(argv[0], argv.data(), envp.data());
    ::_exit(127);
  }
  LimitedRun run;
  if (pid < 0) {
    run.err = "fork failed";
    return run;
  }
  int status = 0;
  for (;;) {
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (done == pid) break;
    if (run.seconds > seconds * kHangGuardScale) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      run.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (WIFEXITED(status)) run.code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) run.signal = WTERMSIG(status);
  run.out = detail::slurp(out_path);
  run.err = detail::slurp(err_path);
  std::filesystem::remove(out_path);
  std::filesystem::remove(err_path);
  return run;
}

/// 1 MiB, for memory bounds.
constexpr std::size_t kMiB = std::size_t{1} << 20;

}  // namespace fabmesh::testing
