#include "pipeline/batch/ledger.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>

#include "geometry/core/errors.h"
#include "io/design/manifest.h"
#include "io/file.h"
#include "pipeline/batch/output_links.h"
#include "pipeline/batch/sha256.h"

namespace fabmesh {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kCheckDigits = 16;

// The ledger is the batch's own file: a failure to use it is the machine's
// (disk full, permission: MachineError) or, rarely, the folder's (FileError).
[[noreturn]] void fail(const std::string& path, const std::string& what, int error) {
  throw_write_failure(path, what, error);
}

// Opens the ledger `path` with `flags`, only when it is a regular file: a
// link is not followed (O_NOFOLLOW: writing through it would truncate its
// target) and a FIFO, device or socket is refused before any byte is read
// (O_NONBLOCK: opening a FIFO does not wait for a writer).
int open_ledger(const std::string& path, int flags) {
  const int fd = ::open(path.c_str(), flags | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC, 0666);
  if (fd < 0 && errno == ELOOP) {
    throw FileError(path, 0, 0,
                    fmt::format("{}: the ledger is a symbolic link, not a regular file: fabmesh reads and "
                                "writes only its own files in a batch folder; remove it",
                                path));
  }
  if (fd < 0) fail(path, "cannot open the ledger", errno);
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const int error = errno;
    ::close(fd);
    fail(path, "cannot inspect the ledger", error);
  }
  if (!S_ISREG(st.st_mode)) {
    ::close(fd);
    throw FileError(path, 0, 0,
                    fmt::format("{}: the ledger is {}, not a regular file: fabmesh reads and writes only its "
                                "own files in a batch folder; remove it",
                                path, file_kind(st.st_mode)));
  }
  return fd;
}

std::string header_json(const LedgerHeader& h) {
  nlohmann::ordered_json j;
  j["fabmesh_batch_ledger"] = 1;
  j["plan"] = h.plan;
  j["variants"] = h.variants;
  j["shard"] = h.shard.index;
  j["shards"] = h.shard.count;
  j["fabmesh"] = FABMESH_VERSION;
  return j.dump();
}

// The whole number `key` of `j` when it is in [0, max]. Not get<std::size_t>:
// it casts any number, and 1e300 beyond size_t's range is undefined behaviour.
std::optional<std::size_t> count_field(const nlohmann::json& j, const char* key, std::size_t max) {
  const auto it = j.find(key);
  if (it == j.end() || !it->is_number_unsigned() || it->get<std::uint64_t>() > max) return std::nullopt;
  return it->get<std::size_t>();
}

// The header, or nothing when `json` is not one fabmesh writes: a merge sizes
// its per-shard tallies by the shard count, so that is bounded as --shard's is.
std::optional<LedgerHeader> parse_header(std::string_view json) {
  const nlohmann::json j = nlohmann::json::parse(json, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("fabmesh_batch_ledger")) return std::nullopt;
  const auto plan = j.find("plan");
  const std::optional<std::size_t> variants = count_field(j, "variants", kMaxBatchVariants);
  const std::optional<std::size_t> index = count_field(j, "shard", kMaxShards);
  const std::optional<std::size_t> shards = count_field(j, "shards", kMaxShards);
  if (plan == j.end() || !plan->is_string() || !variants || !index || !shards || *shards == 0 ||
      *index >= *shards)
    return std::nullopt;
  return LedgerHeader{plan->get<std::string>(), *variants, {*index, *shards}};
}

// The longest line a ledger can hold: the longest row, its tab, check and newline.
constexpr std::size_t kMaxLineBytes = kMaxLedgerRowBytes + kCheckDigits + 2;

