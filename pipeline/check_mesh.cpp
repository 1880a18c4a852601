#include "pipeline/check_mesh.h"

#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <utility>

#include "geometry/core/errors.h"
#include "geometry/mesh/weld.h"
#include "geometry/mesh/weld_hint.h"
#include "io/mesh/read_mesh.h"
#include "pipeline/report.h"

namespace fabmesh {
namespace {

ValidationOptions validation_options(const CheckOptions& args) {
  ValidationOptions options;
  options.max_self_intersection_seconds = args.max_seconds;
  options.max_locations =
      args.keep_for_marking ? std::numeric_limits<std::size_t>::max() : args.max_locations;
  return options;
}

/// The weld hint of an object with boundary edges: a tolerance from the
/// data, larger than the one used, that closes every boundary edge when tried
/// on `soup` (the object as read, or as welded when its weld was exact:
/// `welded_already` then 0, else the vertices that weld merged).
std::optional<WeldHint> weld_hint(const TriangleSoup& soup, std::size_t welded_already,
                                  const ObjectCheck& object, const CheckOptions& args) {
  if (object.report.boundary_edges == 0) return std::nullopt;
  const std::optional<WeldCandidate> candidate = weld_candidate(object.welded);
  if (!candidate || candidate->tolerance <= args.weld_tolerance) return std::nullopt;
  WeldResult welded;
  try {
    welded = weld(soup, WeldOptions{candidate->tolerance});
  } catch (const RangeError&) {
    return std::nullopt;  // too small for the coordinates' magnitude
  }
  CheckOptions quick = args;  // only the verdict is wanted: no locations
  quick.max_locations = 0;
  quick.keep_for_marking = false;
  const ValidationReport after = validate(welded.soup, validation_options(quick));
  if (after.boundary_edges != 0) return std::nullopt;
  return WeldHint{candidate->tolerance, candidate->closing_distance, candidate->mean_edge,
                  welded.merged_vertices - welded_already, after.valid()};
}

/// One occurrence: its faces, its vertices by the file's numbering, and their coordinates.
nlohmann::ordered_json location_json(const DefectLocation& at, const WeldResult& welded) {
  nlohmann::ordered_json j;
  j["faces"] = at.faces;
  nlohmann::ordered_json vertices = nlohmann::ordered_json::array();
  nlohmann::ordered_json points = nlohmann::ordered_json::array();
  for (const std::uint32_t v : at.vertices) {
    vertices.push_back(welded.representatives[v]);
    const Vec3& p = welded.soup.vertices[v];
    points.push_back({p.x(), p.y(), p.z()});
  }
  j["vertices"] = std::move(vertices);
  j["points"] = std::move(points);
  return j;
}

/// `defect_locations`: per defect kind found, {count, listed, locations}.
nlohmann::ordered_json locations_json(const ValidationReport& report, const WeldResult& welded,
                                      std::size_t max_locations) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (const DefectReport& d : report.defects) {
    nlohmann::ordered_json kind;
    kind["count"] = d.count;
    const std::size_t listed = std::min(d.locations.size(), max_locations);
    kind["listed"] = listed;
    kind["locations"] = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < listed; ++i)
      kind["locations"].push_back(location_json(d.locations[i], welded));
    j[to_key(d.kind)] = std::move(kind);
  }
  return j;
}

// `soup` checked: welded, then validated. When `owned` is `soup` itself (the
// caller's copy, read from a file) and only exactly equal vertices merge, it
// is emptied after the weld: the weld hint can start from the welded soup (a
// weld by distance merges the same positions whether or not exact copies
// came first, and keeps the lowest index's), and the raw vertices, three
// per triangle of an STL, would otherwise stay in memory through validation.
ObjectCheck check_object(std::string name, const TriangleSoup& soup, const CheckOptions& args,
                         const StageTimings& before, TriangleSoup* owned = nullptr) {
  StageTimings timings = before;
  StageTimer timer(timings);
  WeldResult welded = weld(soup, WeldOptions{args.weld_tolerance});
  const bool exact = args.weld_tolerance == 0.0;
  if (exact && owned == &soup) *owned = {};  // `soup` is not used again
  timer.lap("weld");
  ObjectCheck result{
      std::move(name), validate(welded.soup, validation_options(args)), welded.merged_vertices, {}, {},
      std::nullopt};
  result.report.timings_ms.insert(result.report.timings_ms.begin(), timings.begin(), timings.end());
  result.defect_locations = locations_json(result.report, welded, args.max_locations);
  result.welded = std::move(welded.soup);
  if (result.report.boundary_edges > 0) {
    StageTimer hint_timer(result.report.timings_ms);
    result.weld_hint = exact ? weld_hint(result.welded, 0, result, args)
                             : weld_hint(soup, result.welded_vertices, result, args);
    hint_timer.lap("weld_hint");
  }
  return result;
}

nlohmann::ordered_json weld_hint_json(const std::optional<WeldHint>& hint) {
  if (!hint) return nullptr;
  nlohmann::ordered_json j;
  j["tolerance"] = hint->tolerance;
  j["closing_distance"] = hint->closing_distance;
  j["mean_edge"] = hint->mean_edge;
  j["merged_vertices"] = hint->merged_vertices;
  j["valid_after"] = hint->valid_after;
  return j;
}

