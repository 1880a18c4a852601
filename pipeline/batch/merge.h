#pragma once
// Merging a batch's shards: the summary of the whole plan from every shard's
// ledger, and what is missing.

#include <cstddef>
#include <string>
#include <vector>

#include "pipeline/batch/shard.h"
#include "pipeline/batch/summary.h"

namespace fabmesh {

/// The exit code of a merge that finds variants no shard has finished.
inline constexpr int kIncompleteExitCode = 4;

/// A shard that has not finished its variants.
struct ShardGap {
  Shard shard;
  bool started = false;     ///< it has a ledger
  std::size_t owned = 0;    ///< its variants
  std::size_t missing = 0;  ///< of them, without a row
};

struct MergeOutcome {
  std::size_t variants = 0;
  SummaryCounts counts;              ///< over the plan, missing ones included
  std::vector<std::string> missing;  ///< names of the variants without a row, in plan order
  std::vector<ShardGap> gaps;        ///< by shard count, then index
  std::string plan;                  ///< the plan's digest
  int exit_code = 0;                 ///< the worst variant's, or kIncompleteExitCode when some are missing
};

/// Writes `out_dir`/summary.{csv,jsonl} for the plan its shards ran (the one
/// their current ledgers name), from the rows of every ledger there, and
/// reports the variants and shards still missing. Idempotent.
/// \throw InputError when `out_dir` holds no ledger, or current ledgers of
/// different plans (the manifest changed between shards); FileError
MergeOutcome merge_batch(const std::string& out_dir);

}  // namespace fabmesh
