// `fabmesh check MESH... [--json] [--weld-tolerance X] [--max-seconds S]`: validates mesh files
// made anywhere. Exit 0 when every mesh is valid, 1 when any is invalid, 2
// when any cannot be read.

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "geometry/core/error_checks.h"
#include "geometry/core/stage_timer.h"
#include "geometry/mesh/interpenetration.h"
#include "geometry/validation/validate.h"
#include "pipeline/check_mesh.h"
#include "pipeline/cli/commands.h"
#include "pipeline/failure.h"
#include "pipeline/report.h"

namespace fabmesh::cli {
namespace {

struct CheckArgs : CheckOptions {
  std::vector<std::string> files;
  bool json = false;
};

/// "(V vertices, T triangles, C components, genus G, volume X u^3, area Y u^2)".
std::string facts(const ValidationReport& r, const std::string& units) {
  std::string text = fmt::format("({} vertices, {} triangles, {} component{}", r.vertices, r.triangles,
                                 r.components, r.components == 1 ? "" : "s");
  if (r.genus) text += fmt::format(", genus {}", *r.genus);
  const std::string unit = units.empty() ? "" : " " + units;
  text += fmt::format(", volume {:g}{}, area {:g}{})", r.volume, unit.empty() ? "" : unit + "^3", r.area,
                      unit.empty() ? "" : unit + "^2");
  return text;
}

/// The file's format and unit line, then its notes.
std::string file_lines(const FileCheck& check) {
  std::string text = fmt::format("  {} file{}{}\n", check.format,
                                 check.units.empty() ? " (no unit in the file)" : ", unit " + check.units,
                                 check.format == "GLB" || check.format == "glTF" ? ", Y up" : "");
  return text;
}

std::string welded_line(const FileCheck& check, const ObjectCheck& object, const char* indent) {
  if (object.welded_vertices == 0) return "";
  return fmt::format(
      "{}welded {} coincident vertices{}\n", indent, object.welded_vertices,
      check.format == "STL" ? " (normal for STL, which repeats every vertex per triangle)" : "");
}

std::string single_verdict(const FileCheck& check) {
  const ObjectCheck& only = check.objects.front();
  const ValidationReport& r = only.report;
  std::string text = fmt::format("{}: {} {}\n", check.file, check.facts.message, facts(r, check.units));
  text += file_lines(check);
  text += welded_line(check, only, "  ");
  for (const std::string& note : check.notes) text += "  " + note + "\n";
  for (const std::string& line : describe_defects(r)) text += "  - " + line + "\n";
  return text;
}

/// "assembly: 3 objects, none interpenetrating" or naming the pairs.
std::string assembly_line(const FileCheck& check) {
  std::string text = fmt::format("  assembly: {} objects, ", check.objects.size());
  if (check.assembly.pairs.empty()) {
    text += "none interpenetrating";
  } else {
    std::vector<std::string> pairs;
    for (const auto& [a, b] : check.assembly.pairs) {
      pairs.push_back(
          fmt::format("{} '{}' and {} '{}'", a + 1, check.objects[a].name, b + 1, check.objects[b].name));
    }
    text += fmt::format("interpenetrating: {}", fmt::join(pairs, ", "));
  }
  const auto judged = std::count_if(check.objects.begin(), check.objects.end(),
                                    [](const ObjectCheck& o) { return o.report.valid(); });
  if (static_cast<std::size_t>(judged) < check.objects.size())
    text += fmt::format(" (judged among the {} valid: an invalid object has no inside)", judged);
  if (!check.assembly.complete) text += " (the search stopped at its work bound: later pairs not tested)";
  return text + "\n";
}

std::string several_verdict(const FileCheck& check) {
  const auto valid = std::count_if(check.objects.begin(), check.objects.end(),
                                   [](const ObjectCheck& o) { return o.report.valid(); });
  std::string text = fmt::format("{}: {} ({} objects, {} valid)\n", check.file, check.facts.message,
                                 check.objects.size(), valid);
  text += file_lines(check);
  for (const std::string& note : check.notes) text += "  " + note + "\n";
  for (std::size_t i = 0; i < check.objects.size(); ++i) {
    const ObjectCheck& o = check.objects[i];
    text += fmt::format("  object {} '{}': {} {}\n", i + 1, o.name, o.report.valid() ? "valid" : "INVALID",
                        facts(o.report, check.units));
    text += welded_line(check, o, "    ");
    for (const std::string& line : describe_defects(o.report)) text += "    - " + line + "\n";
  }
  return text + assembly_line(check);
}

std::string human_verdict(const FileCheck& check) {
  if (!check.readable) return fmt::format("{}: UNREADABLE: {}\n", check.file, check.failure.message);
  return check.several() ? several_verdict(check) : single_verdict(check);
}

int run_check(const CheckArgs& args, Streams streams) {
  if (args.weld_tolerance != 0.0) require_positive("--weld-tolerance", args.weld_tolerance);
  std::vector<FileCheck> checks;
  int code = kExitOk;  // the worst file's: unreadable, then invalid
  for (const std::string& file : args.files) {
    checks.push_back(check_file(file, args));
    const FileCheck& c = checks.back();
    if (!c.readable) streams.err << failure_line(c.failure) << "\n";
    code = std::max(code, exit_code_of(c.facts.status));
    if (!args.json) streams.out << human_verdict(c);
  }
  if (args.json) {
    nlohmann::ordered_json items = nlohmann::ordered_json::array();
    for (const FileCheck& c : checks) items.push_back(check_json(c));
    print_json_items(items, streams.out);
  }
  return code;
}

}  // namespace

Runner add_check_command(CLI::App& app) {
  auto args = std::make_shared<CheckArgs>();
  CLI::App* cmd = app.add_subcommand(
      "check", "Validate mesh files (STL, OBJ, PLY, OFF, Draco, 3MF, GLB, glTF) for fabrication");
  cmd->add_option("MESH", args->files, "Mesh files to check; the format is told by content")->required();
  cmd->add_flag("--json", args->json, "Print the JSON reports (an array, one entry per file)");
  cmd->add_option("--weld-tolerance", args->weld_tolerance,
                  "Merge vertices closer than this (model units) before judging topology; default 0: only "
                  "exactly equal coordinates merge")
      ->check(non_negative_number());
  cmd->add_option("--max-seconds", args->max_seconds,
                  "Time budget of each object's self-intersection test, seconds; past it the test stops "
                  "and the mesh is not called valid (exit 1, 'self-intersection test unfinished'); "
                  "default 600, 0: no limit")
      ->check(non_negative_number());
  return [args](Streams streams) { return run_check(*args, streams); };
}

}  // namespace fabmesh::cli
