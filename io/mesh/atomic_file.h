#pragma once
// Atomic file output: a crash never leaves a truncated file under the final name.

#include <string>
#include <string_view>

namespace fabmesh {

/// Writes `bytes` to a temporary file in the folder of `path`, flushes it to
/// disk, then renames it to `path` (replacing any existing file). On failure
/// the temporary file is removed and `path` is untouched.
/// \throw FileError when the folder is not writable or the write fails.
void write_file_atomically(const std::string& path, std::string_view bytes);

/// The whole content of the file at `path`.
/// \throw FileError when it cannot be opened or read.
std::string read_file(const std::string& path);

}  // namespace fabmesh
