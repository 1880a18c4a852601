#include "pipeline/parameter_schema.h"

#include <fmt/format.h>

#include <cmath>

#include "pipeline/report.h"

namespace fabmesh {
namespace {

// Whether `x` is a whole multiple of `step` as decimals written in the
// shortest round-trip form: the quotient, rounded, times the step gives x back.
bool multiple_of(double x, double step) {
  const double q = std::round(x / step);
  return std::abs(q * step - x) <= 1e-9 * std::max(std::abs(x), step);
}

}  // namespace

nlohmann::ordered_json parameter_schema(
    const Design& design, const std::function<std::optional<Design>(const std::string& set)>& with_set) {
  using Json = nlohmann::ordered_json;
  Json properties = Json::object();
  for (const DesignParameter& p : design.common.parameters) {
    if (p.kind != ParameterKind::Number) {
      Json j = p.kind == ParameterKind::Choice
                   ? Json{{"type", "string"}, {"enum", p.choices}, {"default", p.text}}
                   : Json{{"type", "boolean"}, {"default", p.value != 0.0}};
      if (!p.description.empty()) j["description"] = p.description;
      properties[p.name] = std::move(j);
      continue;
    }
    Json j = {{"type", "number"}, {"default", p.value}};
    if (p.min) j["minimum"] = *p.min;
    if (p.max) j["maximum"] = *p.max;
    if (p.step && *p.step > 0.0 && multiple_of(p.min.value_or(0.0), *p.step)) j["multipleOf"] = *p.step;
    if (!p.description.empty()) j["description"] = p.description;
    properties[p.name] = std::move(j);
  }
  Json examples = Json::array();
  if (!design.common.parameter_sets.empty()) {
    Json names = Json::array();
    for (const ParameterSet& set : design.common.parameter_sets) {
      names.push_back(set.name);
      const std::optional<Design> resolved = with_set(set.name);
      if (!resolved) continue;
      Json example = {{"parameter_set", set.name}};
      for (const auto& [name, written] : set.values) {
        for (const DesignParameter& p : resolved->common.parameters) {
          if (p.name == name) example[name] = parameter_json(p);
        }
      }
      examples.push_back(std::move(example));
    }
    Json j = {{"type", "string"},
              {"enum", std::move(names)},
              {"description",
               "a parameter set of the design (parameter_sets): its values apply, and the "
               "other properties given win over them"}};
    if (!design.common.parameter_set.empty()) j["default"] = design.common.parameter_set;
    properties["parameter_set"] = std::move(j);
  }
  Json schema = {
      {"$schema", "https://json-schema.org/draft/2020-12/schema"},
      {"title", design.common.name},
      {"description", fmt::format("The named parameters of the {} design {} ({}); each is set by name, "
                                  "as `fabmesh run -D NAME=VALUE` does",
                                  kind_name(design), design.common.path, design.common.units)},
      {"type", "object"},
      {"properties", std::move(properties)},
      {"additionalProperties", false}};
  if (!examples.empty()) schema["examples"] = std::move(examples);
  return schema;
}

}  // namespace fabmesh
