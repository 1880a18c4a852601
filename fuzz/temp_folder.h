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

/// Removes the folder `folder()` names when the process exits normally.
/// Call it after the static that holds the path is constructed, so that the
/// handler runs before the path's destructor. A process that crashes (a
/// finding, each run of -minimize_crash) leaves its folder behind.
template <const std::string& (*folder)()>
void remove_at_exit() {
  std::atexit([] {
    std::error_code ec;
    std::filesystem::remove_all(folder(), ec);
  });
}

}  // namespace fabmesh::fuzz
