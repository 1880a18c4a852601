// libFuzzer entry for batch ledgers (pipeline/batch/ledger.h): the input is
// written as DIR/.batch/ledger-0-of-1.jsonl and read back the ways fabmesh
// reads a ledger:
//  - list_ledgers (the header), for_each_row, read_row at every offset it
//    reports, and row_from_json on every committed row (and row_json's
//    round trip of what it returns);
//  - a resumed run's reading (run_batch): PlanRows over the ledger, then for
//    each kept row summary_row and row_stands;
//  - `fabmesh batch --merge DIR` (merge_batch, which writes DIR/summary.*);
//  - reopening the ledger for appending (LedgerWriter: cuts a torn last
//    line, moves another plan's ledger aside).
// The plan is fuzz/ledger_plan.json, the plan of configs/examples/
// batch_vessel_sweep.yaml that the seeds (tests/data/fuzz-seeds/ledger/,
// written by `fabmesh batch`) were run for, so their rows belong to it.
//
// The first byte of the input selects how the rest becomes the ledger:
//  - even ('0' in the seeds): the bytes as they are. A committed line ends
//    with the first 16 hex digits of its JSON's SHA-256, so a mutated line
//    is almost always dropped as torn: this mode fuzzes the line framing.
//  - odd ('1'): every whole line is committed afresh (ledger_line) after its
//    old check, if it has one (a tab and 16 characters at its end), is
//    dropped; an unended last line stays as it is (torn). Mutations then
//    reach the header and row JSON parsers.
//
// Each step may only return or throw the typed errors it documents
// (FileError, InputError); anything else (a crash, another exception, a
// sanitizer report, a hang caught by -timeout, memory beyond -rss_limit_mb)
// or a broken invariant (__builtin_trap) is a finding.
// DIR is made once per process (fuzz/temp_folder.h) and removed at exit.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "fuzz/temp_folder.h"
#include "geometry/core/errors.h"
#include "pipeline/batch/batch_row.h"
#include "pipeline/batch/ledger.h"
#include "pipeline/batch/merge.h"
#include "pipeline/batch/plan.h"
#include "pipeline/batch/run_variant.h"
#include "pipeline/batch/summary.h"

namespace {

namespace fs = std::filesystem;
using fabmesh::FileError;
using fabmesh::InputError;

void require(bool holds) {
  if (!holds) __builtin_trap();
}

// The plan the seeds' rows belong to (read once; never changed).
const fabmesh::BatchPlan& fixture_plan() {
  static const fabmesh::BatchPlan plan = fabmesh::read_plan(FABMESH_FUZZ_LEDGER_PLAN);
  return plan;
}

std::string make_batch_folder() {
  const std::string dir = fabmesh::fuzz::make_temp_folder("fuzz-ledger");
  fs::create_directories(fs::path(dir) / ".batch");
  fabmesh::save_plan(fixture_plan(), (fs::path(dir) / ".batch").string());
  return dir;
}

// This process's batch folder, made on first use, removed at exit.
const std::string& batch_folder() { return fabmesh::fuzz::process_folder<make_batch_folder>(); }

std::string ledger_folder() { return fabmesh::ledger_folder(batch_folder()); }

// The ledger bytes of `text` with every whole line committed afresh.
std::string recommitted(std::string_view text) {
  constexpr std::size_t kCheck = 17;  // a tab and 16 hex digits
  std::string out;
  for (std::size_t start = 0; start < text.size();) {
    const std::size_t newline = text.find('\n', start);
    if (newline == std::string_view::npos) {
      out.append(text.substr(start));  // torn
      break;
    }
    std::string_view json = text.substr(start, newline - start);
    if (json.size() >= kCheck && json[json.size() - kCheck] == '\t') json.remove_suffix(kCheck);
    out += fabmesh::ledger_line(json);
    start = newline + 1;
  }
  return out;
}

// Leaves only the plan in the ledger folder (the last input's ledgers, moved
// aside ones included, are gone) and writes `bytes` as the ledger.
std::string write_ledger(const std::string& bytes) {
  const std::string folder = ledger_folder();
  const std::string plan = fabmesh::plan_path(folder, fixture_plan().digest);
  std::error_code ec;
  std::vector<fs::path> stale;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->path().string() != plan) stale.push_back(it->path());
  }
  for (const fs::path& p : stale) fs::remove_all(p, ec);
  const std::string path = (fs::path(folder) / "ledger-0-of-1.jsonl").string();
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
  return path;
}

