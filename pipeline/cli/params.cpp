// fabmesh params DESIGN [-D ...] [--json]: the design's named parameters, as
// a table or as a JSON Schema (draft 2020-12) of the overrides it takes.

#include <fmt/format.h>

#include <memory>
#include <optional>

#include "pipeline/cli/commands.h"
#include "pipeline/load_design.h"
#include "pipeline/parameter_schema.h"

namespace fabmesh::cli {
namespace {

struct ParamsArgs {
  std::string design;
  std::vector<std::string> defines;
  bool json = false;
};

int run_params(const ParamsArgs& args, Streams io) {
  const std::vector<Override> overrides = parse_overrides(args.defines);
  const Design design = load_design(args.design, overrides);
  // The design with one of its sets alone (no -D: the set's own values),
  // which checks them and gives them resolved.
  const auto with_set = [&](const std::string& set) {
    return load_design(args.design, {make_override("parameter_set", set)});
  };
  if (args.json) {
    io.out << parameter_schema(design, [&](const std::string& set) { return std::optional(with_set(set)); })
                  .dump(2)
           << "\n";
    return 0;
  }
  const std::vector<DesignParameter>& parameters = design.common.parameters;
  if (parameters.empty()) {
    io.out << fmt::format("# {}: no named parameters (`parameters:` in the design declares them)\n",
                          design.common.name);
    return 0;
  }
  io.out << fmt::format("# {}: {} named parameter(s), set with -D NAME=VALUE\n", design.common.name,
                        parameters.size());
  for (const DesignParameter& p : parameters) {
    std::string range;
    if (p.min || p.max) {
      range = fmt::format(" in [{}, {}]", p.min ? fmt::format("{:g}", *p.min) : std::string("-inf"),
                          p.max ? fmt::format("{:g}", *p.max) : std::string("inf"));
    }
    if (p.step) range += fmt::format(", step {:g}", *p.step);
    if (p.kind == ParameterKind::Choice) {
      std::string choices;
      for (const std::string& c : p.choices) choices += (choices.empty() ? "" : ", ") + c;
      range = fmt::format(", one of {}", choices);
    } else if (p.kind == ParameterKind::Switch) {
      range = ", true or false";
    }
    const std::string value = p.kind == ParameterKind::Number ? fmt::format("{:g}", p.value) : p.text;
    io.out << fmt::format("{} = {}{}{}\n", p.name, value, range,
                          p.description.empty() ? std::string() : ": " + p.description);
  }
  if (!design.common.parameter_sets.empty()) {
    io.out << fmt::format("# {} parameter set(s), used with -P NAME{}\n", design.common.parameter_sets.size(),
                          design.common.parameter_set.empty()
                              ? std::string()
                              : fmt::format(" (the values above use set '{}')", design.common.parameter_set));
    for (const ParameterSet& set : design.common.parameter_sets) {
      const Design resolved = with_set(set.name);
      std::string values;
      for (const auto& [name, written] : set.values) {
        for (const DesignParameter& p : resolved.common.parameters) {
          if (p.name != name) continue;
          values += fmt::format("{}{}={}", values.empty() ? "" : ", ", name,
                                p.kind == ParameterKind::Number ? fmt::format("{:g}", p.value) : p.text);
          if (!written.empty() && written.front() == '=') values += " (" + written + ")";
        }
      }
      io.out << fmt::format("{}: {}\n", set.name, values);
    }
  }
  return 0;
}

}  // namespace

Runner add_params_command(CLI::App& app) {
  auto args = std::make_shared<ParamsArgs>();
  CLI::App* cmd = app.add_subcommand(
      "params", "Print a design's named parameters, or with --json their JSON Schema (draft 2020-12)");
  cmd->add_option("design", args->design, "Design file (YAML)")->required();
  add_define_option(cmd, args->defines);
  cmd->add_flag("--json", args->json,
                "Print a JSON Schema of the overrides the design takes by parameter name, for web forms");
  return [args](Streams io) { return run_params(*args, io); };
}

}  // namespace fabmesh::cli
