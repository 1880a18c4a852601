// fabmesh batch MANIFEST [-o DIR] [--jobs N] [--shard I/N] [--force] [--json] [--slurm [--array-size N]]
// fabmesh batch --merge DIR [--json]: many variants of designs (docs/batch.md).

#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "geometry/core/errors.h"
#include "io/design/manifest.h"
#include "io/file.h"
#include "pipeline/batch/batch_report.h"
#include "pipeline/batch/merge.h"
#include "pipeline/batch/output_links.h"
#include "pipeline/batch/plan.h"
#include "pipeline/batch/progress.h"
#include "pipeline/batch/run_batch.h"
#include "pipeline/batch/slurm_script.h"
#include "pipeline/cli/commands.h"
#include "pipeline/failure.h"
#include "pipeline/report.h"

namespace fabmesh::cli {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

constexpr std::size_t kShownFailures = 20;
constexpr std::size_t kDefaultArraySize = 100;

struct BatchArgs {
  std::string manifest;
  std::string out;
  std::size_t jobs = 0;
  std::string shard;
  bool force = false;
  bool json = false;
  bool slurm = false;
  std::size_t array_size = 0;
  std::string merge;
  std::string report;  ///< --report FILE.html
};

// Default folder: out/MANIFEST-STEM.
std::string out_dir_of(const BatchArgs& args) {
  if (!args.out.empty()) return args.out;
  return (fs::path("out") / fs::path(args.manifest).stem()).string();
}

Json counts_json(const SummaryCounts& c) {
  return {{"ok", c.ok},
          {"invalid", c.invalid},
          {"bad_input", c.bad_input},
          {"error", c.error},
          {"environment", c.environment}};
}

std::string counts_text(const SummaryCounts& c) {
  std::string text = fmt::format("{} ok, {} invalid, {} bad input, {} error{}", c.ok, c.invalid, c.bad_input,
                                 c.error, c.error == 1 ? "" : "s");
  // Only when there are some: the machine's failures (disk full, permission), redone by a rerun.
  if (c.environment > 0) text += fmt::format(", {} environment (run again once fixed)", c.environment);
  return text;
}

void print_failures(const std::vector<BatchFailure>& failures, const std::string& summary,
                    std::ostream& err) {
  for (std::size_t i = 0; i < failures.size() && i < kShownFailures; ++i) {
    const BatchFailure& f = failures[i];
    err << fmt::format("fabmesh: {}: {}: {}\n", to_string(f.status), f.name, printable_message(f.message));
  }
  if (failures.size() > kShownFailures) {
    err << fmt::format("fabmesh: ... and {} more failed variants (see {})\n",
                       failures.size() - kShownFailures, summary);
  }
}

int run_manifest(const BatchArgs& args, Streams io) {
  const BatchManifest manifest = read_manifest(args.manifest);
  BatchOptions options;
  options.out_dir = out_dir_of(args);
  options.jobs = args.jobs;
  options.force = args.force;
  if (!args.shard.empty()) options.shard = parse_shard(args.shard);
  std::unique_ptr<ProgressPrinter> printer;
  if (io.verbosity > 0) {
    const bool terminal = &io.err == &std::cerr && ::isatty(STDERR_FILENO) == 1;
    printer = std::make_unique<ProgressPrinter>(io.err, ProgressOptions{terminal});
    options.progress = [&printer](const BatchProgress& p) { (*printer)(p); };
  }
  const BatchOutcome out = run_batch(manifest, options);
  const fs::path dir(options.out_dir);
  const std::string summary = out.summary_written
                                  ? (dir / "summary.csv").string()
                                  : (dir / ".batch" / fs::path(out.ledger).filename()).string();
  print_failures(out.failures, summary, io.err);
  for (std::size_t i = 0; i < out.rebuilt.size() && i < kShownFailures; ++i)
    io.err << fmt::format("fabmesh: note: {}: {}\n", out.rebuilt[i].first, out.rebuilt[i].second);
  const std::string shard = fmt::format("{}/{}", options.shard.index, options.shard.count);
  if (args.json) {
    Json j;
    j["manifest"] = args.manifest;
    j["output"] = options.out_dir;
    j["variants"] = out.variants;
    j["shard"] = shard;
    j["in_shard"] = out.in_shard;
    j["ran"] = out.ran;
    j["reused"] = out.reused;
    j.update(counts_json(out.counts));
    j["exit_code"] = out.counts.exit_code;
    j["ledger"] = out.ledger;
    j["summary"] = out.summary_written ? Json{{"csv", (dir / "summary.csv").string()},
                                              {"jsonl", (dir / "summary.jsonl").string()}}
                                       : Json(nullptr);
    j["failures"] = Json::array();
    for (const BatchFailure& f : out.failures) {
      j["failures"].push_back({{"name", f.name},
                               {"status", to_string(f.status)},
                               {"exit_code", f.exit_code},
                               {"message", f.message}});
    }
    j["rebuilt"] = Json::array();
    for (const auto& [name, why] : out.rebuilt) j["rebuilt"].push_back({{"name", name}, {"reason", why}});
    j["timings_ms"] = {{"plan", out.plan_ms}, {"jobs", out.jobs_ms}, {"wall", out.wall_ms}};
    print_json_items(Json::array({j}), io.out);
  } else if (io.verbosity > 0) {
    const std::string what = options.shard.count == 1 ? fmt::format("{} variants", out.variants)
                                                      : fmt::format("shard {} ({} of {} variants)", shard,
                                                                    out.in_shard, out.variants);
    io.out << fmt::format("{}: {}: {}; {} run, {} reused from earlier runs\n", args.manifest, what,
                          counts_text(out.counts), out.ran, out.reused);
    if (out.summary_written) {
      io.out << fmt::format("summary: {}, {}\n", (dir / "summary.csv").string(),
                            (dir / "summary.jsonl").string());
    } else {
      io.out << fmt::format("when every shard is done: fabmesh batch --merge {}\n", options.out_dir);
    }
  }
  if (!args.report.empty() && out.summary_written) {
    write_batch_report(options.out_dir, args.report);
    if (io.verbosity > 0 && !args.json) io.out << fmt::format("report: {}\n", args.report);
  }
  return out.counts.exit_code;
}

// A job name Slurm shows: the manifest's stem in plain characters.
std::string job_name(const std::string& manifest) {
  std::string name = "fabmesh-";
  for (const char c : fs::path(manifest).stem().string()) {
    const bool plain = std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
    name += plain ? c : '_';
  }
  return name;
}

int write_slurm(const BatchArgs& args, Streams io) {
  const BatchManifest manifest = read_manifest(args.manifest);
  refuse_unknown_override_paths(manifest);  // now, not in every task of the job
  const std::string out_dir = fs::absolute(out_dir_of(args)).lexically_normal().string();
  const std::size_t variants = manifest.variant_count();
  SlurmScriptOptions o;
  std::error_code ec;
  o.program = fs::read_symlink("/proc/self/exe", ec).string();
  if (ec) throw std::runtime_error("cannot find the fabmesh executable (/proc/self/exe)");
  o.manifest = fs::absolute(args.manifest).lexically_normal().string();
  o.out_dir = out_dir;
  o.job_name = job_name(args.manifest);
  o.variants = variants;
  o.shards =
      std::max<std::size_t>(1, std::min(args.array_size > 0 ? args.array_size : kDefaultArraySize, variants));
  o.cpus_per_task = args.jobs > 0 ? args.jobs : 1;
  const std::string script = slurm_script(o);
  // Slurm opens the tasks' log files in this folder: it must exist before they start (and not be
  // reached through a link: the tasks would write their logs wherever it leads).
  refuse_link((fs::path(out_dir) / ".batch").string(), "batch folder");
  refuse_link((fs::path(out_dir) / ".batch" / "slurm").string(), "folder of the Slurm logs");
  fs::create_directories(fs::path(out_dir) / ".batch" / "slurm", ec);
  if (ec) throw_write_failure(out_dir, "cannot create the folder", ec.value());
  const std::string path = (fs::path(out_dir) / "slurm.sbatch").string();
  write_file_atomically(path, script);
  fs::permissions(path, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                  fs::perm_options::add, ec);
  if (args.json) {
    const Json j = {{"manifest", args.manifest},
                    {"script", path},
                    {"variants", variants},
                    {"shards", o.shards},
                    {"cpus_per_task", o.cpus_per_task},
                    {"submit", "sbatch " + path},
                    {"merge", "fabmesh batch --merge " + out_dir}};
    print_json_items(Json::array({j}), io.out);
  } else {
    io.out << fmt::format("wrote {}: {} variants in {} shards (array tasks 0-{}, {} CPU each)\n", path,
                          variants, o.shards, o.shards - 1, o.cpus_per_task);
    io.out << fmt::format("submit:  sbatch {}\n", path);
    io.out << fmt::format("then:    fabmesh batch --merge {}\n", out_dir);
  }
  return 0;
}

int merge(const BatchArgs& args, Streams io) {
  const MergeOutcome out = merge_batch(args.merge);
  const fs::path dir(args.merge);
  const SummaryCounts& c = out.counts;
  for (const ShardGap& g : out.gaps) {
    io.err << fmt::format("fabmesh: missing: shard {}/{} {} ({} of its {} variants missing)\n", g.shard.index,
                          g.shard.count, g.started ? "is unfinished" : "never ran", g.missing, g.owned);
  }
  for (std::size_t i = 0; i < out.missing.size() && i < kShownFailures; ++i)
    io.err << fmt::format("fabmesh: missing: {}\n", out.missing[i]);
  if (out.missing.size() > kShownFailures)
    io.err << fmt::format("fabmesh: ... and {} more missing variants\n", out.missing.size() - kShownFailures);
  if (args.json) {
    Json j;
    j["output"] = args.merge;
    j["plan"] = out.plan;
    j["variants"] = out.variants;
    j.update(counts_json(c));
    j["missing"] = c.missing;
    j["exit_code"] = out.exit_code;
    j["summary"] = {{"csv", (dir / "summary.csv").string()}, {"jsonl", (dir / "summary.jsonl").string()}};
    j["missing_variants"] = out.missing;
    j["missing_shards"] = Json::array();
    for (const ShardGap& g : out.gaps) {
      j["missing_shards"].push_back({{"shard", fmt::format("{}/{}", g.shard.index, g.shard.count)},
                                     {"started", g.started},
                                     {"variants", g.owned},
                                     {"missing", g.missing}});
    }
    print_json_items(Json::array({j}), io.out);
  } else if (io.verbosity > 0) {
    io.out << fmt::format("{}: {} variants: {}, {} missing\n", args.merge, out.variants, counts_text(c),
                          c.missing);
    io.out << fmt::format("summary: {}, {}\n", (dir / "summary.csv").string(),
                          (dir / "summary.jsonl").string());
  }
  if (!args.report.empty()) {
    write_batch_report(args.merge, args.report);
    if (io.verbosity > 0 && !args.json) io.out << fmt::format("report: {}\n", args.report);
  }
  return out.exit_code;
}

int run_batch_command(const BatchArgs& args, Streams io) {
  if (args.merge.empty() == args.manifest.empty()) {
    throw InputError("batch: give a manifest (fabmesh batch MANIFEST.yaml) or --merge DIR, not both");
  }
  if (!args.report.empty() && fs::path(args.report).extension() != ".html")
    throw InputError(fmt::format("--report {}: the report is an HTML page; name it *.html", args.report));
  if (!args.merge.empty()) {
    if (args.slurm || !args.shard.empty() || args.force || args.jobs > 0 || !args.out.empty())
      throw InputError("batch --merge DIR takes no other option than --json and --report");
    return merge(args, io);
  }
  if (args.slurm) {
    if (!args.report.empty())
      throw InputError(
          "batch --slurm: make the report when merging (fabmesh batch --merge DIR --report FILE.html)");
    if (!args.shard.empty())
      throw InputError("batch --slurm writes a script that runs every shard: drop --shard");
    return write_slurm(args, io);
  }
  if (args.array_size > 0) throw InputError("batch --array-size goes with --slurm");
  return run_manifest(args, io);
}

}  // namespace

