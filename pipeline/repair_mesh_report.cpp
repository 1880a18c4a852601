#include "pipeline/repair_mesh_report.h"

#include <fmt/format.h>

#include <algorithm>

#include "pipeline/report.h"

namespace fabmesh {
namespace {

using Json = nlohmann::ordered_json;

Json point_json(const Vec3& p) { return Json::array({p.x(), p.y(), p.z()}); }

Json index_json(std::uint32_t i) { return i == kNoIndex ? Json(nullptr) : Json(i); }

Json place_json(const RepairPlace& place) {
  Json j;
  j["face"] = index_json(place.face);
  j["vertex"] = index_json(place.vertex);
  j["point"] = point_json(place.point);
  if (!place.detail.empty()) j["detail"] = place.detail;
  return j;
}

Json action_json(const RepairAction& action) {
  Json j;
  j["step"] = to_key(action.step);
  j["count"] = action.count;
  if (!action.detail.empty()) j["detail"] = action.detail;
  Json places = Json::array();
  for (const RepairPlace& p : action.places) places.push_back(place_json(p));
  j["places"] = std::move(places);
  j["places_omitted"] = action.count - std::min(action.count, action.places.size());
  return j;
}

Json dropped_json(const DroppedComponent& d) {
  Json j;
  j["faces"] = d.faces;
  j["first_face"] = index_json(d.first_face);
  j["area"] = d.area;
  j["bounding_box"] = {{"min", point_json(d.lo)}, {"max", point_json(d.hi)}};
  j["why"] = d.why;
  return j;
}

Json bound_json(const DistanceBound& b) {
  return Json{{"upper", b.upper}, {"lower", b.lower}, {"at", point_json(b.at)}, {"faces_measured", b.faces}};
}

Json measure_json(const RepairMeasure& m) {
  Json j;
  j["bound"] = m.distance;
  j["input_to_output"] = bound_json(m.input_to_output);
  j["output_to_input"] = bound_json(m.output_to_input);
  j["unmeasured_input_faces"] = m.unmeasured_faces;
  return j;
}

std::string place_text(const RepairPlace& p) {
  std::string text = fmt::format("({:.6g}, {:.6g}, {:.6g})", p.point.x(), p.point.y(), p.point.z());
  if (p.face != kNoIndex) text += fmt::format(" face {}", p.face);
  if (p.vertex != kNoIndex) text += fmt::format(" vertex {}", p.vertex);
  if (!p.detail.empty()) text += ": " + p.detail;
  return text;
}

std::string result_text(const RepairResult& r, const std::string& indent, int verbosity) {
  std::string text;
  if (r.exact_welded > 0)
    text += fmt::format("{}welded {} coincident vertices first\n", indent, r.exact_welded);
  if (!r.changed) return text + indent + "valid as it is: nothing to repair\n";
  const std::size_t shown = verbosity >= 2 ? 20 : 3;
  for (const RepairAction& a : r.actions) {
    text += fmt::format("{}- {}: {}{}\n", indent, to_string(a.step), a.count,
                        a.detail.empty() ? "" : " (" + a.detail + ")");
    for (std::size_t i = 0; i < std::min(shown, a.places.size()); ++i)
      text += fmt::format("{}    at {}\n", indent, place_text(a.places[i]));
    if (a.count > std::min(shown, a.places.size()))
      text += fmt::format("{}    ... {} more (--json lists the first {})\n", indent,
                          a.count - std::min(shown, a.places.size()), a.places.size());
  }
  for (const DroppedComponent& d : r.dropped)
    text += fmt::format("{}- component of {} faces (first face {}, area {:.4g}) removed: {}\n", indent,
                        d.faces, d.first_face == kNoIndex ? std::string("-") : std::to_string(d.first_face),
                        d.area, d.why);
  text += fmt::format("{}components {} -> {}, volume {:.6g} -> {:.6g}, area {:.6g} -> {:.6g}\n", indent,
                      r.components_before, r.after.components, r.before.volume, r.after.volume, r.before.area,
                      r.after.area);
  text += fmt::format(
      "{}distance to the input at most {:.4g} (input to output {:.4g}, output to input {:.4g})\n", indent,
      r.measure.distance, r.measure.input_to_output.upper, r.measure.output_to_input.upper);
  for (const std::string& line : r.unresolved) text += fmt::format("{}! {}\n", indent, line);
  return text;
}

}  // namespace

Json repair_result_json(const RepairResult& r) {
  Json j;
  j["changed"] = r.changed;
  j["valid"] = r.ok();
  j["welded_vertices"] = r.exact_welded;
  j["weld"] = {{"distance", r.weld.distance}, {"considered_up_to", r.weld.cap}, {"why", r.weld.why}};
  Json steps = Json::array();
  for (const RepairAction& a : r.actions) steps.push_back(action_json(a));
  j["repairs"] = std::move(steps);
  Json dropped = Json::array();
  for (const DroppedComponent& d : r.dropped) dropped.push_back(dropped_json(d));
  j["dropped_components"] = std::move(dropped);
  j["components"] = {
      {"before", r.components_before}, {"after", r.after.components}, {"dropped", r.dropped.size()}};
  j["volume"] = {{"before", r.before.volume}, {"after", r.after.volume}};
  j["area"] = {{"before", r.before.area}, {"after", r.after.area}};
  j["distance"] = measure_json(r.measure);
  j["unresolved"] = r.unresolved;
  j["before"] = validation_json(r.before);
  j["after"] = validation_json(r.after);
  return j;
}

Json repair_json(const FileRepair& r) {
  Json j;
  j["file"] = r.file;
  j["format"] = r.format.empty() ? Json(nullptr) : Json(r.format);
  j["units"] = r.units.empty() ? Json(nullptr) : Json(r.units);
  j["notes"] = r.notes;
  j["status"] = to_string(status_of(r.exit_code()));
  j["exit_code"] = r.exit_code();
  j["message"] = r.failure.message;
  j["output"] = r.written ? Json(r.output) : Json(nullptr);
  j["output_format"] = r.output_format.empty() ? Json(nullptr) : Json(r.output_format);
  j["output_units"] = r.output_units.empty() ? Json(nullptr) : Json(r.output_units);
  j["solids"] = r.solids;
  j["valid_as_written"] = r.valid_as_written;
  j["writing_error"] = r.writing_error;
  j["distance"] = r.distance;
  if (r.objects.size() == 1) {
    j.update(repair_result_json(r.objects.front().result));
    j["distance"] = r.distance;
    j["distance_repair"] = measure_json(r.objects.front().result.measure);
  } else {
    j["changed"] = std::any_of(r.objects.begin(), r.objects.end(),
                               [](const RepairedObject& o) { return o.result.changed; });
    j["valid"] = r.exit_code() == 0;
    Json objects = Json::array();
    for (const RepairedObject& o : r.objects) {
      Json item{{"name", o.name}};
      item.update(repair_result_json(o.result));
      objects.push_back(std::move(item));
    }
    j["objects"] = std::move(objects);
  }
  j["timings_ms"] = timings_json(r.timings_ms);
  return j;
}

std::string repair_text(const FileRepair& r, int verbosity) {
  if (!r.readable) return fmt::format("{}: UNREADABLE: {}\n", r.file, r.failure.message);
  std::string verdict =
      r.exit_code() == 0 ? (r.written ? "written to " + r.output : "verified, not written") : "NOT REPAIRED";
  std::string text = fmt::format("{}: {} ({} file{}) -> {}\n", r.file,
                                 r.failure.exit_code == 0 ? r.failure.message : "invalid", r.format,
                                 r.units.empty() ? "" : ", unit " + r.units, verdict);
  for (const std::string& note : r.notes) text += "  " + note + "\n";
  for (const RepairedObject& o : r.objects) {
    if (r.objects.size() > 1) text += fmt::format("  object '{}':\n", o.name);
    text += result_text(o.result, r.objects.size() > 1 ? "    " : "  ", verbosity);
  }
  if (r.exit_code() == 0)
    text += fmt::format(
        "  {} solid{} as {}, valid as written; distance to the input at most {:.4g} (writing adds {:.3g})\n",
        r.solids, r.solids == 1 ? "" : "s", r.output_format, r.distance, r.writing_error);
  else if (r.failure.message.rfind("could not be made valid", 0) != 0)
    text += "  " + r.failure.message + "\n";
  else
    text += "  try --wrap: a closed surface wrapped around it, lossy by design, its distance measured\n";
  return text;
}

}  // namespace fabmesh
