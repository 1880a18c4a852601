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

/// Registers `-D path=value` (repeatable) and `-P NAME` on a command that
/// reads designs. `-P NAME` is `-D parameter_set=NAME`: the design's
/// parameter set NAME, under every `-D` (a `-D` of a parameter wins).
inline void add_define_option(CLI::App* cmd, std::vector<std::string>& defines) {
  cmd->add_option(
         "-D,--define", defines,
         "Override a design field, e.g. -D body.wall=2.5 -D profile.points[1]=[1,5] (the value is YAML; "
         "repeatable)")
      ->allow_extra_args(false);
  cmd->add_option_function<std::string>(
         "-P,--parameter-set",
         [&defines](const std::string& name) { defines.push_back("parameter_set=" + name); },
         "Use the design's parameter set NAME (parameter_sets:); -D values win over the set's")
      ->type_name("NAME");
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

/// `text` in ASCII lower case: file endings are told apart case-insensitively (X.STL is an STL).
inline std::string ascii_lower(std::string text) {
  for (char& c : text) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return text;
}

/// True when `-o out` names a file by its ending rather than a folder: no
/// trailing '/', and its last part ends in a '.' and 1 to 8 letters or digits,
/// a letter among them ("x.xyz", "mug.gltf"; not "out", "v1.2" or ".cache").
inline bool names_a_file(const std::string& out) {
  if (out.empty() || out.back() == '/') return false;
  const std::size_t slash = out.find_last_of('/');
  const std::string last = out.substr(slash == std::string::npos ? 0 : slash + 1);
  const std::size_t dot = last.find_last_of('.');
  if (dot == std::string::npos || dot == 0 || last.size() - dot - 1 > 8 || dot + 1 == last.size())
    return false;
  bool letter = false;
  for (std::size_t i = dot + 1; i < last.size(); ++i) {
    const char c = last[i];
    const bool is_letter = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
    if (!is_letter && !(c >= '0' && c <= '9')) return false;
    letter = letter || is_letter;
  }
  return letter;
}

// --- commands ---
Runner add_check_command(CLI::App& app);  ///< `fabmesh check MESH... [--json] [--weld-tolerance X]`
Runner add_sample_command(CLI::App& app);
Runner add_params_command(CLI::App& app);
Runner add_optimize_command(CLI::App& app);
Runner add_run_command(CLI::App& app);
Runner add_plot_command(CLI::App& app);     ///< `fabmesh plot DESIGN... [-o FILE.svg | DIR]`
Runner add_preview_command(CLI::App& app);  ///< `fabmesh preview MESH|DESIGN -o FILE.png`
Runner add_batch_command(CLI::App& app);    ///< `fabmesh batch MANIFEST ...`, `fabmesh batch --merge DIR`
Runner add_studio_command(CLI::App& app);   ///< `fabmesh studio DESIGN [--port N] [--host ADDR] [--no-open]`
Runner add_repair_command(CLI::App& app);  ///< `fabmesh repair MESH... [-o OUT] [--max-deviation D] [--wrap]`

/// `fabmesh` without arguments: runs the bundled vessel example into ./out,
/// found at ../share/fabmesh/examples from the program's own folder (2, with
/// a message saying where it looked, when it is not there).
int run_bundled_example(Streams streams);

/// Parses argv, runs the chosen command and maps exceptions to exit codes:
/// InputError -> 2, ValidationFailed -> 1, anything else -> 3.
int run_app(int argc, const char* const* argv, Streams streams);

}  // namespace fabmesh::cli
