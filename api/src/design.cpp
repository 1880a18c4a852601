#include "fabmesh/design.h"

#include <memory>

#include "api/src/detail.h"
#include "io/design/overrides.h"
#include "pipeline/load_design.h"
#include "pipeline/output_table.h"

namespace fabmesh::api {
namespace {

Design handle(fabmesh::Design design) {
  return Design(std::make_shared<const detail::DesignData>(detail::DesignData{std::move(design)}));
}

// The library's overrides as the command line's `-D key=value`, checked the same way.
std::vector<fabmesh::Override> command_line_overrides(const Overrides& overrides) {
  std::vector<fabmesh::Override> out;
  out.reserve(overrides.size());
  for (const Override& o : overrides) out.push_back(fabmesh::make_override(o.key, o.value));
  return out;
}

}  // namespace

std::string Design::kind() const { return kind_name(data_->design); }
std::string Design::name() const { return data_->design.common.name; }
Unit Design::units() const { return unit_named(data_->design.common.units); }
double Design::tolerance() const { return data_->design.common.tolerance; }
std::filesystem::path Design::path() const { return data_->design.common.path; }

std::vector<std::string> Design::outputs() const {
  std::vector<std::string> names;
  for (const fabmesh::OutputFormat* f : fabmesh::resolve_outputs(data_->design)) names.emplace_back(f->name);
  return names;
}

std::vector<Parameter> Design::parameters() const {
  std::vector<Parameter> out;
  for (const fabmesh::DesignParameter& p : data_->design.common.parameters)
    out.push_back({p.name, p.value, p.min, p.max, p.step, p.description,
                   p.kind == fabmesh::ParameterKind::Choice   ? "choice"
                   : p.kind == fabmesh::ParameterKind::Switch ? "switch"
                                                              : "number",
                   p.text, p.choices});
  return out;
}

std::string Design::parameter_set() const { return data_->design.common.parameter_set; }

std::vector<std::string> Design::parameter_sets() const {
  std::vector<std::string> names;
  for (const fabmesh::ParameterSet& s : data_->design.common.parameter_sets) names.push_back(s.name);
  return names;
}

Design read_design(const std::filesystem::path& path, const Overrides& overrides) {
  return detail::translated(
      [&] { return handle(fabmesh::load_design(path.string(), command_line_overrides(overrides))); });
}

Design parse_design(std::string_view yaml_text, const Overrides& overrides,
                    const std::filesystem::path& source) {
  return detail::translated([&] {
    return handle(fabmesh::load_design_text(std::string(yaml_text), source.string(),
                                            command_line_overrides(overrides)));
  });
}

}  // namespace fabmesh::api
