#pragma once
// Runs the real `fabmesh` executable (FABMESH_BINARY) through the shell and
// captures its standard output: the end-to-end `check` tests.

#include <catch2/catch.hpp>
#include <string>

#include "tests/io/mesh/external_tool.h"

namespace fabmesh::testing {

/// What one run of the executable did.
struct ShellRun {
  int code = -1;
  std::string out;
};

/// Runs `fabmesh ARGS` (stderr to /dev/null) and returns its exit code and stdout.
inline ShellRun run_in_shell(const std::string& args) {
  const test::ToolRun run =
      test::run_command(std::string("'") + FABMESH_BINARY + "' " + args + " 2>/dev/null");
  return {run.code, run.output};
}

using test::quoted;

}  // namespace fabmesh::testing
