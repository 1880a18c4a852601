#pragma once
// The per-process folder of a fuzzer that reads files (fuzz_manifest,
// fuzz_ledger): made once with mkdtemp, reused by every input, removed at exit.

#include <stdlib.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace fabmesh::fuzz {

/// A new empty folder NAME-XXXXXX under $TMPDIR when it is set, else under
/// /dev/shm when there is one (the batch code flushes what it writes to disk:
/// in memory that costs nothing), else under /tmp.
inline std::string make_temp_folder(const char* name) {
  namespace fs = std::filesystem;
  const char* tmp = std::getenv("TMPDIR");
  std::error_code ec;
  const fs::path parent = tmp != nullptr && *tmp != '\0'     ? fs::path(tmp)
                          : fs::is_directory("/dev/shm", ec) ? fs::path("/dev/shm")
                                                             : fs::path("/tmp");
  std::string dir = (parent / (std::string(name) + "-XXXXXX")).string();
  if (::mkdtemp(dir.data()) == nullptr) __builtin_trap();
  return dir;
}

/// This process's folder, made by `make` on first use and removed when the
/// process exits normally (the handler is registered after the path is
/// constructed, so it runs before the path's destructor). A process that
/// crashes (a finding, each run of -minimize_crash) leaves its folder behind.
template <std::string (*make)()>
const std::string& process_folder() {
  static const std::string dir = make();
  static const bool removing = (std::atexit([] {
                                  std::error_code ec;
                                  std::filesystem::remove_all(dir, ec);
                                }),
                                true);
  (void)removing;
  return dir;
}

}  // namespace fabmesh::fuzz
