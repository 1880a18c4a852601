#include "pipeline/report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <type_traits>
#include <variant>

#include "geometry/core/errors.h"

namespace fabmesh {

namespace {

/// One object per component: faces, signed volume, orientation, and its
/// nesting (null when not determined).
nlohmann::ordered_json component_shells_json(const ValidationReport& r) {
  nlohmann::ordered_json shells = nlohmann::ordered_json::array();
  for (const ComponentShell& s : r.component_shells) {
    nlohmann::ordered_json j;
    j["faces"] = s.faces;
    j["volume"] = s.volume;
    j["orientation"] = s.outward ? "outward" : "inward";
    j["depth"] = s.depth ? nlohmann::ordered_json(*s.depth) : nlohmann::ordered_json(nullptr);
    j["inside"] = s.inside ? nlohmann::ordered_json(*s.inside) : nlohmann::ordered_json(nullptr);
    j["location"] = {s.location.x(), s.location.y(), s.location.z()};
    shells.push_back(std::move(j));
  }
  return shells;
}

}  // namespace

MeshFacts mesh_facts(const ValidationReport& v, const std::string& units) {
  MeshFacts m;
  m.units = units;
  m.vertices = v.vertices;
  m.triangles = v.triangles;
  m.volume = v.volume;
  m.area = v.area;
  m.valid = v.valid();
  return m;
}

MeshFacts mesh_facts(const Result& r) {
  const Part* part = product(r);
  MeshFacts m = mesh_facts(part != nullptr ? part->validation : ValidationReport{}, r.units);
  m.kind = r.kind;
  m.measured = r.purpose != MeshPurpose::Drawing;
  m.bbox_min = r.bbox_min;
  m.bbox_max = r.bbox_max;
  m.max_deviation = r.max_deviation;
  m.tolerance = r.tolerance;
  return m;
}

void set_written_verdict(ItemFacts& item, const MeshFacts& mesh) {
  const bool fit = !mesh.measured || mesh.valid;
  item.status = fit ? ItemStatus::Ok : ItemStatus::Invalid;
  item.message = !mesh.measured ? "drawing written"
                 : fit          ? kValidForFabrication
                                : "written for viewing only: not valid for fabrication";
}

ItemFacts item_facts(const Result& r) {
  ItemFacts item;
  item.name = r.name;
  item.mesh = mesh_facts(r);
  set_written_verdict(item, *item.mesh);
  item.files = written_paths(r);
  item.timings_ms = r.timings_ms;
  if (!r.parameter_set.empty()) item.remarks.push_back("parameter set: " + r.parameter_set);
  if (const Facts::Value* print = r.facts.find("print")) {
    if (const auto* group = std::get_if<Facts>(print); group != nullptr && group->contains("summary"))
      item.remarks.push_back(group->text("summary"));
  }
  for (const std::string& w : r.warnings) item.remarks.push_back("warning: " + w);
  return item;
}

ItemFacts failed_facts(const std::string& name, int exit_code, const std::string& message) {
  ItemFacts item;
  item.name = name;
  item.status = status_of(exit_code);
  item.message = message;
  return item;
}

ItemFacts check_facts(const std::string& file, const std::vector<MeshFacts>& objects) {
  ItemFacts item;
  item.name = file;
  const bool valid = std::all_of(objects.begin(), objects.end(), [](const MeshFacts& m) { return m.valid; });
  item.status = valid ? ItemStatus::Ok : ItemStatus::Invalid;
  item.message = valid ? "valid" : "INVALID";
  if (objects.size() == 1) item.mesh = objects.front();
  return item;
}

nlohmann::ordered_json validation_json(const ValidationReport& r) {
  nlohmann::ordered_json j;
  j["vertices"] = r.vertices;
  j["triangles"] = r.triangles;
  j["components"] = r.components;
  j["genus"] = r.genus ? nlohmann::ordered_json(*r.genus) : nlohmann::ordered_json(nullptr);
  j["volume"] = r.volume;
  j["area"] = r.area;
  j["topology"] = r.topology_proof.empty() ? "analysed" : "proven by construction";
  if (!r.topology_proof.empty()) j["topology_proof"] = r.topology_proof;
  j["watertight"] = r.boundary_edges == 0 && r.non_manifold_edges == 0;
  j["manifold"] = r.non_manifold_edges == 0 && r.non_manifold_vertices == 0;
  j["boundary_edges"] = r.boundary_edges;
  j["non_manifold_edges"] = r.non_manifold_edges;
  j["non_manifold_vertices"] = r.non_manifold_vertices;
  j["inconsistent_edges"] = r.inconsistent_edges;
  j["degenerate_faces"] = r.degenerate_faces;
  j["duplicate_faces"] = r.duplicate_faces;
  j["non_finite_vertices"] = r.non_finite_vertices;
  j["consistently_oriented"] = r.consistently_oriented;
  j["oriented_outward"] = r.oriented_outward;
  j["self_intersecting"] = r.self_intersecting;
  j["self_intersection"] = to_string(r.self_intersection);
  if (r.self_intersection == IntersectionCheck::ProvenByConstruction) {
    j["self_intersection_proof"] = r.embedding_proof;
    if (r.embedding_margin > 0.0) j["embedding_margin"] = r.embedding_margin;
  }
  j["intersecting_pairs"] = r.intersecting_pairs;
  j["component_shells"] = component_shells_json(r);
  j["undetermined_components"] = r.undetermined_components;
  j["defects"] = describe_defects(r);
  j["defect_kinds"] = nlohmann::ordered_json::array();
  for (const DefectReport& d : r.defects) j["defect_kinds"].push_back(to_key(d.kind));
  j["valid"] = r.valid();
  return j;
}

nlohmann::ordered_json timings_json(const StageTimings& timings, const std::string& prefix) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (const auto& [stage, ms] : timings) j[prefix + stage] = ms;
  return j;
}