// Calls `each(json, offset)` for the committed lines of the file at `path`, read
// a block at a time, while it returns true. Every byte is searched for a line
// end once, and a line longer than any ledger line is refused as corruption
// as soon as it is seen: time linear in the file, memory bounded by kMaxLineBytes.
template <class Each>
void each_committed_in_file(const std::string& path, Each each) {
  const int fd = open_ledger(path, O_RDONLY);
  std::string pending;           // the start of a line the last block did not end
  std::uint64_t pending_at = 0;  // its offset in the file
  char buffer[1 << 16];
  for (off_t offset = 0;;) {
    const ssize_t n = ::pread(fd, buffer, sizeof buffer, offset);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int error = errno;
      ::close(fd);
      fail(path, "cannot read the ledger", error);
    }
    if (n == 0) break;  // what is pending is a torn last line
    offset += n;
    pending.append(buffer, static_cast<std::size_t>(n));
    std::size_t start = 0;
    const std::size_t fresh = pending.size() - static_cast<std::size_t>(n);  // searched before
    for (std::size_t newline; (newline = pending.find('\n', std::max(start, fresh))) != std::string::npos;
         start = newline + 1) {
      const auto json = committed_json(std::string_view(pending).substr(start, newline - start + 1));
      if (json && !each(*json, pending_at + start)) {
        ::close(fd);
        return;
      }
    }
    pending.erase(0, start);
    pending_at += start;
    if (pending.size() > kMaxLineBytes) {
      ::close(fd);
      throw FileError(path, 0, 0,
                      fmt::format("{}: the ledger is corrupt: the line at byte {} runs over {} bytes without "
                                  "ending, longer than any ledger line can be ({} at most); move the file "
                                  "away (its shard's variants then run again)",
                                  path, pending_at, pending.size(), kMaxLineBytes));
    }
  }
  ::close(fd);
}

void write_all(int fd, std::string_view bytes, const std::string& path) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail(path, "cannot append to the ledger", n < 0 ? errno : EIO);
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
}

// Opens and locks `path`; -1 with errno EWOULDBLOCK when another process holds it.
int open_locked(const std::string& path) {
  const int fd = open_ledger(path, O_RDWR | O_CREAT | O_APPEND);
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    ::close(fd);
    if (error == EWOULDBLOCK) {
      errno = EWOULDBLOCK;
      return -1;
    }
    fail(path, "cannot lock the ledger", error);
  }
  return fd;
}

// A free name for a ledger of plan `digest` moved aside.
std::string aside_name(const std::string& path, const std::string& digest) {
  const std::string stem = path.substr(0, path.size() - std::string(".jsonl").size());
  std::string name = fmt::format("{}.{}.jsonl", stem, digest.substr(0, 16));
  for (int k = 2; fs::exists(name); ++k) name = fmt::format("{}.{}-{}.jsonl", stem, digest.substr(0, 16), k);
  return name;
}

}  // namespace

std::string ledger_line(std::string_view json) {
  std::string line(json);
  line += '\t';
  line += sha256_hex(json).substr(0, kCheckDigits);
  line += '\n';
  return line;
}

std::optional<std::string_view> committed_json(std::string_view line) {
  if (line.empty() || line.back() != '\n') return std::nullopt;
  line.remove_suffix(1);
  const std::size_t tab = line.rfind('\t');
  if (tab == std::string_view::npos || line.size() - tab - 1 != kCheckDigits) return std::nullopt;
  const std::string_view json = line.substr(0, tab);
  if (sha256_hex(json).compare(0, kCheckDigits, line.substr(tab + 1)) != 0) return std::nullopt;
  return json;
}

std::string ledger_name(const Shard& s) { return "ledger-" + s.tag() + ".jsonl"; }

