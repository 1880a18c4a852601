#include <exception>
#include <map>
#include <string>
#include <vector>

#include "pipeline/cli/commands.h"
#include "pipeline/failure.h"
#include "pipeline/report.h"

namespace fabmesh::cli {
namespace {

// Whether `command` was given --json, and not told to write a file to
// standard output (`run -o -`, whose reports go to the error stream).
bool wants_json(const CLI::App* command) {
  if (command == nullptr || command->get_option_no_throw("--json") == nullptr ||
      command->count("--json") == 0)
    return false;
  const CLI::Option* output = command->get_option_no_throw("--output");
  return output == nullptr || output->count() == 0 || output->as<std::string>() != "-";
}

// The --json item of a command that failed before any of its inputs had an
// item of its own (a bad manifest, two designs of one name): the command,
// its inputs (positional arguments) and the failure.
nlohmann::ordered_json command_error_item(const CLI::App& command, const Failure& failure) {
  std::vector<std::string> inputs;
  for (const CLI::Option* option : command.get_options()) {
    if (!option->get_positional()) continue;
    for (const std::string& value : option->results()) inputs.push_back(value);
  }
  nlohmann::ordered_json item = {{"command", command.get_name()}, {"inputs", inputs}};
  item["error"] = failure.message;
  item["exit_code"] = failure.exit_code;
  return item;
}

}  // namespace

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
  add(&add_params_command);
  add(&add_optimize_command);
  add(&add_run_command);
  add(&add_plot_command);
  add(&add_preview_command);
  add(&add_batch_command);
  add(&add_studio_command);
  add(&add_repair_command);

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
    if (wants_json(chosen))
      print_json_items(nlohmann::ordered_json::array({command_error_item(*chosen, failure)}), streams.out);
    return failure.exit_code;
  }
}

}  // namespace fabmesh::cli