nlohmann::ordered_json bounding_box_json(const MeshFacts& mesh) {
  const Vec3& lo = mesh.bbox_min;
  const Vec3& hi = mesh.bbox_max;
  const Vec3 size = hi - lo;
  nlohmann::ordered_json j;
  j["min"] = {lo.x(), lo.y(), lo.z()};
  j["max"] = {hi.x(), hi.y(), hi.z()};
  j["size"] = {size.x(), size.y(), size.z()};
  j["units"] = mesh.units;
  return j;
}

namespace {

// One fact's value as JSON; groups keep their keys in order of name.
nlohmann::json fact_json(const Facts::Value& value);

nlohmann::json group_json(const Facts& facts) {
  nlohmann::json j = nlohmann::json::object();
  for (const Facts::Entry& e : facts.entries()) j[e.name] = fact_json(e.value);
  return j;
}

nlohmann::json fact_json(const Facts::Value& value) {
  return std::visit(
      [](const auto& v) -> nlohmann::json {
        using V = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<V, Facts>) {
          return group_json(v);
        } else if constexpr (std::is_same_v<V, std::vector<Facts>>) {
          nlohmann::json list = nlohmann::json::array();
          for (const Facts& f : v) list.push_back(group_json(f));
          return list;
        } else {
          return nlohmann::json(v);
        }
      },
      value);
}

Facts::Value fact_from_json(const nlohmann::ordered_json& j, const std::string& name) {
  if (j.is_null()) return nullptr;
  if (j.is_boolean()) return j.get<bool>();
  if (j.is_number_integer()) return j.get<std::int64_t>();
  if (j.is_number()) return j.get<double>();
  if (j.is_string()) return j.get<std::string>();
  if (j.is_object()) return facts_from_json(j);
  if (!j.is_array()) throw InputError(fmt::format("build fact '{}': {} is not a fact", name, j.dump()));
  if (j.empty() || j.front().is_number()) {
    std::vector<double> numbers;
    for (const auto& x : j) {
      if (!x.is_number())
        throw InputError(fmt::format("build fact '{}': a list of numbers holds {}", name, x.dump()));
      numbers.push_back(x.get<double>());
    }
    return numbers;
  }
  if (j.front().is_string()) {
    std::vector<std::string> texts;
    for (const auto& x : j) {
      if (!x.is_string())
        throw InputError(fmt::format("build fact '{}': a list of texts holds {}", name, x.dump()));
      texts.push_back(x.get<std::string>());
    }
    return texts;
  }
  std::vector<Facts> groups;
  for (const auto& x : j) groups.push_back(facts_from_json(x));
  return groups;
}

}  // namespace

nlohmann::ordered_json facts_json(const Facts& facts) { return group_json(facts); }

Facts facts_from_json(const nlohmann::ordered_json& j) {
  if (!j.is_object()) throw InputError(fmt::format("build facts: {} is not an object", j.dump()));
  Facts facts;
  for (const auto& [name, value] : j.items()) facts.set(name, fact_from_json(value, name));
  return facts;
}

nlohmann::ordered_json part_json(const Part& part) {
  const ValidationReport& v = part.validation;
  nlohmann::ordered_json j;
  j["name"] = part.name;
  j["role"] = to_string(part.role);
  j["vertices"] = v.vertices;
  j["triangles"] = v.triangles;
  j["volume"] = v.volume;
  j["area"] = v.area;
  j["genus"] = v.genus ? nlohmann::ordered_json(*v.genus) : nlohmann::ordered_json(nullptr);
  j["self_intersection"] = to_string(v.self_intersection);
  j["valid"] = v.valid();
  return j;
}

nlohmann::ordered_json parameter_json(const DesignParameter& p) {
  switch (p.kind) {
    case ParameterKind::Choice:
      return p.text;
    case ParameterKind::Switch:
      return p.value != 0.0;
    case ParameterKind::Number:
      break;
  }
  return p.value;
}

