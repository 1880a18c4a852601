#pragma once
// Running the real consumers of fabmesh's files (PrusaSlicer, OpenSCAD, the
// Khronos glTF validator under node, draco_encoder/draco_decoder) from tests.

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>

namespace fabmesh::test {

/// What one external command did.
struct ToolRun {
  int code = -1;       ///< exit status, -1 when it did not exit normally
  std::string output;  ///< standard output and standard error, interleaved
};

/// Runs `command` with /bin/sh as it is: its standard output and exit status.
inline ToolRun run_command(const std::string& command) {
  ToolRun run;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return run;
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) run.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  run.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

/// Runs `command` with /bin/sh, standard error joined to standard output.
inline ToolRun run_tool(const std::string& command) { return run_command(command + " 2>&1"); }

/// True when `program` is an executable on PATH.
inline bool on_path(const std::string& program) {
  return run_tool("command -v '" + program + "' >/dev/null").code == 0;
}

/// `path` in single quotes for /bin/sh.
inline std::string quoted(const std::string& path) { return "'" + path + "'"; }

/// The command that validates a glTF/GLB file with the Khronos validator.
inline std::string gltf_validator_command(const std::string& file) {
  return "node " + quoted(std::string(FABMESH_SOURCE_DIR) + "/tools/node/validate-gltf.js") + " " +
         quoted(file);
}

/// True when node and the validator package (scripts/install-deps.sh --test) are there.
inline bool gltf_validator_installed() {
  return on_path("node") && run_tool("test -d " + quoted(std::string(FABMESH_SOURCE_DIR) +
                                                         "/tools/node/node_modules/gltf-validator"))
                                    .code == 0;
}

/// `prusa-slicer ARGS` headless, with a private HOME and data folder `home`.
inline ToolRun prusa_slicer(const std::string& home, const std::string& args) {
  std::filesystem::create_directories(home);
  return run_tool("HOME=" + quoted(home) + " prusa-slicer --datadir " + quoted(home) + " --loglevel 1 " +
                  args);
}

/// The "key = value" lines of `prusa-slicer --info FILE` (size_x, manifold, volume, ...);
/// `run` receives the whole run.
inline std::map<std::string, std::string> prusa_info(const std::string& home, const std::string& file,
                                                     ToolRun* run = nullptr) {
  const ToolRun r = prusa_slicer(home, "--info " + quoted(file));
  if (run != nullptr) *run = r;
  std::map<std::string, std::string> info;
  std::istringstream lines(r.output);
  for (std::string l; std::getline(lines, l);) {
    const std::size_t eq = l.find(" = ");
    if (eq == std::string::npos) continue;
    std::string key = l.substr(0, eq), value = l.substr(eq + 3);
    key.erase(0, key.find_first_not_of(" \t"));
    value.erase(0, value.find_first_not_of(' '));
    while (!value.empty() && (value.back() == ' ' || value.back() == '\r')) value.pop_back();
    if (!key.empty() && key.find(' ') == std::string::npos) info[key] = value;
  }
  return info;
}

}  // namespace fabmesh::test

/// Fails the test (never skips it) when `program` is missing.
#define REQUIRE_PROGRAM(program)                                                                          \
  do {                                                                                                    \
    INFO("this test runs " << (program) << ", which is not on PATH: run scripts/install-deps.sh --test"); \
    REQUIRE(fabmesh::test::on_path(program));                                                             \
  } while (false)
