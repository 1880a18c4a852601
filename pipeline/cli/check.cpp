// `fabmesh check MESH... [--json] [--weld-tolerance X] [--max-seconds S]`: validates mesh files
// made anywhere. Exit 0 when every mesh is valid, 1 when any is invalid, 2
// when any cannot be read, 6 when none is invalid but a self-intersection
// test did not finish (undetermined).

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <malloc.h>

#include <algorithm>
#include <cmath>
#include <limits>
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
#include "pipeline/check_mark.h"
#include "pipeline/check_mesh.h"
#include "pipeline/cli/commands.h"
#include "pipeline/failure.h"
#include "pipeline/report.h"

namespace fabmesh::cli {
namespace {

struct CheckArgs : CheckOptions {
  std::vector<std::string> files;
  bool json = false;
  std::string mark;  ///< --mark OUT.glb|OUT.ply: empty when not asked
};

/// Writes the marked mesh of `check` to args.mark; the legend lines (text mode).
std::string write_mark(const CheckArgs& args, const FileCheck& check) {
  const MarkedMesh marked = marked_mesh(check);
  write_marked(marked, args.mark);
  std::string text = fmt::format("  marked: {}\n", args.mark);
  for (const std::string& line : legend_lines(marked)) text += "    " + line + "\n";
  return text;
}

/// A volume or an area: "12.5 mm^3", or past the range of doubles (a mesh
/// of coordinates near 1e300), "beyond 1.8e+308 mm^3" (never "inf" or "nan").
std::string measure_text(double value, const std::string& unit) {
  if (std::isfinite(value)) return fmt::format("{:g}{}", value, unit);
  if (std::isnan(value)) return "not computed";
  return fmt::format("beyond {}{:g}{} (not representable)", value < 0 ? "-" : "",
                     std::numeric_limits<double>::max(), unit);
}

/// "(V vertices, T triangles, C components, genus G, volume X u^3, area Y u^2)".
std::string facts(const ValidationReport& r, const std::string& units) {
  std::string text = fmt::format("({} vertices, {} triangles, {} component{}", r.vertices, r.triangles,
                                 r.components, r.components == 1 ? "" : "s");
  if (r.genus) text += fmt::format(", genus {}", *r.genus);
  const std::string unit = units.empty() ? "" : " " + units;
  text += fmt::format(", volume {}, area {})", measure_text(r.volume, unit.empty() ? "" : unit + "^3"),
                      measure_text(r.area, unit.empty() ? "" : unit + "^2"));
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

/// "hint: --weld-tolerance 4e-05 closes every boundary edge ...", when welding would.
std::string hint_line(const ObjectCheck& object, const char* indent) {
  if (!object.weld_hint) return "";
  const WeldHint& h = *object.weld_hint;
  return fmt::format(
      "{}hint: --weld-tolerance {:g} closes every boundary edge and makes the mesh {} (welding {} more "
      "vertices; each boundary edge has another within {:.3g} at both ends, the mean edge is {:.3g})\n",
      indent, h.tolerance, h.valid_after ? "valid" : "closed, though not yet valid", h.merged_vertices,
      h.closing_distance, h.mean_edge);
}

std::string single_verdict(const FileCheck& check) {
  const ObjectCheck& only = check.objects.front();
  const ValidationReport& r = only.report;
  std::string text = fmt::format("{}: {} {}\n", check.file, check.facts.message, facts(r, check.units));
  text += file_lines(check);
  text += welded_line(check, only, "  ");
  for (const std::string& note : check.notes) text += "  " + note + "\n";
  for (const std::string& line : describe_defects(r)) text += "  - " + line + "\n";
  return text + hint_line(only, "  ");
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
    const char* verdict = o.report.valid() ? "valid" : o.report.defects.empty() ? "UNDETERMINED" : "INVALID";
    text += fmt::format("  object {} '{}': {} {}\n", i + 1, o.name, verdict, facts(o.report, check.units));
    text += welded_line(check, o, "    ");
    for (const std::string& line : describe_defects(o.report)) text += "    - " + line + "\n";
    text += hint_line(o, "    ");
  }
  return text + assembly_line(check);
}

/// The verdict in words; none for a file that could not be read (its error
/// is on standard error, once).
std::string human_verdict(const FileCheck& check) {
  if (!check.readable) return "";
  return check.several() ? several_verdict(check) : single_verdict(check);
}

/// `check` gives blocks of 1 MiB and more back as soon as they are freed,
/// where the program otherwise keeps those below 64 MiB for reuse
/// (pipeline/cli/main.cpp: between a batch's variants that pays). A check
/// goes through one large mesh in stages (the file's bytes, the raw soup,
/// the weld's buckets, the validation's arrays) whose blocks do not fit in
/// each other's holes: kept, they stayed resident beside the next stage's,
/// 209 against 197 MiB at the peak on a 1e6-triangle torus, and 209 against
/// 154 MiB through the validation (bench/README.md, "Mesh check").
void return_large_blocks_at_once() {
  mallopt(M_MMAP_THRESHOLD, 1 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 20);
}

int run_check(const CheckArgs& args, Streams streams) {
  return_large_blocks_at_once();
  if (args.weld_tolerance != 0.0) require_positive("--weld-tolerance", args.weld_tolerance);
  if (std::count(args.files.begin(), args.files.end(), "-") > 1)
    throw InputError("check: '-' (standard input) may be given once");
  if (!args.mark.empty() && args.files.size() != 1)
    throw InputError(
        fmt::format("--mark {}: marks the mesh of one file, not {}", args.mark, args.files.size()));
  std::vector<FileCheck> checks;
  int code = kExitOk;  // the worst file's: unreadable, then invalid, then undetermined
  for (const std::string& file : args.files) {
    checks.push_back(check_file(file, args));
    const FileCheck& c = checks.back();
    if (!c.readable) streams.err << failure_line(c.failure) << "\n";
    code = worst_check_code(code, exit_code_of(c));
    if (!args.json) streams.out << human_verdict(c);
    if (!args.mark.empty() && c.readable) {
      const std::string legend = write_mark(args, c);
      if (!args.json) streams.out << legend;
    }
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
  cmd->add_option("MESH", args->files,
                  "Mesh files to check ('-': standard input); the format is told by content")
      ->required();
  cmd->add_flag("--json", args->json, "Print the JSON reports (an array, one entry per file)");
  cmd->add_option("--weld-tolerance", args->weld_tolerance,
                  "Merge vertices closer than this (model units) before judging topology; default 0: only "
                  "exactly equal coordinates merge")
      ->check(non_negative_number());
  cmd->add_option("--max-locations", args->max_locations,
                  "With --json, list at most N occurrences of each defect kind with their faces, vertices "
                  "and coordinates (defect_locations; its count is always the total); default 100")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--mark", args->mark,
                  "Write the mesh with its defective faces coloured by defect kind to OUT.glb or OUT.ply "
                  "(one file only; the legend is printed)")
      ->option_text("OUT.glb|OUT.ply")
      ->each([args](const std::string&) { args->keep_for_marking = true; });
  cmd->add_option("--max-seconds", args->max_seconds,
                  "Time budget of each object's self-intersection test, seconds; past it the test stops "
                  "and, unless a defect was found, the verdict is UNDETERMINED (exit 6, 'self-intersection "
                  "test unfinished'); default 600, 0: no limit")
      ->check(non_negative_number());
  return [args](Streams streams) { return run_check(*args, streams); };
}

}  // namespace fabmesh::cli