// A row as the summary reads it: row_from_json throws only InputError, and
// row_json is its inverse.
void check_record(std::string_view json) {
  const nlohmann::ordered_json j = nlohmann::ordered_json::parse(json, nullptr, false);
  if (j.is_discarded()) return;
  fabmesh::BatchRow row;
  try {
    row = fabmesh::row_from_json(j);
  } catch (const InputError&) {
    return;  // a damaged row, rejected cleanly
  }
  const nlohmann::ordered_json written = fabmesh::row_json(row);
  try {
    require(fabmesh::row_json(fabmesh::row_from_json(written)) == written);
  } catch (const InputError&) {
    __builtin_trap();  // row_json wrote what row_from_json cannot read
  }
}

// The header and the rows, as list_ledgers and for_each_row give them.
void check_rows(const std::string& ledger) {
  std::vector<fabmesh::LedgerFile> files;
  try {
    files = fabmesh::list_ledgers(ledger_folder());
  } catch (const FileError&) {
    return;  // a line longer than any ledger line: corrupt
  }
  require(files.size() == 1 && files[0].path == ledger && files[0].current);
  if (files[0].header) require(files[0].header->shard.index < files[0].header->shard.count);
  const std::uint64_t size = fs::file_size(ledger);
  std::uint64_t next = 0;  // where the next line can start
  try {
    fabmesh::for_each_row(files[0], [&](std::string_view json, std::uint64_t offset) {
      require(offset >= next);
      next = offset + json.size() + 18;  // the tab, the check, the newline
      require(next <= size);
      try {
        require(fabmesh::read_row(ledger, offset, json.size()) == json);
      } catch (const FileError&) {
        __builtin_trap();  // the row for_each_row just read
      }
      check_record(json);
    });
  } catch (const FileError&) {
    return;
  }
}

// What a resumed run reads: the rows kept for the plan's variants, and
// whether each stands for running it again.
void check_resume() {
  const fabmesh::BatchPlan& plan = fixture_plan();
  fabmesh::PlanRows rows(plan);
  try {
    rows.offer_ledgers(ledger_folder());
  } catch (const FileError&) {
    return;
  }
  for (std::size_t i = 0; i < plan.size(); ++i) {
    std::optional<std::string> json;
    try {
      json = rows.row(i);
    } catch (const FileError&) {
      continue;
    }
    require(json.has_value() == (rows.status(i) != fabmesh::VariantStatus::Missing));
    if (!json) continue;
    fabmesh::row_stands(*json, batch_folder());
    try {
      const fabmesh::BatchRow row = fabmesh::summary_row(plan, rows, i);
      require(row.index == i && row.name == plan.name(i) && row.key == plan.key(i));
      require(row.status == rows.status(i));
    } catch (const InputError&) {
      continue;  // a damaged row
    }
  }
}

// `fabmesh batch --merge DIR`.
void check_merge() {
  fabmesh::MergeOutcome out;
  try {
    out = fabmesh::merge_batch(batch_folder());
  } catch (const InputError&) {
    return;  // no ledger, or a plan that is not there (FileError)
  }
  const fabmesh::SummaryCounts& c = out.counts;
  require(c.ok + c.invalid + c.bad_input + c.error + c.missing + c.environment == out.variants);
  require(out.missing.size() == c.missing);
  require(out.exit_code == (out.missing.empty() ? c.exit_code : fabmesh::kIncompleteExitCode));
}

// Reopening the ledger to append: afterwards it begins with this plan's header.
void check_reopen(const std::string& ledger) {
  const fabmesh::BatchPlan& plan = fixture_plan();
  std::vector<fabmesh::LedgerFile> files;
  try {
    const fabmesh::LedgerWriter writer(ledger_folder(), {plan.digest, plan.size(), fabmesh::Shard{0, 1}});
    require(writer.path() == ledger);
    files = fabmesh::list_ledgers(ledger_folder());
  } catch (const InputError&) {
    return;  // corrupt (FileError)
  }
  const auto reopened = std::find_if(files.begin(), files.end(),
                                     [&](const fabmesh::LedgerFile& f) { return f.path == ledger; });
  require(reopened != files.end() && reopened->current && reopened->header &&
          reopened->header->plan == plan.digest);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string_view text(reinterpret_cast<const char*>(data) + 1, size - 1);
  const std::string ledger = write_ledger((data[0] & 1) != 0 ? recommitted(text) : std::string(text));
  check_rows(ledger);
  check_resume();
  check_merge();
  check_reopen(ledger);
  return 0;
}