Runner add_batch_command(CLI::App& app) {
  auto args = std::make_shared<BatchArgs>();
  CLI::App* cmd =
      app.add_subcommand("batch", "Build many variants of designs from a manifest (docs/batch.md)");
  cmd->add_option("manifest", args->manifest, "The manifest (YAML): base designs and their variants");
  cmd->add_option("-o,--output", args->out, "The batch folder (default: out/MANIFEST-NAME)");
  cmd->add_option("--jobs", args->jobs, "Variants built at once (default: every core)")
      ->check(CLI::Range(1, 4096));
  cmd->add_option("--shard", args->shard,
                  "Run only shard I of N (counted from 0): the variants i with i mod N = I");
  cmd->add_flag("--force", args->force, "Run every variant again, even those done by earlier runs");
  cmd->add_flag("--json", args->json,
                "Print the JSON report (an array of one entry, about the run: docs/batch.md)");
  cmd->add_flag("--slurm", args->slurm,
                "Write DIR/slurm.sbatch, a Slurm job array running the shards, and say how to submit it");
  cmd->add_option("--array-size", args->array_size, "With --slurm: the number of shards (default: 100)")
      ->check(CLI::Range(1, 1000000));
  cmd->add_option(
      "--report", args->report,
      "Also write an HTML page of the summary, a thumbnail of each variant's mesh beside its files "
      "(a whole batch, or with --merge)");
  cmd->add_option("--merge", args->merge, "Merge the summaries of the shards in DIR into DIR/summary.*");
  return [args](Streams io) { return run_batch_command(*args, io); };
}

}  // namespace fabmesh::cli
