// fabmesh run DESIGN... [-o OUTDIR] [--json]: the main job.

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>

#include "pipeline/cli/commands.h"
#include "pipeline/failure.h"
#include "pipeline/job.h"
#include "pipeline/load_design.h"
#include "pipeline/report.h"

namespace fabmesh::cli {
namespace {

struct RunArgs {
  std::vector<std::string> designs;
  std::vector<std::string> defines;
  std::string out_dir = "out";
  bool json = false;
};

// One design's outcome: a report, or the exit code and message of its failure.
struct Outcome {
  std::optional<JobReport> report;
  int code = 0;
  std::string error;
};

Outcome run_one(const std::string& path, const std::vector<Override>& overrides, const JobOptions& options) {
  Outcome o;
  try {
    o.report = run_job(load_design(path, overrides), options);
  } catch (...) {
    const Failure failure = describe_failure(std::current_exception(), path);
    o.code = failure.exit_code;
    o.error = failure_line(failure);
  }
  return o;
}

int run_designs(const RunArgs& args, Streams io) {
  JobOptions options;
  options.out_dir = args.out_dir;
  const std::vector<Override> overrides = parse_overrides(args.defines);
  std::vector<Outcome> outcomes(args.designs.size());
  // Jobs are pure functions of their designs: a batch runs them in parallel.
  tbb::parallel_for(std::size_t{0}, args.designs.size(),
                    [&](std::size_t i) { outcomes[i] = run_one(args.designs[i], overrides, options); });
  int code = 0;
  nlohmann::ordered_json all = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < outcomes.size(); ++i) {
    const Outcome& o = outcomes[i];
    code = std::max(code, o.code);
    if (!o.error.empty()) io.err << o.error << "\n";
    if (args.json) {
      all.push_back(o.report ? to_json(*o.report)
                             : nlohmann::ordered_json{
                                   {"design", args.designs[i]}, {"error", o.error}, {"exit_code", o.code}});
    } else if (o.report) {
      print_summary(*o.report, io.out);
    }
  }
  if (args.json) io.out << (all.size() == 1 ? all[0] : all).dump(2) << "\n";
  return code;
}

}  // namespace

std::string bundled_example() { return std::string(FABMESH_EXAMPLES_DIR) + "/vessel_golden_shell.yaml"; }

Runner add_run_command(CLI::App& app) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* cmd = app.add_subcommand("run", "Build, validate and write the meshes of design files");
  cmd->add_option("designs", args->designs, "Design files (YAML)")->required();
  cmd->add_option("-o,--out", args->out_dir, "Output folder (default: out)");
  cmd->add_flag("--json", args->json, "Print one JSON report per design");
  add_define_option(cmd, args->defines);
  return [args](Streams io) { return run_designs(*args, io); };
}

int run_bundled_example(Streams io) {
  RunArgs args;
  args.designs = {bundled_example()};
  io.out << fmt::format("fabmesh: no design given; running the bundled example {}\n", args.designs[0]);
  const int code = run_designs(args, io);
  if (code == 0) {
    io.out << fmt::format("Files are in {}/. Try `fabmesh run --help` and the designs in {}.\n",
                          std::filesystem::absolute(args.out_dir).string(), FABMESH_EXAMPLES_DIR);
  }
  return code;
}

}  // namespace fabmesh::cli
