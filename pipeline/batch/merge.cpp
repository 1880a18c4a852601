#include "pipeline/batch/merge.h"

#include <fmt/format.h>

#include <map>
#include <set>

#include "geometry/core/errors.h"
#include "pipeline/batch/ledger.h"

namespace fabmesh {
namespace {

// The plan the current ledgers of `folder` name: there must be exactly one.
std::string current_plan(const std::vector<LedgerFile>& ledgers, const std::string& out_dir) {
  std::map<std::string, std::vector<std::string>> plans;  // digest -> ledger files
  for (const LedgerFile& f : ledgers) {
    if (f.current && f.header) plans[f.header->plan].push_back(f.path);
  }
  if (plans.empty()) {
    throw InputError(
        fmt::format("{}: no batch ledger here (run `fabmesh batch MANIFEST -o {}` or its shards first)",
                    out_dir, out_dir));
  }
  if (plans.size() > 1) {
    std::string list;
    for (const auto& [digest, files] : plans) {
      list += fmt::format("\n  plan {}: {}", digest.substr(0, 12), files.front());
      if (files.size() > 1) list += fmt::format(" and {} more", files.size() - 1);
    }
    throw InputError(
        fmt::format("{}: the shards here ran different plans (the manifest or its designs changed between "
                    "them):{}\nrerun every "
                    "shard with the current manifest, or move the stale ledgers out of {}",
                    out_dir, list, ledger_folder(out_dir)));
  }
  return plans.begin()->first;
}

}  // namespace

MergeOutcome merge_batch(const std::string& out_dir) {
  const std::string folder = ledger_folder(out_dir);
  const std::vector<LedgerFile> ledgers = list_ledgers(folder);
  MergeOutcome out;
  out.plan = current_plan(ledgers, out_dir);
  const BatchPlan plan = read_plan(plan_path(folder, out.plan));
  out.variants = plan.size();
  PlanRows rows(plan);
  for (const LedgerFile& file : ledgers) {
    const std::size_t ledger = rows.add_ledger(file.path);
    for_each_row(file,
                 [&](std::string_view json, std::uint64_t offset) { rows.offer(json, ledger, offset); });
  }
  out.counts = write_summary(plan, rows, out_dir);
  for (std::size_t i = 0; i < plan.size(); ++i) {
    if (rows.status(i) == VariantStatus::Missing) out.missing.push_back(plan.name(i));
  }
  // Which shards own the missing variants, for each shard count that ran.
  std::map<std::size_t, std::set<std::size_t>> started;  // shard count -> indices with a ledger
  for (const LedgerFile& f : ledgers) {
    if (f.current && f.header && f.header->plan == out.plan)
      started[f.header->shard.count].insert(f.header->shard.index);
  }
  for (const auto& [count, indices] : started) {
    std::vector<ShardGap> gaps(count);
    for (std::size_t i = 0; i < plan.size(); ++i) {
      ShardGap& g = gaps[i % count];
      ++g.owned;
      if (rows.status(i) == VariantStatus::Missing) ++g.missing;
    }
    for (std::size_t s = 0; s < count; ++s) {
      if (gaps[s].missing == 0) continue;
      gaps[s].shard = {s, count};
      gaps[s].started = indices.count(s) > 0;
      out.gaps.push_back(gaps[s]);
    }
  }
  out.exit_code = out.missing.empty() ? out.counts.exit_code : kIncompleteExitCode;
  return out;
}

}  // namespace fabmesh
