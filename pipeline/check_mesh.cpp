#include "pipeline/check_mesh.h"

#include <utility>

#include "geometry/core/errors.h"
#include "geometry/mesh/weld.h"
#include "io/mesh/read_mesh.h"
#include "pipeline/report.h"

namespace fabmesh {
namespace {

ObjectCheck check_object(std::string name, const TriangleSoup& soup, const CheckOptions& args,
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

}  // namespace

FileCheck check_file(const std::string& path, const CheckOptions& args) {
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

namespace {

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

}  // namespace

nlohmann::ordered_json check_json(const FileCheck& check) {
  if (!check.readable) {
    nlohmann::ordered_json j = error_item("file", check.file, check.failure);
    j["valid"] = false;  // every item of `check --json` says whether its file is valid
    return j;
  }
  nlohmann::ordered_json j;
  j["file"] = check.file.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(check.file);
  j["format"] = check.format.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(check.format);
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

FileCheck check_soup(const TriangleSoup& soup, const CheckOptions& options) {
  FileCheck result;
  result.objects.push_back(check_object("", soup, options, {}));
  result.objects.front().welded = {};
  result.readable = true;
  result.facts = check_facts("", object_facts(result));
  return result;
}

}  // namespace fabmesh
