#pragma once
// The ledgers of a batch folder (DIR/.batch/ledger-I-of-N.jsonl): one per
// shard, append-only, one writer each. A line is committed when it is whole:
// "JSON<TAB>CHECK\n", CHECK the first 16 hex digits of the JSON's SHA-256. A
// line torn by a kill (or a crash) fails the check and is dropped; its
// variant is redone.

#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pipeline/batch/shard.h"

namespace fabmesh {

/// The first line of a ledger: which plan and which shard it records.
struct LedgerHeader {
  std::string plan;          ///< the plan's digest
  std::size_t variants = 0;  ///< in the whole plan
  Shard shard;
};

/// The longest JSON a ledger row may hold: a row longer than this is written
/// without its overrides (the plan has them) and with its message cut
/// (run_batch), so a longer line in a ledger is corruption.
inline constexpr std::size_t kMaxLedgerRowBytes = std::size_t{4} << 20;

/// `json` as a committed ledger line (with its check and newline).
std::string ledger_line(std::string_view json);

/// The JSON of a committed ledger line (without its newline), or nothing when
/// the line is torn or its check fails.
std::optional<std::string_view> committed_json(std::string_view line);

/// A shard's ledger, open for appending. Holds an exclusive lock on the file
/// (flock, released when the process ends, however it ends).
class LedgerWriter {
 public:
  /// Opens `folder`/ledger-I-of-N.jsonl, creating the folder and the file.
  /// Cuts a torn last line. A ledger of another plan is moved aside (its rows
  /// stay readable, as ledger-I-of-N.DIGEST.jsonl) and a new one begun.
  /// \throw InputError when another process writes this shard's ledger,
  /// FileError when it cannot be opened or written or is corrupt (a line
  /// longer than any ledger line can be)
  LedgerWriter(const std::string& folder, const LedgerHeader& header);
  ~LedgerWriter();
  LedgerWriter(const LedgerWriter&) = delete;
  LedgerWriter& operator=(const LedgerWriter&) = delete;

  /// Appends a committed line of `json` (one write; safe from several threads)
  /// and returns the byte offset of the JSON in the file. \throw FileError
  std::uint64_t append(std::string_view json);
  /// Flushes the ledger to disk (fdatasync). \throw FileError
  void sync();
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
  std::uint64_t size_ = 0;  ///< of the file: this writer is its only one
  std::mutex writing_;
};

/// The file name of shard `s`'s ledger.
std::string ledger_name(const Shard& s);

/// A ledger file of a batch folder and its header, when committed.
struct LedgerFile {
  std::string path;
  bool current = false;  ///< ledger-I-of-N.jsonl (not one moved aside)
  std::optional<LedgerHeader> header;
};

/// The ledger files of `folder` (the batch's .batch folder): the ones moved
/// aside first, then the current ones, each group oldest first (modification
/// time, then name): later rows supersede earlier ones. Empty when there is none.
std::vector<LedgerFile> list_ledgers(const std::string& folder);

/// Calls `row(json, offset)` for every committed row (not header) of `file`, in
/// order; `offset` is where the JSON starts in the file. A torn or failing line
/// is skipped. Each block of the file is read and searched once, and memory
/// stays bounded by kMaxLedgerRowBytes. \throw FileError when the file cannot
/// be read, or holds a line longer than any ledger line can be (corrupt)
void for_each_row(const LedgerFile& file,
                  const std::function<void(std::string_view json, std::uint64_t offset)>& row);

/// The `size` bytes at `offset` of the file at `path` (a row for_each_row or
/// LedgerWriter::append located). \throw FileError
std::string read_row(const std::string& path, std::uint64_t offset, std::size_t size);

}  // namespace fabmesh
