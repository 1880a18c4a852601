#pragma once
// Test helper: headless Chromium, run offline with a fresh profile per call.

#include <sys/wait.h>

#include <array>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "tests/io/mesh/temp_dir.h"

namespace fabmesh::test {

/// True when a `chromium` executable is on the PATH.
inline bool chromium_available() { return std::system("command -v chromium > /dev/null 2>&1") == 0; }

struct ChromiumRun {
  int code = -1;
  std::string out;  ///< stdout (e.g. --dump-dom)
  std::string err;  ///< stderr (logging, console messages)
};

/// Runs `chromium --headless ARGS URL` with networking, sync and component
/// updates off and a fresh profile; `args` are already quoted for the shell.
inline ChromiumRun run_chromium(const std::string& args, const std::string& url) {
  const TempDir profile;
  const std::string err_path = profile.file("stderr.txt");
  const std::string command =
      "chromium --headless --no-sandbox --disable-gpu --disable-background-networking "
      "--disable-component-update --disable-sync --no-first-run --no-default-browser-check "
      "--hide-scrollbars --user-data-dir='" +
      profile.file("profile") + "' " + args + " '" + url + "' 2>'" + err_path + "'";
  ChromiumRun run;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return run;
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) run.out.append(buffer.data(), n);
  const int status = pclose(pipe);
  run.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::FILE* err = std::fopen(err_path.c_str(), "rb");
  if (err != nullptr) {
    while ((n = fread(buffer.data(), 1, buffer.size(), err)) > 0) run.err.append(buffer.data(), n);
    std::fclose(err);
  }
  return run;
}

/// file:// URL of an absolute path (characters outside [A-Za-z0-9/._-] percent-encoded).
inline std::string file_url(const std::string& path) {
  std::string url = "file://";
  const std::string abs = std::filesystem::absolute(path).string();
  for (const char c : abs) {
    const auto u = static_cast<unsigned char>(c);
    if (std::isalnum(u) || c == '/' || c == '.' || c == '_' || c == '-') {
      url += c;
    } else {
      static const char* hex = "0123456789ABCDEF";
      url += '%';
      url += hex[u >> 4];
      url += hex[u & 15];
    }
  }
  return url;
}

}  // namespace fabmesh::test
