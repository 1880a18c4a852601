#include "io/file.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <tuple>
#include <utility>

#include "geometry/core/errors.h"

namespace fabmesh {
namespace {

namespace fs = std::filesystem;

// Pieces smaller than this are gathered before they are written.
constexpr std::size_t kBlockBytes = std::size_t{1} << 20;

[[noreturn]] void fail(const std::string& path, const std::string& what, int error) {
  const std::string message = fmt::format("{}: {}: {}", path, what, std::strerror(error));
  if (error == ENOENT) throw MissingFileError(path, 0, 0, message);
  throw FileError(path, 0, 0, message);
}

// Closes a descriptor on every path out of a scope.
class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  ~Descriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

std::string read_bounded(const std::string& path, std::size_t max_bytes, std::string_view what) {
  // O_NONBLOCK: opening a FIFO must not wait for a writer before fstat can refuse it.
  Descriptor fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY));
  if (fd.get() < 0) fail(path, fmt::format("cannot open the {}", what), errno);
  struct stat st {};
  if (::fstat(fd.get(), &st) != 0) fail(path, fmt::format("cannot inspect the {}", what), errno);
  if (!S_ISREG(st.st_mode)) {
    throw FileError(path, 0, 0,
                    fmt::format("{}: the {} is {}, not a regular file", path, what, file_kind(st.st_mode)));
  }
  auto too_large = [&]() {
    return FileError(path, 0, 0, fmt::format("{}: the {} is larger than {} bytes", path, what, max_bytes));
  };
  if (static_cast<std::size_t>(st.st_size) > max_bytes) throw too_large();
  std::string bytes;
  bytes.reserve(static_cast<std::size_t>(st.st_size));
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd.get(), buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail(path, fmt::format("cannot read the {}", what), errno);
    if (n == 0) break;
    if (bytes.size() + static_cast<std::size_t>(n) > max_bytes) throw too_large();
    bytes.append(buffer, static_cast<std::size_t>(n));
  }
  return bytes;
}

// The host name as it may appear in a file name.
std::string host_tag() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "host";
  std::string tag;
  for (const char* c = name; *c != '\0' && tag.size() < 32; ++c) {
    const bool plain = (*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9');
    tag += plain ? *c : '_';
  }
  return tag.empty() ? "host" : tag;
}

// The token naming this process in its temporaries, with its PID: its start
// time ("s" and clock ticks after boot, as /proc/PID/stat gives it), which
// no later process of the same PID shares; "r" and random digits where /proc
// cannot tell.
std::string start_token(pid_t pid) {
  std::string stat;
  try {
    stat = read_bounded(fmt::format("/proc/{}/stat", pid), 4096, "process status");
  } catch (const FileError&) {
    return "";
  }
  // Fields after the command's closing parenthesis: 3 (state) ... 22 (starttime).
  const std::size_t close = stat.rfind(')');
  if (close == std::string::npos) return "";
  std::size_t at = close + 1;
  for (int field = 3; field < 22 && at != std::string::npos; ++field) at = stat.find(' ', at + 1);
  if (at == std::string::npos) return "";
  const std::size_t end = stat.find(' ', at + 1);
  const std::string ticks = stat.substr(at + 1, end == std::string::npos ? std::string::npos : end - at - 1);
  if (ticks.empty() || ticks.find_first_not_of("0123456789") != std::string::npos) return "";
  return "s" + ticks;
}

const std::string& own_token() {
  static const std::string token = [] {
    const std::string start = start_token(::getpid());
    return start.empty() ? fmt::format("r{:08x}", std::random_device()()) : start;
  }();
  return token;
}

// Whether a temporary named for process `pid` and `token` ("" in names
// without one, of fabmesh before 0.3) may be written still. A live writer is
// never stale: this process's own temporaries (another thread's, or a
// pending file's) carry its token. A process that no longer runs, or whose
// PID now names a later process (another start time), left its file behind.
bool writer_alive(long pid, const std::string& token) {
  if (pid == ::getpid()) return token == own_token();
  const bool running = ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
  if (!running) return false;
  if (token.empty() || token[0] != 's') return true;
  const std::string now = start_token(static_cast<pid_t>(pid));
  return now.empty() || now == token;
}

