#pragma once
// Runs a batch: every variant of a manifest (or of one shard), in parallel,
// resumable after any interruption, into one folder per variant, with a
// ledger per shard and, for a whole batch, the summary files.

#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "io/design/manifest.h"
#include "pipeline/batch/batch_row.h"
#include "pipeline/batch/shard.h"
#include "pipeline/batch/summary.h"

namespace fabmesh {

/// Where a running batch is (for progress lines).
struct BatchProgress {
  std::size_t total = 0;   ///< variants of this run (its shard)
  std::size_t done = 0;    ///< finished, reused ones included
  std::size_t reused = 0;  ///< stood for by earlier runs' rows
  std::size_t failed = 0;  ///< not ok
  double elapsed_s = 0.0;
  bool finished = false;  ///< the last call
};

struct BatchOptions {
  std::string out_dir;   ///< the batch folder (created when missing)
  std::size_t jobs = 0;  ///< variants at once (threads); 0: every hardware thread
  Shard shard;           ///< the slice to run; {0, 1}: the whole batch, which then writes the summary
  bool force = false;    ///< run every variant even when an earlier row stands for it
  /// Called after each variant, one call at a time (from the worker threads), and once at the end.
  std::function<void(const BatchProgress&)> progress;
};

/// A failure, for the command's messages.
struct BatchFailure {
  std::string name;
  VariantStatus status = VariantStatus::Error;
  int exit_code = 3;
  std::string message;
};

/// What a run did.
struct BatchOutcome {
  std::size_t variants = 0;  ///< in the whole plan
  std::size_t in_shard = 0;
  std::size_t ran = 0;
  std::size_t reused = 0;
  SummaryCounts counts;                ///< over this run's shard (exit_code: the worst)
  std::vector<BatchFailure> failures;  ///< in plan order
  /// Variants whose earlier ok row did not stand because a file it lists is
  /// missing or changed (row_stands' why): name, why. In plan order.
  std::vector<std::pair<std::string, std::string>> rebuilt;
  std::string ledger;            ///< this shard's ledger
  bool summary_written = false;  ///< out_dir/summary.{csv,jsonl} (whole batches only)
  double plan_ms = 0.0;          ///< reading done: keys of every variant
  double wall_ms = 0.0;          ///< the whole run
  double jobs_ms = 0.0;          ///< the variants' own job times, summed
};

/// Refuses an override path that is not a key of a base design (`body.wal`
/// for `body.wall`): every variant would fail alike, so the batch fails once,
/// before any runs, naming the path where the manifest gives it. Each path
/// the manifest sets is applied alone to each base; a value that is bad is
/// left for its variant to report. \throw UnknownKeyError (exit 2)
void refuse_unknown_override_paths(const BatchManifest& manifest);

/// Runs `manifest`'s variants of `options.shard` into `options.out_dir`.
/// Every variant's key is computed first (the plan, saved in out_dir/.batch);
/// a variant with a committed row of the same name and key that still stands
/// (row_stands) is reused, unless `force`; the others run in parallel, each
/// committing its row to the shard's ledger as soon as its files are written.
/// One variant's failure never stops the others. A whole batch (shard 0/1)
/// ends by writing the summary. \throw InputError when the shard's ledger is
/// locked by another process, FileError when the folder cannot be written
BatchOutcome run_batch(const BatchManifest& manifest, const BatchOptions& options);

}  // namespace fabmesh
