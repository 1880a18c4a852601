#include <exception>
#include <map>
#include <string>

#include "pipeline/cli/commands.h"
#include "pipeline/failure.h"

namespace fabmesh::cli {

int run_app(int argc, const char* const* argv, Streams streams) {
  CLI::App app{"fabmesh: parametric product designs to fabrication-ready meshes"};
  app.require_subcommand(0, 1);
  app.set_version_flag("--version", std::string("fabmesh ") + FABMESH_VERSION);
  bool quiet = false, verbose = false;
  // Options of the program, accepted before or after the command (`fabmesh run -q x.yaml`).
  app.fallthrough();
  app.add_flag("-q,--quiet", quiet, "Print results and errors only (no summaries, no progress)");
  app.add_flag("-v,--verbose", verbose, "Print more: every stage's time");
  std::map<const CLI::App*, Runner> runners;
  auto add = [&](Runner (*adder)(CLI::App&)) {
    const std::size_t before = app.get_subcommands({}).size();
    Runner runner = adder(app);
    runners.emplace(app.get_subcommands({}).at(before), std::move(runner));
  };
  // --- commands ---
  add(&add_check_command);
  add(&add_sample_command);
  add(&add_optimize_command);
  add(&add_run_command);
  add(&add_plot_command);
  add(&add_preview_command);
  add(&add_batch_command);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version are "errors" with exit code 0 in CLI11.
    const int code = app.exit(e, streams.out, streams.err);
    return code == 0 ? 0 : 2;
  }

  streams.verbosity = quiet ? 0 : verbose ? 2 : 1;
  const CLI::App* chosen = nullptr;
  for (const auto& [sub, runner] : runners) {
    if (sub->parsed()) chosen = sub;
  }
  try {
    if (chosen == nullptr) return run_bundled_example(streams);
    return runners.at(chosen)(streams);
  } catch (...) {
    const Failure failure = describe_failure(std::current_exception());
    streams.err << failure_line(failure) << "\n";
    return failure.exit_code;
  }
}

}  // namespace fabmesh::cli
