#pragma once
// Runs the real `fabmesh` executable (FABMESH_BINARY) through the shell and
// captures its standard output: the end-to-end `check` tests.

#include <sys/wait.h>

#include <array>
#include <catch2/catch.hpp>
#include <cstdio>
#include <string>

namespace fabmesh::testing {

/// What one run of the executable did.
struct ShellRun {
  int code = -1;
  std::string out;
};

/// Runs `fabmesh ARGS` (stderr to /dev/null) and returns its exit code and stdout.
inline ShellRun run_in_shell(const std::string& args) {
  const std::string command = std::string("'") + FABMESH_BINARY + "' " + args + " 2>/dev/null";
  ShellRun run;
  FILE* pipe = popen(command.c_str(), "r");
  REQUIRE(pipe != nullptr);
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) run.out.append(buffer.data(), n);
  const int status = pclose(pipe);
  run.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

/// `path` in single quotes, for the shell.
inline std::string quoted(const std::string& path) { return "'" + path + "'"; }

}  // namespace fabmesh::testing
