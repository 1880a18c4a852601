#include "pipeline/batch/streamed_file.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>

#include "geometry/core/errors.h"
#include "io/file.h"

namespace fabmesh {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kBlockBytes = 1u << 20;

[[noreturn]] void fail(const std::string& path, const std::string& what, int error) {
  throw FileError(path, 0, 0, fmt::format("{}: {}: {}", path, what, std::strerror(error)));
}

// Removes the temporaries of `path` whose process (on this host) no longer runs.
void remove_stale(const std::string& path) {
  const fs::path prefix(temporary_prefix(path));
  const std::string start = prefix.filename().string();
  std::error_code ec;
  for (fs::directory_iterator it(prefix.parent_path(), ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.compare(0, start.size(), start) != 0) continue;
    const std::size_t dash = name.find('-', start.size());
    const std::string pid = name.substr(start.size(), dash == std::string::npos ? 0 : dash - start.size());
    if (pid.empty() || pid.find_first_not_of("0123456789") != std::string::npos || pid.size() > 9) continue;
    const auto p = static_cast<pid_t>(std::stol(pid));
    const bool alive = p != ::getpid() && (::kill(p, 0) == 0 || errno == EPERM);
    if (!alive) fs::remove(it->path(), ec);
  }
}

}  // namespace

StreamedFile::StreamedFile(std::string path) : path_(std::move(path)) {
  remove_stale(path_);
  std::random_device entropy;
  for (int attempt = 0; attempt < 64 && fd_ < 0; ++attempt) {
    temp_ = fmt::format("{}{}-{:08x}", temporary_prefix(path_), ::getpid(), entropy());
    fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd_ < 0 && errno != EEXIST) fail(path_, "cannot create a temporary file", errno);
  }
  if (fd_ < 0) fail(path_, "cannot create a temporary file", EEXIST);
  buffer_.reserve(kBlockBytes);
}

StreamedFile::~StreamedFile() {
  if (fd_ >= 0) {
    ::close(fd_);
    std::remove(temp_.c_str());
  }
}

void StreamedFile::append(std::string_view bytes) {
  buffer_ += bytes;
  if (buffer_.size() >= kBlockBytes) flush();
}

void StreamedFile::flush() {
  std::string_view left = buffer_;
  while (!left.empty()) {
    const ssize_t n = ::write(fd_, left.data(), left.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail(path_, "write failed", n < 0 ? errno : EIO);
    left.remove_prefix(static_cast<std::size_t>(n));
  }
  buffer_.clear();
}

void StreamedFile::commit() {
  flush();
  if (::fsync(fd_) != 0) fail(path_, "flush failed", errno);
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) {
    const int error = errno;
    std::remove(temp_.c_str());
    fail(path_, "flush failed", error);
  }
  if (std::rename(temp_.c_str(), path_.c_str()) != 0) {
    const int error = errno;
    std::remove(temp_.c_str());
    fail(path_, "cannot rename the temporary file into place", error);
  }
  const fs::path folder = fs::path(path_).has_parent_path() ? fs::path(path_).parent_path() : fs::path(".");
  const int dir = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir >= 0) {
    ::fsync(dir);
    ::close(dir);
  }
}

}  // namespace fabmesh