LedgerWriter::LedgerWriter(const std::string& folder, const LedgerHeader& header)
    : path_((fs::path(folder) / ledger_name(header.shard)).string()) {
  refuse_link(folder, "batch folder");
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) fail(folder, "cannot create the folder", ec.value());
  fd_ = open_locked(path_);
  if (fd_ < 0) {
    throw InputError(
        fmt::format("{}: another fabmesh batch is running shard {}/{} into this folder (its ledger is "
                    "locked); wait for it or use another -o",
                    path_, header.shard.index, header.shard.count));
  }
  // The header (the first line) and the end of the last committed line, read a block at a time.
  std::optional<LedgerHeader> found;
  std::uint64_t keep = 0;
  const auto scan = [&] {
    found.reset();
    keep = 0;
    each_committed_in_file(path_, [&](std::string_view json, std::uint64_t offset) {
      if (offset == 0) found = parse_header(json);
      if (!found) return false;                        // not a ledger: begun anew below
      keep = offset + json.size() + kCheckDigits + 2;  // the tab, the check, the newline
      return true;
    });
  };
  scan();
  if (found && found->plan != header.plan) {
    // Another plan's rows stay readable beside the new ledger.
    const std::string aside = aside_name(path_, found->plan);
    if (std::rename(path_.c_str(), aside.c_str()) != 0)
      fail(path_, "cannot move the old ledger aside", errno);
    ::close(fd_);
    fd_ = open_locked(path_);
    if (fd_ < 0) throw InputError(fmt::format("{}: another fabmesh batch took this ledger", path_));
    scan();
  }
  // Without a committed header the file holds nothing usable; else cut a torn tail.
  struct stat st {};
  if (::fstat(fd_, &st) != 0) fail(path_, "cannot read the size of the ledger", errno);
  if (!found) keep = 0;
  if (keep != static_cast<std::uint64_t>(st.st_size) && ::ftruncate(fd_, static_cast<off_t>(keep)) != 0) {
    fail(path_, "cannot cut the torn end of the ledger", errno);
  }
  if (!found) write_all(fd_, ledger_line(header_json(header)), path_);
  const off_t end = ::lseek(fd_, 0, SEEK_END);
  if (end < 0) fail(path_, "cannot find the end of the ledger", errno);
  size_ = static_cast<std::uint64_t>(end);
}

LedgerWriter::~LedgerWriter() {
  if (fd_ >= 0) ::close(fd_);
}

std::uint64_t LedgerWriter::append(std::string_view json) {
  const std::string line = ledger_line(json);
  std::lock_guard<std::mutex> lock(writing_);
  write_all(fd_, line, path_);
  const std::uint64_t offset = size_;
  size_ += line.size();
  return offset;
}

void LedgerWriter::sync() {
  std::lock_guard<std::mutex> lock(writing_);
  if (::fdatasync(fd_) != 0) fail(path_, "cannot flush the ledger", errno);
}

std::vector<LedgerFile> list_ledgers(const std::string& folder) {
  static const std::regex current(R"(ledger-[0-9]+-of-[0-9]+\.jsonl)");
  static const std::regex any(R"(ledger-[0-9]+-of-[0-9]+\..*\.jsonl)");
  struct Found {
    LedgerFile file;
    fs::file_time_type time;
  };
  std::vector<Found> found;
  refuse_link(folder, "batch folder");
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const bool is_current = std::regex_match(name, current);
    if (!is_current && !std::regex_match(name, any)) continue;
    std::error_code time_ec;
    Found f{{it->path().string(), is_current, std::nullopt}, fs::last_write_time(it->path(), time_ec)};
    // The header is the first line: read no further.
    each_committed_in_file(f.file.path, [&](std::string_view json, std::uint64_t) {
      f.file.header = parse_header(json);
      return false;
    });
    found.push_back(std::move(f));
  }
  std::sort(found.begin(), found.end(), [](const Found& a, const Found& b) {
    if (a.file.current != b.file.current) return !a.file.current;
    if (a.time != b.time) return a.time < b.time;
    return a.file.path < b.file.path;
  });
  std::vector<LedgerFile> out;
  out.reserve(found.size());
  for (Found& f : found) out.push_back(std::move(f.file));
  return out;
}

void for_each_row(const LedgerFile& file,
                  const std::function<void(std::string_view json, std::uint64_t offset)>& row) {
  bool header = true;
  each_committed_in_file(file.path, [&](std::string_view json, std::uint64_t offset) {
    if (!(header && parse_header(json))) row(json, offset);
    header = false;
    return true;
  });
}

std::string read_row(const std::string& path, std::uint64_t offset, std::size_t size) {
  const int fd = open_ledger(path, O_RDONLY);
  std::string json(size, '\0');
  std::size_t got = 0;
  while (got < size) {
    const ssize_t n = ::pread(fd, json.data() + got, size - got, static_cast<off_t>(offset + got));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int error = n < 0 ? errno : EIO;
      ::close(fd);
      fail(path, "cannot read a row of the ledger", error);
    }
    got += static_cast<std::size_t>(n);
  }
  ::close(fd);
  return json;
}

}  // namespace fabmesh
