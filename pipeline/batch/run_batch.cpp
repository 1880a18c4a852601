#include "pipeline/batch/run_batch.h"

#include <fmt/format.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <mutex>
#include <optional>

#include "geometry/core/errors.h"
#include "io/design/read_design.h"
#include "pipeline/batch/ledger.h"
#include "pipeline/batch/output_links.h"
#include "pipeline/batch/plan.h"
#include "pipeline/batch/run_variant.h"

namespace fabmesh {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Counts finished variants and reports progress, one report at a time.
class Tally {
 public:
  Tally(std::size_t total, const std::function<void(const BatchProgress&)>& report) : report_(report) {
    progress_.total = total;
  }

  void finished(bool reused, bool ok) {
    std::lock_guard<std::mutex> lock(mutex_);
    ++progress_.done;
    if (reused) ++progress_.reused;
    if (!ok) ++progress_.failed;
    send(false);
  }

  void end() {
    std::lock_guard<std::mutex> lock(mutex_);
    send(true);
  }

 private:
  void send(bool finished) {
    if (!report_) return;
    progress_.elapsed_s = std::chrono::duration<double>(Clock::now() - start_).count();
    progress_.finished = finished;
    report_(progress_);
  }

  const std::function<void(const BatchProgress&)>& report_;
  BatchProgress progress_;
  std::mutex mutex_;
  Clock::time_point start_ = Clock::now();
};

// Refuses a variant folder of the shard that is a link, before anything is
// written: the batch would write its files, then tidy, through the link.
void refuse_linked_variant_folders(const BatchPlan& plan, const Shard& shard, std::size_t in_shard,
                                   const std::string& out_dir) {
  std::vector<std::string> links;
  for (std::size_t k = 0; k < in_shard; ++k) {
    const std::string folder =
        (std::filesystem::path(out_dir) / plan.name(shard.index + k * shard.count)).string();
    if (is_link(folder)) links.push_back(folder);
  }
  if (links.empty()) return;
  constexpr std::size_t kShown = 5;
  std::string others;
  for (std::size_t k = 1; k < links.size() && k <= kShown; ++k) others += (k == 1 ? "" : ", ") + links[k];
  if (links.size() > kShown + 1) others += fmt::format(" and {} more", links.size() - kShown - 1);
  try {
    refuse_link(links.front(), "variant folder");
  } catch (const InputError& e) {
    if (others.empty()) throw;
    throw InputError(fmt::format("{} (so are {})", e.what(), others));
  }
}

// The row's JSON for the ledger, within kMaxLedgerRowBytes: a row quoting a
// huge value in its message (a table cell of megabytes, say) is written
// without its overrides (the summary takes them from the plan) and with its
// message cut at a character's start.
std::string ledger_row_json(BatchRow row) {
  std::string json = row_json(row).dump();
  if (json.size() <= kMaxLedgerRowBytes) return json;
  constexpr std::size_t kKeptMessage = std::size_t{64} << 10;
  row.overrides.clear();
  if (row.message.size() > kKeptMessage) {
    std::size_t cut = kKeptMessage;
    while (cut > 0 && (static_cast<unsigned char>(row.message[cut]) & 0xC0) == 0x80) --cut;
    row.message = fmt::format("{}... ({} more bytes)", row.message.substr(0, cut), row.message.size() - cut);
  }
  for (SkippedOutput& s : row.skipped) {
    if (s.reason.size() > kKeptMessage) s.reason.resize(kKeptMessage);
  }
  return row_json(row).dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

}  // namespace

void refuse_unknown_override_paths(const BatchManifest& manifest) {
  const std::size_t per_base = manifest.variant_count() / std::max<std::size_t>(1, manifest.bases.size());
  if (per_base == 0) return;
  for (std::size_t b = 0; b < manifest.bases.size(); ++b) {
    // The paths with the values of the base's first variant where it gives one (its text names
    // the manifest's place), else a null value: an unknown key is found before any value is read.
    std::vector<Override> paths = variant_overrides(manifest, manifest.variant(b * per_base));
    for (const std::string& p : manifest.parameters) {
      const bool given =
          std::any_of(paths.begin(), paths.end(), [&](const Override& o) { return o.path == p; });
      if (!given) paths.push_back({p, "null", p});
    }
    for (const Override& o : paths) {
      try {
        manifest.bases[b].resolve({o});
      } catch (const UnknownKeyError& e) {
        const std::string& key = e.field();
        if (o.path == key || o.path.rfind(key + ".", 0) == 0 || o.path.rfind(key + "[", 0) == 0) {
          throw UnknownKeyError(key, e.path(), e.line(), e.column(),
                                std::string(e.what()) + "; every variant sets this path, so none was run");
        }
      } catch (const InputError&) {
        // a value, or a path that needs another override first: its variants report it
      }
    }
  }
}

BatchOutcome run_batch(const BatchManifest& manifest, const BatchOptions& options) {
  const Clock::time_point start = Clock::now();
  BatchOutcome out;
  const int threads =
      options.jobs > 0 ? static_cast<int>(options.jobs) : tbb::this_task_arena::max_concurrency();
  // More threads than cores (--jobs above the core count) need a larger pool, for this run only.
  std::optional<tbb::global_control> pool;
  if (threads > tbb::this_task_arena::max_concurrency())
    pool.emplace(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  tbb::task_arena arena(threads);
  const Shard shard = options.shard;
  const std::string folder = ledger_folder(options.out_dir);

  refuse_unknown_override_paths(manifest);
  BatchPlan plan;
  arena.execute([&] { plan = plan_batch(manifest); });
  out.variants = plan.size();
  out.in_shard = shard.size_of(plan.size());
  refuse_linked_variant_folders(plan, shard, out.in_shard, options.out_dir);
  LedgerWriter ledger(folder, {plan.digest, plan.size(), shard});
  out.ledger = ledger.path();
  save_plan(plan, folder);
  // Rows of earlier runs, of any shard count: each variant's last row of its key.
  PlanRows rows(plan);
  rows.offer_ledgers(folder);
  out.plan_ms = ms_since(start);

  std::vector<VariantStatus> status(out.in_shard, VariantStatus::Missing);
  const std::size_t own_ledger = rows.add_ledger(ledger.path());
  std::vector<std::pair<std::size_t, BatchFailure>> failures;  // by k, in finishing order
  std::mutex failing;
  std::vector<std::pair<std::size_t, std::pair<std::string, std::string>>> rebuilt;  // by k
  const auto failed = [&](std::size_t k, const BatchRow& row) {
    std::lock_guard<std::mutex> lock(failing);
    failures.push_back({k, {row.name, row.status, row.exit_code, row.message}});
  };
  std::atomic<std::size_t> ran{0};
  std::atomic<long long> jobs_us{0};
  std::mutex keeping;  // the kept rows, for the summary of a whole batch
  Tally tally(out.in_shard, options.progress);
  // Countertops that differ only in thickness share their work in the plane.
  PlaneMemo planes;
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, out.in_shard, 1), [&](const tbb::blocked_range<std::size_t>& r) {
          for (std::size_t k = r.begin(); k != r.end(); ++k) {
            const std::size_t i = shard.index + k * shard.count;
            const std::optional<std::string> earlier = rows.row(i);
            std::string why;
            if (!options.force && earlier && row_stands(*earlier, options.out_dir, &why)) {
              status[k] = rows.status(i);
              if (status[k] != VariantStatus::Ok) {
                const BatchRow row = summary_row(plan, rows, i);
                failed(k, row);
              }
              tally.finished(true, status[k] == VariantStatus::Ok);
              continue;
            }
            if (!why.empty()) {
              std::lock_guard<std::mutex> lock(failing);
              rebuilt.push_back({k, {plan.name(i), why}});
            }
            const BatchRow row = run_variant(manifest, i, plan.variant(i), options.out_dir, &planes);
            const std::string json = ledger_row_json(row);
            const std::uint64_t offset = ledger.append(json);
            for (const auto& [stage, ms] : row.timings_ms) {
              if (stage == "job") jobs_us += static_cast<long long>(ms * 1000.0);
            }
            if (shard.count == 1) {
              std::lock_guard<std::mutex> lock(keeping);
              rows.offer(json, own_ledger, offset);
            }
            status[k] = row.status;
            if (row.status != VariantStatus::Ok) failed(k, row);
            ++ran;
            tally.finished(false, row.status == VariantStatus::Ok);
          }
        });
  });
  ledger.sync();
  out.ran = ran;
  out.reused = out.in_shard - out.ran;
  out.jobs_ms = static_cast<double>(jobs_us.load()) / 1000.0;
  for (std::size_t k = 0; k < out.in_shard; ++k) {
    out.counts.add(status[k], exit_code_of(status[k]));
  }
  std::sort(failures.begin(), failures.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (auto& f : failures) out.failures.push_back(std::move(f.second));
  std::sort(rebuilt.begin(), rebuilt.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (auto& r : rebuilt) out.rebuilt.push_back(std::move(r.second));
  if (shard.count == 1) {
    write_summary(plan, rows, options.out_dir);
    out.summary_written = true;
  }
  out.wall_ms = ms_since(start);
  tally.end();
  return out;
}

}  // namespace fabmesh
