#include "geometry/fairing/fair_curve.h"

#include "geometry/fairing/quasi_bspline_energy.h"
#include "geometry/fairing/tbezier_energy.h"

namespace fabmesh {

std::vector<SegmentFairing> fair_tbezier_segments(const CompositeCurve& curve) {
  std::vector<SegmentFairing> out;
  for (std::size_t i = 0; i < curve.size(); ++i) {
    const Segment& seg = curve.segments()[i];
    if (seg.kind() != SegmentKind::TBezier) continue;
    const FairestShape f = tbezier_fairest(tbezier_curvature_variation_energy(seg.control_points()));
    out.push_back({i, f.lambda, f.mu, f.energy});
  }
  return out;
}

BSplineFairing fair_bspline(const CurveSpec& spec, FairMode kind) {
  if (kind == FairMode::None) kind = FairMode::CurvatureVariation;
  const int order = kind == FairMode::Strain ? 2 : 3;
  const FairestLambdas f = quasi_bspline_fairest(spec.bspline_points, order);
  return {kind, f.lambdas, f.energy};
}

}  // namespace fabmesh