// Removes temporaries of `path` left behind by fabmesh processes of this
// host that no longer run (killed mid-write). Others' files, and those of
// writers still running (this process's other threads included), are never touched.
void remove_stale_temporaries(const std::string& path) {
  const fs::path target(path);
  const fs::path folder = target.has_parent_path() ? target.parent_path() : ".";
  const std::string prefix = "." + target.filename().string() + ".tmp-" + host_tag() + "-";
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.compare(0, prefix.size(), prefix) != 0) continue;
    // PID-TOKEN-RANDOM, or PID-RANDOM (no token).
    const std::size_t dash = name.find('-', prefix.size());
    if (dash == std::string::npos) continue;
    const std::string pid_text = name.substr(prefix.size(), dash - prefix.size());
    if (pid_text.empty() || pid_text.size() > 9 ||
        pid_text.find_first_not_of("0123456789") != std::string::npos)
      continue;
    const std::size_t next = name.find('-', dash + 1);
    std::string token =
        name.substr(dash + 1, next == std::string::npos ? std::string::npos : next - dash - 1);
    if (token.empty() || (token[0] != 's' && token[0] != 'r')) token.clear();
    if (!writer_alive(std::stol(pid_text), token)) fs::remove(it->path(), ec);
  }
}

// Creates the temporary file for `path`: the umask applies to 0666.
std::pair<std::string, int> create_temporary(const std::string& path) {
  std::random_device entropy;
  for (int attempt = 0; attempt < 64; ++attempt) {
    const std::string temp =
        fmt::format("{}{}-{}-{:08x}", temporary_prefix(path), ::getpid(), own_token(), entropy());
    const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) return {temp, fd};
    if (errno != EEXIST) throw_write_failure(path, "cannot create a temporary file", errno);
  }
  fail(path, "cannot create a temporary file", EEXIST);
}

// A temporary that cannot be renamed into place: the machine's fault (the
// temporary gone, the folder changed, an I/O error), never the input's,
// unless the output's name is taken by a folder: the names asked for clash.
[[noreturn]] void rename_failed(const std::string& path, bool several, int error) {
  const std::string message =
      fmt::format("{}: cannot rename the temporary file into place{}: {}", path,
                  several ? " (no output of this job was kept)" : "", std::strerror(error));
  if (error == EISDIR) throw FileError(path, 0, 0, message + " (a folder has the output's name)");
  throw MachineError(path, error, message);
}

// Makes the renames in a folder durable.
void sync_folder(const std::string& path) {
  const fs::path target(path);
  const std::string folder = target.has_parent_path() ? target.parent_path().string() : ".";
  Descriptor fd(::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  if (fd.get() >= 0) ::fsync(fd.get());
}

}  // namespace

bool is_environment_errno(int error) {
  switch (error) {
    case ENOSPC:
    case EDQUOT:
    case EFBIG:
    case EIO:
    case EACCES:
    case EPERM:
    case EROFS:
      return true;
    default:
      return false;
  }
}

void throw_write_failure(const std::string& path, const std::string& what, int error) {
  const std::string message = fmt::format("{}: {}: {}", path, what, std::strerror(error));
  if (is_environment_errno(error)) throw MachineError(path, error, message);
  throw FileError(path, 0, 0, message);
}

