#pragma once
// Files in and out: bounded reads of regular files, atomic writes.

#include <sys/types.h>

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "geometry/core/errors.h"

namespace fabmesh {

/// The whole content of the regular file at `path`. FIFOs, devices, sockets
/// and folders are refused before any byte is read (reading them could block
/// forever or never end), and the size is checked while reading, so a file
/// larger than `max_bytes` (or one that grows) costs at most max_bytes + 1
/// bytes of memory. `what` names the file's role in messages ("design file").
/// \throw FileError naming the path: missing, unreadable, not a regular file, too large.
std::string read_file(const std::string& path, std::size_t max_bytes, std::string_view what);

/// read_file with no size limit beyond the memory the file needs (for files
/// fabmesh wrote itself). \throw FileError
std::string read_file(const std::string& path);

/// What a file that is not a regular one is, from its st_mode, for
/// messages: "a folder", "a FIFO", "a character device", "a block device",
/// "a socket", or "not a regular file".
const char* file_kind(mode_t mode);

/// True for the errno values a MachineError (geometry/core/errors.h) stands
/// for: writing failed for a reason of the machine, not of the input: the
/// disk or quota is full (ENOSPC, EDQUOT), a file size limit was reached
/// (EFBIG), an I/O error (EIO), or permission is denied (EACCES, EPERM, a
/// read-only filesystem). The same input may succeed once that is fixed: a
/// batch runs such a variant again (exit code 5).
bool is_environment_errno(int error);

/// Throws MachineError when `error` (an errno) is one of the machine's
/// (is_environment_errno), else FileError; the message is "path: what: the
/// system's words".
[[noreturn]] void throw_write_failure(const std::string& path, const std::string& what, int error);

/// One file to write: where, and its bytes.
struct FileWrite {
  std::string path;
  std::string bytes;
};

/// Writes `bytes` to `path` atomically: a temporary file in the same folder
/// (created with the process's umask applied to 0666), flushed to disk, then
/// renamed over `path`. On failure the temporary file is removed and `path`
/// is untouched. Stale temporaries of `path` left by killed runs of fabmesh
/// on this host are removed first; those of writers still running (other
/// threads of this process included) are never touched, so threads may write
/// one path at once (the last rename wins). \throw FileError, MachineError
/// (the machine's failures, a rename that fails included: see commit_files)
void write_file_atomically(const std::string& path, std::string_view bytes);

/// Writes several files all or nothing, as far as the filesystem allows:
/// every file is written to its temporary and flushed before any is renamed
/// into place; when a rename fails, the files already renamed are rolled back
/// (the previous version restored, or the new file removed) before the error
/// is thrown. Only a crash between two renames can leave a mixed set, and no
/// file is ever truncated. \throw FileError or MachineError naming the
/// file that failed (as commit_files)
void write_files_atomically(const std::vector<FileWrite>& files);

/// A file being written atomically, piece by piece: its bytes go to a
/// temporary in the target's folder (created with the process's umask applied
/// to 0666; stale temporaries of the target left by killed runs removed
/// first) and reach `path` only through commit_files or commit_file.
/// Destroying a pending file that was not committed removes its temporary:
/// nothing partial is ever left under `path`. Small pieces are gathered and
/// written a block at a time, so a file may be written a line at a time.
/// Move-only.
class PendingFile {
 public:
  /// Creates the temporary for `path`. \throw FileError
  explicit PendingFile(std::string path);
  ~PendingFile();
  PendingFile(PendingFile&& other) noexcept;
  PendingFile& operator=(PendingFile&& other) = delete;
  PendingFile(const PendingFile&) = delete;
  PendingFile& operator=(const PendingFile&) = delete;

  /// Appends `bytes` (pieces smaller than a block are gathered first).
  /// \throw FileError (the temporary is removed)
  void write(std::string_view bytes);
  /// Flushes the bytes to disk and closes the temporary; no write after it.
  /// \throw FileError (the temporary is removed)
  void finish();
  /// Where the file goes once committed.
  const std::string& path() const { return path_; }

 private:
  friend void commit_files(std::vector<PendingFile>& files);

  /// Finishes `file` and renames it into place: commit_files of one file.
  /// \throw FileError
  void commit_file(PendingFile&& file);
  void discard() noexcept;
  void write_through(std::string_view bytes);
  std::string path_;
  std::string temporary_;  ///< empty once renamed into place or removed
  std::string gathered_;   ///< small pieces not written yet
  int fd_ = -1;
};

/// Renames finished pending files into place all or nothing, as
/// write_files_atomically does (previous versions restored when a rename
/// fails), and makes the renames durable. A rename that fails is the
/// machine's fault (MachineError, exit code 5), except onto a folder of
/// the output's name (FileError: the names asked for clash).
/// \throw MachineError, FileError naming the file that failed, or a file not finished
void commit_files(std::vector<PendingFile>& files);

/// Finishes `file` and renames it into place: commit_files of one file.
/// \throw FileError
void commit_file(PendingFile&& file);

/// The name pattern of the temporary files write_file_atomically uses for
/// `path` (".NAME.tmp-HOST-PID-TOKEN-RANDOM" in the same folder; TOKEN is the
/// process's start time, "s" and its clock ticks after boot, so a later process of
/// the same PID cannot pass for it), for tests: the prefix up to the PID.
std::string temporary_prefix(const std::string& path);

}  // namespace fabmesh
