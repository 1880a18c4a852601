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

#include "geometry/core/errors.h"
#include "geometry/core/stage_timer.h"
#include "geometry/mesh/interpenetration.h"
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
  double max_seconds = 600.0;  ///< time budget of each object's self-intersection test (0: none)
};

/// One object of a file, welded and validated.
struct ObjectCheck {
  std::string name;  ///< empty for a file of one object
  ValidationReport report;
  std::size_t welded_vertices = 0;
  TriangleSoup welded;  ///< kept for the assembly test when the file has several objects
};

/// The outcome for one file: a report per object, or why it could not be read.
struct FileCheck {
  std::string file;
  bool readable = false;
  std::string format;
  std::string units;  ///< as the file states it; empty for formats that carry none
  std::vector<std::string> notes;
  std::vector<ObjectCheck> objects;  ///< one for a single-object file
  /// Several objects: the pairs of them that interpenetrate (indices into objects).
  Interpenetration assembly;
  StageTimings timings_ms;  ///< several objects: read and assembly
  Failure failure;          ///< why it could not be read, when not readable
  ItemFacts facts;          ///< its verdict: check_facts, or failed_facts when not readable

  bool several() const { return objects.size() > 1; }
  bool valid() const { return facts.status == ItemStatus::Ok; }
};

ObjectCheck check_object(std::string name, const TriangleSoup& soup, const CheckArgs& args,
                         const StageTimings& before) {
  StageTimings timings = before;
  StageTimer timer(timings);
  WeldResult welded = weld(soup, WeldOptions{args.weld_tolerance});
  timer.lap("weld");
  ValidationOptions options;
  options.max_self_intersection_seconds = args.max_seconds;
  ObjectCheck result{std::move(name), validate(welded.soup, options), welded.merged_vertices, {}};
  result.report.timings_ms.insert(result.report.timings_ms.begin(), timings.begin(), timings.end());
  result.welded = std::move(welded.soup);
  return result;
}

/// The interpenetrating pairs of `objects`, the invalid ones not judged.
Interpenetration assembly_pairs(const std::vector<ObjectCheck>& objects) {
  std::vector<const TriangleSoup*> solids;
  solids.reserve(objects.size());
  for (const ObjectCheck& o : objects) solids.push_back(o.report.valid() ? &o.welded : nullptr);
  return interpenetrating_pairs(solids);
}

/// The facts of each object of a file read, in the file's units.
std::vector<MeshFacts> object_facts(const FileCheck& check) {
  std::vector<MeshFacts> facts;
  for (const ObjectCheck& o : check.objects) facts.push_back(mesh_facts(o.report, check.units));
  return facts;
}

FileCheck check_file(const std::string& path, const CheckArgs& args) {
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
    if (file.objects.empty()) {
      result.objects.push_back(check_object("", file.soup, args, timings));
    } else {
      file.soup = {};  // the objects hold the same triangles
      result.timings_ms = timings;
      for (MeshObject& object : file.objects)
        result.objects.push_back(check_object(std::move(object.name), object.soup, args, {}));
      StageTimer assembly(result.timings_ms);
      result.assembly = assembly_pairs(result.objects);
      assembly.lap("assembly");
    }
    for (ObjectCheck& o : result.objects) o.welded = {};
    result.readable = true;
    result.facts = check_facts(path, object_facts(result));
  } catch (const InputError&) {
    result.failure = describe_failure(std::current_exception());
    result.facts = failed_facts(path, result.failure.exit_code, result.failure.message);
  }
  return result;
}

nlohmann::ordered_json object_json(const ObjectCheck& object) {
  nlohmann::ordered_json j;
  j["welded_vertices"] = object.welded_vertices;
  j.update(validation_json(object.report));
  j["timings_ms"] = timings_json(object.report.timings_ms);
  return j;
}

nlohmann::ordered_json assembly_json(const FileCheck& check) {
  nlohmann::ordered_json j;
  j["objects"] = check.objects.size();
  nlohmann::ordered_json judged = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < check.objects.size(); ++i) {
    if (check.objects[i].report.valid()) judged.push_back(i);
  }
  j["judged"] = judged;
  nlohmann::ordered_json pairs = nlohmann::ordered_json::array();
  for (const auto& [a, b] : check.assembly.pairs) pairs.push_back({a, b});
  j["interpenetrating"] = pairs;
  j["complete"] = check.assembly.complete;
  return j;
}

nlohmann::ordered_json to_json(const FileCheck& check) {
  if (!check.readable) {
    nlohmann::ordered_json j = error_item("file", check.file, check.failure);
    j["valid"] = false;  // every item of `check --json` says whether its file is valid
    return j;
  }
  nlohmann::ordered_json j;
  j["file"] = check.file;
  j["format"] = check.format;
  j["units"] = check.units.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(check.units);
  if (!check.several()) {
    const ObjectCheck& only = check.objects.front();
    j["welded_vertices"] = only.welded_vertices;
    j["notes"] = check.notes;
    j.update(validation_json(only.report));
    j["timings_ms"] = timings_json(only.report.timings_ms);
    return j;
  }
  j["notes"] = check.notes;
  nlohmann::ordered_json objects = nlohmann::ordered_json::array();
  for (const ObjectCheck& o : check.objects) {
    nlohmann::ordered_json entry;
    entry["name"] = o.name;
    entry.update(object_json(o));
    objects.push_back(std::move(entry));
  }
  j["objects"] = std::move(objects);
  j["assembly"] = assembly_json(check);
  j["valid"] = check.valid();
  j["timings_ms"] = timings_json(check.timings_ms);
  return j;
}

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
    for (const FileCheck& c : checks) items.push_back(to_json(c));
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
