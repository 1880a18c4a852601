// fabmesh optimize DESIGN [--json]: fairest shape parameters of a design's curve.

#include "pipeline/optimize.h"

#include <fmt/format.h>

#include <memory>
#include <nlohmann/json.hpp>

#include "pipeline/cli/commands.h"
#include "pipeline/load_design.h"
#include "pipeline/report.h"

namespace fabmesh::cli {
namespace {

struct OptimizeArgs {
  std::string design;
  std::vector<std::string> defines;
  bool json = false;
};

void print_human(const std::string& name, const OptimizedCurve& o, std::ostream& out) {
  const nlohmann::ordered_json& r = o.json;
  if (r["family"] == "quasi_bspline") {
    out << fmt::format("{}: quasi_bspline, fairest lambdas for {} energy:\n", name,
                       r["energy_kind"].get<std::string>());
    const auto lambdas = r["lambdas"].get<std::vector<double>>();
    for (std::size_t i = 0; i < lambdas.size(); ++i)
      out << fmt::format("  lambda_{} = {:.6f}\n", i + 1, lambdas[i]);
    out << fmt::format("  energy = {:.6g}\n", r["energy"].get<double>());
  } else {
    out << fmt::format("{}: tbezier, fairest (lambda, mu) per segment for curvature-variation energy:\n",
                       name);
    for (const auto& s : r["segments"]) {
      out << fmt::format("  segment {}: lambda = {:.6f}, mu = {:.6f}, energy = {:.6g}\n",
                         s["index"].get<int>() + 1, s["lambda"].get<double>(), s["mu"].get<double>(),
                         s["energy"].get<double>());
    }
  }
  for (std::size_t i = 0; i < o.built.joints.size(); ++i) out << "  " << joint_line(o.built, i) << "\n";
}

int run_optimize(const OptimizeArgs& args, Streams io) {
  const Design design = load_design(args.design, parse_overrides(args.defines));
  const std::vector<OptimizedCurve> curves = optimize_design(design);
  if (!args.json) {
    for (const OptimizedCurve& c : curves) print_human(design.common.name + " " + c.name, c, io.out);
  }
  const nlohmann::ordered_json all = optimize_items(args.design, curves);
  if (args.json) print_json_items(all, io.out);
  return 0;
}

}  // namespace

Runner add_optimize_command(CLI::App& app) {
  auto args = std::make_shared<OptimizeArgs>();
  CLI::App* cmd = app.add_subcommand("optimize", "Fairest shape parameters of a design's curves");
  cmd->add_option("design", args->design, "Design file (YAML)")->required();
  add_define_option(cmd, args->defines);
  cmd->add_flag("--json", args->json, "Print the JSON results (an array, one entry per curve)");
  return [args](Streams io) { return run_optimize(*args, io); };
}

}  // namespace fabmesh::cli
