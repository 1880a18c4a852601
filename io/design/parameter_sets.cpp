// Parameter sets of design files (docs/design-files.md, "Parameter sets").

#include "io/design/yaml/parameter_sets.h"

#include <fmt/format.h>

#include <string>

#include "io/design/read_design.h"
#include "io/design/yaml/design_tree.h"

namespace fabmesh::yaml {
namespace {

constexpr std::size_t kMaxSets = 1000;

std::string names_of(const YAML::Node& map) {
  std::string out;
  if (!map.IsDefined() || !map.IsMap()) return out;
  for (const auto& kv : map) out += (out.empty() ? "" : ", ") + kv.first.Scalar();
  return out;
}

void check_sets(const YAML::Node& root, const Fields& f) {
  const YAML::Node sets = root["parameter_sets"];
  if (!sets.IsDefined() || !sets.IsMap() || sets.size() == 0) {
    f.fail(sets, "parameter_sets",
           "expected a map of set names to parameter values, e.g. parameter_sets: {small: {height: 5}}");
  }
  if (sets.size() > kMaxSets)
    f.fail(sets, "parameter_sets",
           fmt::format("{} sets; a design declares at most {}", sets.size(), kMaxSets));
  // (A const lookup of a missing key is an invalid node: IsDefined before IsMap.)
  const YAML::Node parameters = root["parameters"];
  if (!parameters.IsDefined() || !parameters.IsMap()) {
    f.fail(sets, "parameter_sets",
           "the design declares no parameters: a set gives values to `parameters`, e.g. "
           "parameters: {height: 10} and parameter_sets: {tall: {height: 14}}");
  }
  for (const auto& set : sets) {
    const std::string problem = set.first.IsScalar() ? parameter_set_name_problem(set.first.Scalar())
                                                     : "a set's name is a plain name, not a list or a map";
    if (!problem.empty()) f.fail_key(set.first, set.second, "parameter_sets", problem);
    const std::string field = "parameter_sets." + set.first.Scalar();
    if (!set.second.IsMap() || set.second.size() == 0) {
      f.fail(set.second, field,
             "expected a map of parameters to values, e.g. {height: 14, wall: 0.4} (at least one)");
    }
    for (const auto& entry : set.second) {
      const std::string name = entry.first.IsScalar() ? entry.first.Scalar() : std::string();
      const std::string at = fmt::format("{}.{}", field, name);
      if (name.empty() || !parameters[name].IsDefined()) {
        f.fail_key(entry.first, entry.second, at,
                   fmt::format("{:?} is not a parameter of the design (the parameters are: {})", name,
                               names_of(parameters)));
      }
      if (!entry.second.IsScalar()) {
        f.fail(entry.second, at, "expected a number or an expression \"=...\", the parameter's value");
      }
      const YAML::Node declared = parameters[name].IsMap() ? parameters[name]["value"] : parameters[name];
      const bool choice = parameters[name].IsMap() && parameters[name]["choices"].IsDefined();
      if (is_switch_value(declared) && !is_switch_value(entry.second))
        f.fail(entry.second, at, fmt::format("{} is a switch: true or false", name));
      if (!choice && !is_switch_value(declared) && is_switch_value(entry.second))
        f.fail(entry.second, at, fmt::format("{} is a number, not a switch", name));
    }
  }
}

}  // namespace

bool edits_parameter_sets(const std::string& override_path) {
  const std::string key = "parameter_sets";
  return override_path.compare(0, key.size(), key) == 0 &&
         (override_path.size() == key.size() || override_path[key.size()] == '.' ||
          override_path[key.size()] == '[');
}

// NOLINTNEXTLINE(performance-unnecessary-value-param): a handle, the tree is changed through it
void apply_parameter_set(YAML::Node root, const Fields& f) {
  if (root["parameter_sets"].IsDefined()) check_sets(root, f);
  const YAML::Node chosen = root["parameter_set"];
  if (!chosen.IsDefined() || chosen.IsNull()) return;  // `parameter_set: null`: none
  const std::string name = f.text(chosen, "parameter_set");
  const YAML::Node sets = root["parameter_sets"];
  if (!sets.IsDefined()) {
    f.fail(chosen, "parameter_set",
           fmt::format("no parameter set '{}': the design declares no parameter_sets", name));
  }
  const YAML::Node set = sets[name];
  if (!set.IsDefined()) {
    f.fail(chosen, "parameter_set",
           fmt::format("no parameter set '{}' (the sets are: {})", name, names_of(sets)));
  }
  YAML::Node parameters = root["parameters"];
  for (const auto& entry : set) {
    const std::string parameter = entry.first.Scalar();
    // The set's own node (its mark, its expression), where the value was.
    if (parameters[parameter].IsMap()) {
      parameters[parameter]["value"] = entry.second;
    } else {
      parameters[parameter] = entry.second;
    }
  }
}

std::vector<ParameterSet> parameter_sets_of(const YAML::Node& root) {
  std::vector<ParameterSet> out;
  const YAML::Node sets = root["parameter_sets"];
  if (!sets.IsDefined() || !sets.IsMap()) return out;
  for (const auto& set : sets) {
    ParameterSet s{set.first.Scalar(), {}};
    for (const auto& entry : set.second) s.values.emplace_back(entry.first.Scalar(), entry.second.Scalar());
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace fabmesh::yaml
