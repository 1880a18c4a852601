// fabmesh optimize DESIGN [--json]: fairest shape parameters of a design's curve.

#include <fmt/format.h>

#include <memory>
#include <nlohmann/json.hpp>

#include "geometry/core/errors.h"
#include "geometry/fairing/build_curve.h"
#include "pipeline/cli/commands.h"
#include "pipeline/design_curves.h"
#include "pipeline/load_design.h"
#include "pipeline/report.h"

namespace fabmesh::cli {
namespace {

struct OptimizeArgs {
  std::string design;
  std::vector<std::string> defines;
  bool json = false;
};

// The fairest parameters of one curve as JSON, and the curve they give.
struct Optimized {
  nlohmann::ordered_json json;
  BuiltCurve built;
};

Optimized optimize_curve(const NamedCurve& nc) {
  CurveSpec spec = nc.spec;
  Optimized out;
  nlohmann::ordered_json& j = out.json;
  if (spec.family == CurveFamily::QuasiBSpline) {
    if (spec.fair == FairMode::None) spec.fair = FairMode::CurvatureVariation;
    out.built = build_curve(spec);
    j["family"] = "quasi_bspline";
    j["energy_kind"] = to_string(out.built.bspline->energy_kind);
    j["lambdas"] = out.built.bspline->lambdas;
    j["energy"] = out.built.bspline->energy;
  } else if (spec.family == CurveFamily::HBezier) {
    // At the curve's key (in_design places it): "cup.yaml:5:3: profile: ...".
    throw GeometryError(nc.name, "optimize is defined for tbezier and quasi_bspline curves, not hbezier");
  } else {
    spec.fair = FairMode::CurvatureVariation;
    spec.fair_keeps = Continuity::None;  // optimize reports what fairing would lose (continuity_lost)
    out.built = build_curve(spec);
    j["family"] = "tbezier";
    j["segments"] = nlohmann::ordered_json::array();
    for (const SegmentFairing& s : out.built.segments) {
      j["segments"].push_back({{"index", s.index}, {"lambda", s.lambda}, {"mu", s.mu}, {"energy", s.energy}});
    }
  }
  j["joints"] = joints_json(out.built);
  return out;
}

void print_human(const std::string& name, const Optimized& o, std::ostream& out) {
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
  const auto curves = design_curves(design);
  if (curves.empty()) {
    throw InputError(fmt::format("a {} design has no curves to optimize", kind_name(design)),
                     placed(design.common, ErrorLocation{"kind"}));
  }
  nlohmann::ordered_json all = nlohmann::ordered_json::array();
  for (const NamedCurve& nc : curves) {
    Optimized o = in_design(design, [&] { return optimize_curve(nc); });
    if (!args.json) print_human(design.common.name + " " + nc.name, o, io.out);
    nlohmann::ordered_json item = {{"design", args.design}, {"curve", nc.name}};
    item.update(o.json);
    all.push_back(std::move(item));
  }
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
