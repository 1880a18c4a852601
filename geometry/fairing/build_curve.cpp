#include "geometry/fairing/build_curve.h"

#include <fmt/format.h>

#include <Eigen/Core>

#include "geometry/core/errors.h"
#include "geometry/fairing/quasi_bspline_energy.h"
#include "geometry/fairing/tbezier_energy.h"

namespace fabmesh {
namespace {

// What fairing changed on a segment: "segment 3 (lambda 0.5 -> -0.21, mu 0.5 -> 0.13)".
std::string change(const CompositeCurve& before, const CompositeCurve& after, std::size_t i) {
  const Segment& a = before.segments()[i];
  const Segment& b = after.segments()[i];
  if (a.lambda() == b.lambda() && a.mu() == b.mu()) return fmt::format("segment {} (unchanged)", i + 1);
  return fmt::format("segment {} (lambda {:.4g} -> {:.4g}, mu {:.4g} -> {:.4g})", i + 1, a.lambda(),
                     b.lambda(), a.mu(), b.mu());
}

// Every joint keeps its declared continuity (at least fair_keeps) after fairing.
void require_kept_continuity(const CurveSpec& spec, const CompositeCurve& before, const BuiltCurve& out) {
  for (std::size_t i = 0; i < out.joints.size() && i < out.declared.size(); ++i) {
    const JointReport& j = out.joints[i];
    Continuity required = out.declared[i];
    if (spec.fair_keeps && static_cast<int>(*spec.fair_keeps) < static_cast<int>(required))
      required = *spec.fair_keeps;
    if (static_cast<int>(j.achieved) >= static_cast<int>(required)) continue;
    const std::string joint =
        j.closing ? fmt::format("closing joint (segments {} -> {})", j.before + 1, j.after + 1)
                  : fmt::format("joint {} (segments {} -> {})", i + 1, j.before + 1, j.after + 1);
    throw GeometryError(
        spec.key,
        fmt::format(
            "{}: declared {} but after fair: {} it is {} (tangent angle {:.3g} rad, relative curvature "
            "jump {:.3g}): fairing changed {} and {}; drop the fairing, or say what the curve may lose "
            "with fair_keeps: {}",
            joint, to_string(out.declared[i]), to_string(spec.fair), to_string(j.achieved), j.tangent_angle,
            j.curvature_jump, change(before, out.curve, j.before), change(before, out.curve, j.after),
            to_string(j.achieved)));
  }
}

// Sum of the T-Bézier segments' curvature-variation energies at their current shape.
double tbezier_energy(const CompositeCurve& curve) {
  double sum = 0.0;
  for (const Segment& seg : curve.segments()) {
    if (seg.kind() != SegmentKind::TBezier) continue;
    sum += tbezier_curvature_variation_energy(seg.control_points())(seg.lambda(), seg.mu());
  }
  return sum;
}

// The energy fairing minimised, before (the spec's own lambdas) and after.
FairingEffect fairing_effect(const CurveSpec& spec, const CompositeCurve& before, const BuiltCurve& built) {
  FairingEffect effect;
  effect.before = before;
  if (built.bspline) {
    const int order = built.bspline->energy_kind == FairMode::Strain ? 2 : 3;
    const QuadraticEnergy energy = quasi_bspline_energy(spec.bspline_points, order);
    Eigen::VectorXd lambdas = Eigen::VectorXd::Zero(energy.b.size());
    for (std::size_t i = 0; i < spec.bspline_lambdas.size() && i < static_cast<std::size_t>(lambdas.size());
         ++i) {
      lambdas[static_cast<Eigen::Index>(i)] = spec.bspline_lambdas[i];
    }
    effect.energy_before = energy(lambdas);
    effect.energy_after = built.bspline->energy;
    effect.energy_name = order == 2 ? "strain" : "curvature variation";
  } else {
    effect.energy_before = tbezier_energy(before);
    effect.energy_after = tbezier_energy(built.curve);
    effect.energy_name = "curvature variation";
  }
  return effect;
}

}  // namespace

BuiltCurve build_curve(const CurveSpec& spec, const JointTolerances& tol) {
  BuiltCurve out;
  out.curve = construct_curve(spec);
  verify_declared_continuity(spec, out.curve, tol);
  out.declared = declared_continuity(spec);
  const CompositeCurve before = out.curve;
  if (spec.fair != FairMode::None && spec.family == CurveFamily::HBezier) {
    throw GeometryError(spec.key, "fairing is defined for tbezier and quasi_bspline curves, not for hbezier");
  }
  if (spec.fair != FairMode::None) {
    if (spec.family == CurveFamily::QuasiBSpline) {
      out.bspline = fair_bspline(spec, spec.fair);
      CurveSpec faired = spec;
      faired.bspline_lambdas = out.bspline->lambdas;
      out.curve = construct_curve(faired);
    } else if (spec.fair == FairMode::CurvatureVariation) {
      out.segments = fair_tbezier_segments(out.curve);
      std::vector<Segment> segs = out.curve.segments();
      for (const SegmentFairing& f : out.segments) segs[f.index] = segs[f.index].with_shape(f.lambda, f.mu);
      out.curve = CompositeCurve(std::move(segs), out.curve.closed());
    } else {
      throw GeometryError(spec.key, fmt::format("fair: {} applies to quasi_bspline curves; T-Bézier curves "
                                                "take curvature_variation",
                                                to_string(spec.fair)));
    }
  }
  out.joints = out.curve.joints(tol);
  out.through = spec.bspline_through;
  out.through_deviation = spec.bspline_through_deviation;
  if (spec.fair != FairMode::None) {
    require_kept_continuity(spec, before, out);
    out.fairing = fairing_effect(spec, before, out);
  }
  return out;
}

}  // namespace fabmesh
