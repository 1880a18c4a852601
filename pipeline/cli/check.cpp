// `fabmesh check MESH... [--json] [--weld-tolerance X]`: validates mesh files
// made anywhere. Exit 0 when every mesh is valid, 1 when any is invalid, 2
// when any cannot be read.

#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "geometry/core/errors.h"
#include "geometry/core/stage_timer.h"
#include "geometry/mesh/weld.h"
#include "geometry/validation/validate.h"
#include "io/mesh/read_mesh.h"
#include "pipeline/cli/commands.h"
#include "pipeline/failure.h"
#include "pipeline/report.h"

namespace fabmesh::cli {
namespace {

struct CheckArgs {
  std::vector<std::string> files;
  bool json = false;
  double weld_tolerance = 0.0;
};

/// The outcome for one file: a report, or why it could not be read.
struct FileCheck {
  std::string file;
  std::optional<ValidationReport> report;
  std::string format;
  std::string units;  ///< as the file states it; empty for formats that carry none
  std::vector<std::string> notes;
  std::size_t welded_vertices = 0;
  Failure failure;  ///< why it could not be read, when there is no report
};

FileCheck check_file(const std::string& path, double weld_tolerance) {
  FileCheck result;
  result.file = path;
  try {
    StageTimings timings;
    StageTimer timer(timings);
    MeshFile file = read_mesh_file(path);
    result.format = to_string(file.format);
    result.units = file.units;
    result.notes = std::move(file.notes);
    timer.lap("read");
    WeldResult welded = weld(file.soup, WeldOptions{weld_tolerance});
    timer.lap("weld");
    ValidationReport report = validate(welded.soup);
    report.timings_ms.insert(report.timings_ms.begin(), timings.begin(), timings.end());
    result.report = std::move(report);
    result.welded_vertices = welded.merged_vertices;
  } catch (const InputError&) {
    result.failure = describe_failure(std::current_exception());
  }
  return result;
}

nlohmann::ordered_json to_json(const FileCheck& check) {
  nlohmann::ordered_json j;
  j["file"] = check.file;
  if (!check.report) {
    j["error"] = check.failure.message;
    j["valid"] = false;
    return j;
  }
  j["format"] = check.format;
  j["units"] = check.units.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(check.units);
  j["welded_vertices"] = check.welded_vertices;
  j["notes"] = check.notes;
  j.update(validation_json(*check.report));
  j["timings_ms"] = timings_json(check.report->timings_ms);
  return j;
}

std::string human_verdict(const FileCheck& check) {
  if (!check.report) return fmt::format("{}: UNREADABLE: {}\n", check.file, check.failure.message);
  const ValidationReport& r = *check.report;
  std::string text = fmt::format("{}: {} ({} vertices, {} triangles, {} component{}", check.file,
                                 r.valid() ? "valid" : "INVALID", r.vertices, r.triangles, r.components,
                                 r.components == 1 ? "" : "s");
  if (r.genus) text += fmt::format(", genus {}", *r.genus);
  const std::string unit = check.units.empty() ? "" : " " + check.units;
  text += fmt::format(", volume {:g}{}, area {:g}{})\n", r.volume, unit.empty() ? "" : unit + "^3", r.area,
                      unit.empty() ? "" : unit + "^2");
  text += fmt::format("  {} file{}{}\n", check.format,
                      check.units.empty() ? " (no unit in the file)" : ", unit " + check.units,
                      check.format == "GLB" || check.format == "glTF" ? ", Y up" : "");
  if (check.welded_vertices > 0) {
    text += fmt::format(
        "  welded {} coincident vertices{}\n", check.welded_vertices,
        check.format == "STL" ? " (normal for STL, which repeats every vertex per triangle)" : "");
  }
  for (const std::string& note : check.notes) text += "  " + note + "\n";
  for (const std::string& line : describe_defects(r)) text += "  - " + line + "\n";
  return text;
}

int run_check(const CheckArgs& args, Streams streams) {
  if (args.weld_tolerance != 0.0) require_positive("--weld-tolerance", args.weld_tolerance);
  std::vector<FileCheck> checks;
  int code = kExitOk;  // the worst file's: unreadable, then invalid
  for (const std::string& file : args.files) {
    checks.push_back(check_file(file, args.weld_tolerance));
    const FileCheck& c = checks.back();
    if (!c.report) {
      streams.err << failure_line(c.failure) << "\n";
      code = std::max(code, c.failure.exit_code);
    } else if (!c.report->valid()) {
      code = std::max(code, kExitInvalid);
    }
    if (!args.json) streams.out << human_verdict(c);
  }
  if (args.json) {
    nlohmann::ordered_json out;
    if (checks.size() == 1) {
      out = to_json(checks.front());
    } else {
      out = nlohmann::ordered_json::array();
      for (const FileCheck& c : checks) out.push_back(to_json(c));
    }
    streams.out << out.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) << "\n";
  }
  return code;
}

}  // namespace

Runner add_check_command(CLI::App& app) {
  auto args = std::make_shared<CheckArgs>();
  CLI::App* cmd = app.add_subcommand(
      "check", "Validate mesh files (STL, OBJ, PLY, OFF, Draco, 3MF, GLB, glTF) for fabrication");
  cmd->add_option("MESH", args->files, "Mesh files to check; the format is told by content")->required();
  cmd->add_flag("--json", args->json, "Print a JSON report per file (an array for several files)");
  cmd->add_option("--weld-tolerance", args->weld_tolerance,
                  "Merge vertices closer than this (model units) before judging topology; default 0: only "
                  "exactly equal coordinates merge")
      ->check(CLI::NonNegativeNumber);
  return [args](Streams streams) { return run_check(*args, streams); };
}

}  // namespace fabmesh::cli
