// `fabmesh repair MESH... [-o OUT] [--max-deviation D] [--wrap] [--json]`:
// makes mesh files from elsewhere valid for fabrication, with a record of
// every change and where, and a proven bound of the distance moved; or says
// what it could not mend (exit 1). docs/repair.md.

#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "geometry/core/errors.h"
#include "pipeline/cli/commands.h"
#include "pipeline/failure.h"
#include "pipeline/repair_mesh.h"
#include "pipeline/repair_mesh_report.h"
#include "pipeline/report.h"

namespace fabmesh::cli {
namespace {

struct RepairArgs {
  std::vector<std::string> files;
  std::string output;
  double max_deviation = 0.0;
  double weld_distance = -1.0;
  double max_seconds = 600.0;
  bool wrap = false;
  bool no_fill = false;
  bool dry_run = false;
  bool json = false;
};

RepairFileOptions file_options(const RepairArgs& args) {
  RepairFileOptions options;
  options.repair.max_deviation = args.max_deviation;
  options.repair.weld_distance = args.weld_distance;
  options.repair.wrap = args.wrap;
  options.repair.fill_holes = !args.no_fill;
  options.repair.validation.max_self_intersection_seconds = args.max_seconds;
  options.output = args.output;
  options.output_is_folder = !args.output.empty() && (args.files.size() > 1 || !names_a_file(args.output));
  options.write = !args.dry_run;
  return options;
}

int run_repair(const RepairArgs& args, Streams streams) {
  if (args.files.size() > 1 && !args.output.empty() && names_a_file(args.output) && args.output.back() != '/')
    throw InputError(
        fmt::format("-o {}: several meshes need -o FOLDER (each written as FOLDER/STEM.3mf)", args.output));
  const RepairFileOptions options = file_options(args);
  int code = kExitOk;
  nlohmann::ordered_json items = nlohmann::ordered_json::array();
  for (const std::string& file : args.files) {
    const FileRepair r = repair_file(file, options);
    code = std::max(code, r.exit_code());
    if (r.exit_code() != kExitOk) streams.err << failure_line(r.failure) << "\n";
    if (args.json) {
      items.push_back(repair_json(r));
    } else if (streams.verbosity > 0 || r.exit_code() != kExitOk) {
      streams.out << repair_text(r, streams.verbosity);
    }
  }
  if (args.json) print_json_items(items, streams.out);
  return code;
}

}  // namespace

Runner add_repair_command(CLI::App& app) {
  auto args = std::make_shared<RepairArgs>();
  CLI::App* cmd = app.add_subcommand(
      "repair", "Make mesh files valid for fabrication, recording every change and the distance moved");
  cmd->add_option("MESH", args->files, "Mesh files to repair (STL, OBJ, PLY, OFF, Draco, 3MF, GLB, glTF)")
      ->required();
  cmd->add_option(
      "-o,--output", args->output,
      "Where to write: FILE.3mf (default format; also .stl .obj .ply .off) or FOLDER/ (FOLDER/STEM.3mf); "
      "default: STEM.repaired.3mf beside the input");
  cmd->add_option(
         "--max-deviation", args->max_deviation,
         "Refuse (exit 1) when the output would be farther than this from the input (model units); with "
         "--wrap also the wrap's detail; default: no limit")
      ->check(non_negative_number());
  cmd->add_flag(
      "--wrap", args->wrap,
      "Replace the mesh by a closed surface wrapped around it (CGAL alpha wrapping): always valid, lossy "
      "by design, its distance measured; alpha = --max-deviation / 2 (default 1% of the size)");
  cmd->add_option(
         "--weld-distance", args->weld_distance,
         "Merge border vertices closer than this (model units); default: chosen from the data and reported")
      ->check(non_negative_number());
  cmd->add_flag("--no-fill", args->no_fill, "Leave holes open (the mesh is then refused when it has any)");
  cmd->add_option("--max-seconds", args->max_seconds,
                  "Time budget of each self-intersection test, seconds (0: none); default 600")
      ->check(non_negative_number());
  cmd->add_flag("--dry-run", args->dry_run, "Repair and verify, write nothing");
  cmd->add_flag("--json", args->json, "Print the JSON reports (an array, one entry per file)");
  return [args](Streams streams) { return run_repair(*args, streams); };
}

}  // namespace fabmesh::cli