nlohmann::ordered_json to_json(const Result& r) {
  const MeshFacts mesh = mesh_facts(r);
  nlohmann::ordered_json j;
  j["name"] = r.name;
  j["kind"] = mesh.kind;
  j["units"] = mesh.units;
  j["export_units"] = r.export_units;
  if (!r.parameters.empty()) {
    nlohmann::ordered_json parameters = nlohmann::ordered_json::object();
    for (const DesignParameter& p : r.parameters) parameters[p.name] = parameter_json(p);
    j["parameters"] = std::move(parameters);
  }
  if (!r.parameter_set.empty()) j["parameter_set"] = r.parameter_set;
  j["tolerance"] = mesh.tolerance;
  j["max_deviation"] = mesh.max_deviation;
  j["tolerance_split"] = {{"build", r.build_tolerance}, {"outputs", r.tolerance - r.build_tolerance}};
  if (!r.tolerance_shares.empty()) {
    nlohmann::ordered_json stages = nlohmann::ordered_json::array();
    for (const ToleranceShare& s : r.tolerance_shares) {
      nlohmann::ordered_json stage = {{"stage", s.stage}, {"given", s.given}};
      stage["used"] = s.done ? nlohmann::ordered_json(s.used) : nlohmann::ordered_json(nullptr);
      stages.push_back(std::move(stage));
    }
    j["tolerance_split"]["stages"] = std::move(stages);
  }
  j["bounding_box"] = bounding_box_json(mesh);
  j["outputs"] = written_paths(r);
  j["files"] = nlohmann::ordered_json::array();
  for (const OutputFile& f : r.files) {
    nlohmann::ordered_json file = {
        {"path", f.path}, {"format", f.format}, {"units", f.units}, {"max_added_error", f.added_error}};
    if (f.valid_as_written) file["valid_as_written"] = *f.valid_as_written;
    if (!f.parts.empty()) file["parts"] = f.parts;
    j["files"].push_back(std::move(file));
  }
  j["skipped_outputs"] = nlohmann::ordered_json::array();
  for (const SkippedOutput& s : r.skipped)
    j["skipped_outputs"].push_back({{"format", s.format}, {"reason", s.reason}});
  if (!r.notes.empty()) j["notes"] = r.notes;
  if (!r.warnings.empty()) j["warnings"] = r.warnings;
  j["purpose"] = r.purpose == MeshPurpose::Fabrication ? "fabrication"
                 : r.purpose == MeshPurpose::Viewing   ? "viewing"
                                                       : "drawing";
  if (const Part* part = product(r); part != nullptr && r.purpose != MeshPurpose::Drawing)
    j.update(validation_json(part->validation));
  j["parts"] = nlohmann::ordered_json::array();
  for (const Part& part : r.parts) j["parts"].push_back(part_json(part));
  if (const auto* fabrication = r.facts.find("fabrication")) j["fabrication"] = fact_json(*fabrication);
  if (!r.facts.empty()) j["build"] = facts_json(r.facts);
  nlohmann::ordered_json timings = timings_json(r.timings_ms);
  if (const Part* part = product(r)) timings.update(timings_json(part->validation.timings_ms, "validate."));
  j["timings_ms"] = timings;
  return j;
}

nlohmann::ordered_json design_item(const std::string& design_file, const Result& result) {
  nlohmann::ordered_json item = {{"design", design_file}};
  item.update(to_json(result));
  return item;
}

nlohmann::ordered_json error_item(const std::string& key, const std::string& input, const Failure& failure) {
  return {{key, input}, {"error", failure.message}, {"exit_code", failure.exit_code}};
}

void print_json_items(const nlohmann::ordered_json& items, std::ostream& out) {
  const bool shaped = items.is_array() && std::all_of(items.begin(), items.end(),
                                                      [](const auto& item) { return item.is_object(); });
  if (!shaped) throw std::logic_error("a --json document must be an array of objects");
  out << items.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) << "\n";
}

nlohmann::ordered_json joints_json(const BuiltCurve& built) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < built.joints.size(); ++i) {
    const JointReport& j = built.joints[i];
    nlohmann::ordered_json o;
    o["before"] = j.before;
    o["after"] = j.after;
    o["closing"] = j.closing;
    o["declared"] = i < built.declared.size() ? to_string(built.declared[i]) : "none";
    o["achieved"] = to_string(j.achieved);
    o["continuity_lost"] = i < built.declared.size() && j.achieved < built.declared[i];
    o["gap"] = j.gap;
    o["tangent_angle"] = j.tangent_angle;
    o["curvature_jump"] = j.curvature_jump;
    out.push_back(std::move(o));
  }
  return out;
}

std::string joint_line(const BuiltCurve& built, std::size_t joint) {
  const JointReport& j = built.joints[joint];
  const bool has_declared = joint < built.declared.size();
  const bool lost = has_declared && j.achieved < built.declared[joint];
  return fmt::format(
      "joint {} -> {}{}: declared {}, measured {} (gap {:.3g}, angle {:.3g} rad, curvature jump {:.3g}){}",
      j.before + 1, j.after + 1, j.closing ? " (closing)" : "",
      has_declared ? to_string(built.declared[joint]) : "-", to_string(j.achieved), j.gap, j.tangent_angle,
      j.curvature_jump, lost ? "  (continuity lost by fairing)" : "");
}

}  // namespace fabmesh
