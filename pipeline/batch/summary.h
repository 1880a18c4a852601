#pragma once
// A batch's summary (DIR/summary.csv, DIR/summary.jsonl): one row per variant
// of the plan, in plan order, from the rows its ledgers committed.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pipeline/batch/batch_row.h"
#include "pipeline/batch/plan.h"

namespace fabmesh {

/// For each variant of a plan, the row that stands for it: the last committed
/// row with its name and key, a row of a finished variant (ok, invalid, bad
/// input) never superseded by one of an internal error. Keeps where each row
/// is in its ledger, not the row: memory grows by a few bytes per variant.
class PlanRows {
 public:
  explicit PlanRows(const BatchPlan& plan);
  /// Offers a row's JSON, committed at `offset` of the ledger `ledger` (an
  /// index from add_ledger); keeps it when it belongs to the plan and
  /// supersedes the row kept. Rows of other plans or damaged rows are ignored.
  void offer(std::string_view json, std::size_t ledger, std::uint64_t offset);
  /// Registers a ledger file; returns its index for offer().
  std::size_t add_ledger(const std::string& path);
  /// Offers every row of every ledger in `ledger_folder` (list_ledgers order).
  void offer_ledgers(const std::string& ledger_folder);
  /// The JSON of the row kept for variant `i` (read from its ledger), or nothing. \throw FileError
  std::optional<std::string> row(std::size_t i) const;
  /// Its status (Missing when there is none).
  VariantStatus status(std::size_t i) const { return status_[i]; }

 private:
  struct Place {
    std::uint64_t offset = 0;
    std::uint32_t size = 0;
    std::uint32_t ledger = 0;
  };
  const BatchPlan& plan_;
  std::vector<std::string> ledgers_;
  std::vector<Place> places_;
  std::vector<VariantStatus> status_;
};

/// How many variants ended how, and the batch's exit code.
struct SummaryCounts {
  std::size_t ok = 0, invalid = 0, bad_input = 0, error = 0, missing = 0, environment = 0;
  int exit_code = 0;  ///< the worst of the variants' (missing ones aside)
  void add(VariantStatus status, int code);
};

/// The row of variant `i` for the summary: the kept row with the plan's index,
/// design and values, or a `missing` row. \throw InputError for a damaged row
BatchRow summary_row(const BatchPlan& plan, const PlanRows& rows, std::size_t i);

/// Writes `out_dir`/summary.jsonl and summary.csv, each atomically (rows in
/// plan order, no timestamps: only the timing fields differ between runs),
/// streamed a block at a time. \throw FileError
SummaryCounts write_summary(const BatchPlan& plan, const PlanRows& rows, const std::string& out_dir);

/// The batch's own folder inside its output folder (ledgers, plans, Slurm logs).
std::string ledger_folder(const std::string& out_dir);

}  // namespace fabmesh