const char* file_kind(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

std::string temporary_prefix(const std::string& path) {
  const fs::path target(path);
  const fs::path folder = target.has_parent_path() ? target.parent_path() : ".";
  return (folder / ("." + target.filename().string() + ".tmp-" + host_tag() + "-")).string();
}

std::string read_file(const std::string& path, std::size_t max_bytes, std::string_view what) {
  return read_bounded(path, max_bytes, what);
}

std::string read_file(const std::string& path) { return read_bounded(path, SIZE_MAX - 1, "file"); }

PendingFile::PendingFile(std::string path) : path_(std::move(path)) {
  remove_stale_temporaries(path_);
  std::tie(temporary_, fd_) = create_temporary(path_);
}

PendingFile::PendingFile(PendingFile&& other) noexcept
    : path_(std::move(other.path_)),
      temporary_(std::move(other.temporary_)),
      gathered_(std::move(other.gathered_)),
      fd_(other.fd_) {
  other.temporary_.clear();
  other.gathered_.clear();
  other.fd_ = -1;
}

PendingFile::~PendingFile() { discard(); }

void PendingFile::discard() noexcept {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (!temporary_.empty()) std::remove(temporary_.c_str());
  temporary_.clear();
  gathered_ = std::string();
}

void PendingFile::write(std::string_view bytes) {
  if (fd_ < 0) throw FileError(path_, 0, 0, fmt::format("{}: written after it was finished", path_));
  if (gathered_.size() + bytes.size() < kBlockBytes) {
    gathered_ += bytes;
    return;
  }
  write_through(gathered_);
  gathered_.clear();
  write_through(bytes);
}

void PendingFile::write_through(std::string_view bytes) {
  const char* data = bytes.data();
  std::size_t left = bytes.size();
  while (left > 0) {
    const ssize_t n = ::write(fd_, data, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int error = n < 0 ? errno : EIO;
      discard();
      throw_write_failure(path_, "write failed", error);
    }
    data += n;
    left -= static_cast<std::size_t>(n);
  }
}

void PendingFile::finish() {
  if (fd_ < 0) throw FileError(path_, 0, 0, fmt::format("{}: finished twice", path_));
  write_through(gathered_);
  gathered_ = std::string();
  int error = ::fsync(fd_) == 0 ? 0 : errno;
  const int close_error = ::close(fd_) == 0 ? 0 : errno;
  fd_ = -1;
  if (error == 0) error = close_error;
  if (error != 0) {
    discard();
    throw_write_failure(path_, "flush failed", error);
  }
}

void commit_files(std::vector<PendingFile>& files) {
  for (const PendingFile& f : files) {
    if (f.fd_ >= 0 || f.temporary_.empty())
      throw FileError(f.path_, 0, 0, fmt::format("{}: committed before it was finished", f.path_));
  }
  // Keep the previous version of each target (a hard link) until every rename
  // succeeded; a single file needs none: its one rename is atomic.
  std::vector<std::string> backups(files.size());
  for (std::size_t i = 0; i < files.size() && files.size() > 1; ++i) {
    struct stat st {};
    if (::lstat(files[i].path_.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) continue;
    const std::string backup = files[i].temporary_ + "-previous";
    if (::link(files[i].path_.c_str(), backup.c_str()) == 0) backups[i] = backup;
  }
  auto remove_backups = [&]() {
    for (const std::string& b : backups)
      if (!b.empty()) std::remove(b.c_str());
  };
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (std::rename(files[i].temporary_.c_str(), files[i].path_.c_str()) == 0) {
      files[i].temporary_.clear();
      continue;
    }
    const int error = errno;
    for (std::size_t j = 0; j < i; ++j) {  // roll back what is already in place
      if (!backups[j].empty()) {
        std::rename(backups[j].c_str(), files[j].path_.c_str());
        backups[j].clear();
      } else {
        std::remove(files[j].path_.c_str());
      }
    }
    remove_backups();
    for (PendingFile& f : files) f.discard();  // the temporaries not renamed
    rename_failed(files[i].path_, files.size() > 1, error);
  }
  remove_backups();
  for (const PendingFile& f : files) sync_folder(f.path_);
}

void commit_file(PendingFile&& file) {
  std::vector<PendingFile> files;
  files.push_back(std::move(file));
  files.back().finish();
  commit_files(files);
}

void write_file_atomically(const std::string& path, std::string_view bytes) {
  PendingFile file(path);
  file.write(bytes);
  commit_file(std::move(file));
}

void write_files_atomically(const std::vector<FileWrite>& files) {
  std::vector<PendingFile> pending;
  pending.reserve(files.size());
  for (const FileWrite& f : files) {
    pending.emplace_back(f.path);
    pending.back().write(f.bytes);
    pending.back().finish();
  }
  commit_files(pending);
}

}  // namespace fabmesh