/// The interpenetrating pairs of `objects`, the invalid ones not judged.
Interpenetration assembly_pairs(const std::vector<ObjectCheck>& objects) {
  std::vector<const TriangleSoup*> solids;
  solids.reserve(objects.size());
  for (const ObjectCheck& o : objects) solids.push_back(o.report.valid() ? &o.welded : nullptr);
  // Coordinates stored as float32 are within their rounding of where they were
  // made: surfaces that touched may cross by that much.
  return interpenetrating_pairs(solids, 0, float32_contact(solids));
}

/// The facts of each object of a file read, in the file's units.
std::vector<MeshFacts> object_facts(const FileCheck& check) {
  std::vector<MeshFacts> facts;
  for (const ObjectCheck& o : check.objects) facts.push_back(mesh_facts(o.report, check.units));
  return facts;
}

/// The item facts of a file read: check_facts, its message UNDETERMINED
/// when no defect was found but a check did not finish.
ItemFacts read_facts(const FileCheck& check) {
  ItemFacts facts = check_facts(check.file, object_facts(check));
  if (verdict_of(check) == CheckVerdict::Undetermined) facts.message = "UNDETERMINED";
  return facts;
}

/// An object with no defect found that is still not valid: a check did not finish.
bool undetermined(const ValidationReport& report) { return report.defects.empty() && !report.valid(); }

}  // namespace

const char* to_string(CheckVerdict verdict) {
  switch (verdict) {
    case CheckVerdict::Valid:
      return "valid";
    case CheckVerdict::Invalid:
      return "invalid";
    case CheckVerdict::Unreadable:
      return "unreadable";
    case CheckVerdict::Undetermined:
      return "undetermined";
  }
  return "unknown";
}

CheckVerdict verdict_of(const FileCheck& check) {
  if (!check.readable) return CheckVerdict::Unreadable;
  bool unfinished = false;
  for (const ObjectCheck& o : check.objects) {
    if (!o.report.defects.empty()) return CheckVerdict::Invalid;
    unfinished = unfinished || undetermined(o.report);
  }
  return unfinished ? CheckVerdict::Undetermined : CheckVerdict::Valid;
}

int exit_code_of(const FileCheck& check) {
  switch (verdict_of(check)) {
    case CheckVerdict::Valid:
      return kExitOk;
    case CheckVerdict::Invalid:
      return kExitInvalid;
    case CheckVerdict::Undetermined:
      return kExitUndetermined;
    case CheckVerdict::Unreadable:
      break;
  }
  return check.failure.exit_code;
}

int worst_check_code(int a, int b) {
  const auto rank = [](int code) {
    switch (code) {
      case kExitOk:
        return 0;
      case kExitUndetermined:
        return 1;
      case kExitInvalid:
        return 2;
      default:
        return 3 + code;  // bad input, internal, environment: by code
    }
  };
  return rank(a) >= rank(b) ? a : b;
}

FileCheck check_file(const std::string& path, const CheckOptions& args) {
  FileCheck result;
  result.file = path;
  try {
    StageTimings timings;
    StageTimer timer(timings);
    MeshFile file = path == "-" ? read_mesh_stream(std::cin, kStandardInputName) : read_mesh_file(path);
    result.format = to_string(file.format);
    result.units = file.units;
    result.notes = std::move(file.notes);
    timer.lap("read");
    if (file.objects.empty()) {
      result.objects.push_back(check_object("", file.soup, args, timings, &file.soup));
    } else {
      file.soup = {};  // the objects hold the same triangles
      result.timings_ms = timings;
      for (MeshObject& object : file.objects)
        result.objects.push_back(check_object(std::move(object.name), object.soup, args, {}, &object.soup));
      StageTimer assembly(result.timings_ms);
      result.assembly = assembly_pairs(result.objects);
      assembly.lap("assembly");
    }
    if (!args.keep_for_marking) {
      for (ObjectCheck& o : result.objects) o.welded = {};
    }
    result.readable = true;
    result.facts = read_facts(result);
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
  j["defect_locations"] = object.defect_locations;
  j["weld_hint"] = weld_hint_json(object.weld_hint);
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
    j["verdict"] = to_string(CheckVerdict::Unreadable);
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
    j["defect_locations"] = only.defect_locations;
    j["weld_hint"] = weld_hint_json(only.weld_hint);
    j["verdict"] = to_string(verdict_of(check));
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
  j["verdict"] = to_string(verdict_of(check));
  return j;
}

FileCheck check_soup(const TriangleSoup& soup, const CheckOptions& options) {
  // As a file's reader refuses a non-finite coordinate (bad input, exit 2),
  // so does a mesh given in memory: the same contract by either way in.
  for (std::size_t v = 0; v < soup.vertices.size(); ++v) {
    const Vec3& p = soup.vertices[v];
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z())) {
      throw InputError(fmt::format("vertices: vertex {} is ({}, {}, {}): coordinates must be finite", v,
                                   p.x(), p.y(), p.z()),
                       ErrorLocation{"vertices"});
    }
  }
  FileCheck result;
  result.objects.push_back(check_object("", soup, options, {}));
  if (!options.keep_for_marking) result.objects.front().welded = {};
  result.readable = true;
  result.facts = read_facts(result);
  return result;
}

}  // namespace fabmesh
