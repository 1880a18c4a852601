#pragma once
// The subcommands of the `fabmesh` program. Each add_*_command registers its
// options on `app` and returns the function that runs it once parsed.

#include <CLI/CLI.hpp>
#include <cmath>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace fabmesh::cli {

/// Where a command writes: its result to `out`, diagnostics to `err`, and
/// how much: 0 with -q (results and errors only), 1 normally, 2 with -v.
struct Streams {
  std::ostream& out;
  std::ostream& err;
  int verbosity = 1;
};

/// Runs a parsed command; returns the process exit code (0 to 5, pipeline/failure.h).
using Runner = std::function<int(Streams)>;

/// Registers `-D path=value` (repeatable) on a command that reads designs.
inline void add_define_option(CLI::App* cmd, std::vector<std::string>& defines) {
  cmd->add_option(
         "-D,--define", defines,
         "Override a design field, e.g. -D body.wall=2.5 -D profile.points[1]=[1,5] (the value is YAML; "
         "repeatable)")
      ->allow_extra_args(false);
}

/// A check of a number option that is at least 0: a finite number, its
/// message naming the value as given ("-1 is below 0"), never a bound's
/// digits (CLI::NonNegativeNumber prints the largest double's 310).
inline CLI::Validator non_negative_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double value = 0.0;
        if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value))
          return "'" + text + "' is not a number";
        if (value < 0) return text + " is below 0: give a number >= 0";
        return std::string();
      },
      "NUMBER >= 0", "NONNEGATIVE");
}

// --- commands ---
Runner add_check_command(CLI::App& app);  ///< `fabmesh check MESH... [--json] [--weld-tolerance X]`
Runner add_sample_command(CLI::App& app);
Runner add_optimize_command(CLI::App& app);
Runner add_run_command(CLI::App& app);
Runner add_plot_command(CLI::App& app);     ///< `fabmesh plot DESIGN... [-o FILE.svg | DIR]`
Runner add_preview_command(CLI::App& app);  ///< `fabmesh preview MESH|DESIGN -o FILE.png`
Runner add_batch_command(CLI::App& app);    ///< `fabmesh batch MANIFEST ...`, `fabmesh batch --merge DIR`

/// `fabmesh` without arguments: runs the bundled vessel example into ./out,
/// found at ../share/fabmesh/examples from the program's own folder (2, with
/// a message saying where it looked, when it is not there).
int run_bundled_example(Streams streams);

/// Parses argv, runs the chosen command and maps exceptions to exit codes:
/// InputError -> 2, ValidationFailed -> 1, anything else -> 3.
int run_app(int argc, const char* const* argv, Streams streams);

}  // namespace fabmesh::cli
