#include "pipeline/optimize.h"

#include <fmt/format.h>

#include "geometry/core/errors.h"
#include "pipeline/design_curves.h"
#include "pipeline/load_design.h"
#include "pipeline/report.h"

namespace fabmesh {
namespace {

// The fairest parameters of one curve as JSON, and the curve they give.
OptimizedCurve optimize_curve(const NamedCurve& nc) {
  CurveSpec spec = nc.spec;
  OptimizedCurve out;
  out.name = nc.name;
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

}  // namespace

std::vector<OptimizedCurve> optimize_design(const Design& design) {
  const std::vector<NamedCurve> curves = design_curves(design);
  if (curves.empty()) {
    throw InputError(fmt::format("a {} design has no curves to optimize", kind_name(design)),
                     placed(design.common, ErrorLocation{"kind"}));
  }
  std::vector<OptimizedCurve> out;
  out.reserve(curves.size());
  for (const NamedCurve& nc : curves) out.push_back(in_design(design, [&] { return optimize_curve(nc); }));
  return out;
}

nlohmann::ordered_json optimize_items(const std::string& design_file,
                                      const std::vector<OptimizedCurve>& curves) {
  nlohmann::ordered_json all = nlohmann::ordered_json::array();
  for (const OptimizedCurve& c : curves) {
    nlohmann::ordered_json item = {{"design", design_file}, {"curve", c.name}};
    item.update(c.json);
    all.push_back(std::move(item));
  }
  return all;
}

}  // namespace fabmesh
