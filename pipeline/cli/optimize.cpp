// fabmesh optimize DESIGN [--json]: fairest shape parameters of a design's curve.

#include <fmt/format.h>

#include <memory>
#include <nlohmann/json.hpp>

#include "geometry/core/errors.h"
#include "geometry/fairing/fair_curve.h"
#include "io/design/read_design.h"
#include "pipeline/cli/commands.h"
#include "pipeline/design_curves.h"

namespace fabmesh::cli {
namespace {

struct OptimizeArgs {
  std::string design;
  bool json = false;
};

nlohmann::json joints_json(const BuiltCurve& built) {
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t i = 0; i < built.joints.size(); ++i) {
    const JointReport& j = built.joints[i];
    out.push_back({{"before", j.before},
                   {"after", j.after},
                   {"closing", j.closing},
                   {"declared", i < built.declared.size() ? to_string(built.declared[i]) : "none"},
                   {"achieved", to_string(j.achieved)},
                   {"continuity_lost", i < built.declared.size() && j.achieved < built.declared[i]},
                   {"gap", j.gap},
                   {"tangent_angle", j.tangent_angle},
                   {"curvature_jump", j.curvature_jump}});
  }
  return out;
}

nlohmann::json optimize_curve(const NamedCurve& nc) {
  CurveSpec spec = nc.spec;
  nlohmann::json out;
  if (spec.family == CurveFamily::QuasiBSpline) {
    if (spec.fair == FairMode::None) spec.fair = FairMode::CurvatureVariation;
    const BuiltCurve built = build_curve(spec);
    out = {{"family", "quasi_bspline"},
           {"energy_kind", to_string(built.bspline->energy_kind)},
           {"lambdas", built.bspline->lambdas},
           {"energy", built.bspline->energy}};
    out["joints"] = joints_json(built);
    return out;
  }
  if (spec.family == CurveFamily::HBezier) {
    throw GeometryError(nc.name,
                        fmt::format("{}: optimize is defined for tbezier and quasi_bspline curves", nc.name));
  }
  spec.fair = FairMode::CurvatureVariation;
  const BuiltCurve built = build_curve(spec);
  out = {{"family", "tbezier"}, {"segments", nlohmann::json::array()}};
  for (const SegmentFairing& s : built.segments) {
    out["segments"].push_back({{"index", s.index}, {"lambda", s.lambda}, {"mu", s.mu}, {"energy", s.energy}});
  }
  out["joints"] = joints_json(built);
  return out;
}

void print_human(const std::string& name, const nlohmann::json& r, std::ostream& out) {
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
  for (const auto& j : r["joints"]) {
    out << fmt::format("  joint {} -> {}: declared {}, after fairing {}{}\n", j["before"].get<int>() + 1,
                       j["after"].get<int>() + 1, j["declared"].get<std::string>(),
                       j["achieved"].get<std::string>(),
                       j["continuity_lost"].get<bool>() ? "  (continuity lost by fairing)" : "");
  }
}

int run_optimize(const OptimizeArgs& args, Streams io) {
  const Design design = read_design(args.design);
  const auto curves = design_curves(design);
  if (curves.empty()) {
    throw InputError(
        fmt::format("{}: a {} design has no curves to optimize", design.common.path, design.common.kind));
  }
  nlohmann::json all = nlohmann::json::array();
  for (const NamedCurve& nc : curves) {
    nlohmann::json r = optimize_curve(nc);
    if (!args.json) print_human(design.common.name + " " + nc.name, r, io.out);
    if (curves.size() > 1) r["curve"] = nc.name;
    all.push_back(std::move(r));
  }
  if (args.json) io.out << (all.size() == 1 ? all[0] : all).dump(2) << "\n";
  return 0;
}

}  // namespace

Runner add_optimize_command(CLI::App& app) {
  auto args = std::make_shared<OptimizeArgs>();
  CLI::App* cmd = app.add_subcommand("optimize", "Fairest shape parameters of a design's curves");
  cmd->add_option("design", args->design, "Design file (YAML)")->required();
  cmd->add_flag("--json", args->json, "Print the result as JSON");
  return [args](Streams io) { return run_optimize(*args, io); };
}

}  // namespace fabmesh::cli
