#pragma once
// One file written atomically through a buffer flushed a block at a time:
// batch plans and summaries, too large to hold in memory whole. Unlike
// io/file.h's PendingFile (a set of files renamed together by commit_files)
// it is committed on its own.

#include <string>
#include <string_view>

namespace fabmesh {

/// Writes `path` through a temporary in its folder (the name pattern of
/// io/file.h's temporary_prefix), renamed into place by commit(); destroyed
/// uncommitted, it removes the temporary and leaves `path` untouched.
/// Temporaries of `path` that killed processes of this host left are removed first.
class StreamedFile {
 public:
  /// \throw FileError when the temporary cannot be created
  explicit StreamedFile(std::string path);
  ~StreamedFile();
  StreamedFile(const StreamedFile&) = delete;
  StreamedFile& operator=(const StreamedFile&) = delete;

  /// Appends `bytes` (buffered: written a block at a time). \throw FileError
  void append(std::string_view bytes);
  /// Flushes to disk and renames the temporary into place. \throw FileError
  void commit();

 private:
  void flush();

  std::string path_, temp_;
  std::string buffer_;
  int fd_ = -1;
};

}  // namespace fabmesh
