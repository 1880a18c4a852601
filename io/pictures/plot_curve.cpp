#include "io/pictures/plot_curve.h"

#include <Eigen/Core>

#include "geometry/curves/build_curve.h"
#include "geometry/fairing/quasi_bspline_energy.h"
#include "geometry/fairing/tbezier_energy.h"

namespace fabmesh {
namespace {

// Sum of the T-Bézier segments' curvature-variation energies at their current shape.
double tbezier_energy(const CompositeCurve& curve) {
  double sum = 0.0;
  for (const Segment& seg : curve.segments()) {
    if (seg.kind() != SegmentKind::TBezier) continue;
    sum += tbezier_curvature_variation_energy(seg.control_points())(seg.lambda(), seg.mu());
  }
  return sum;
}

}  // namespace

std::vector<std::vector<Vec2>> control_polygons(const CompositeCurve& curve) {
  std::vector<std::vector<Vec2>> out;
  bool in_bspline_run = false;
  for (const Segment& seg : curve.segments()) {
    const auto& p = seg.control_points();
    switch (seg.kind()) {
      case SegmentKind::TBezier:
      case SegmentKind::HBezier:
        out.push_back({p[0], p[1], p[2], p[3]});
        break;
      case SegmentKind::QuasiBSpline:
        // Span i uses p(i-1) .. p(i+2): a run contributes p(i), p(i+1) of its
        // first span, then p(i+1) of each further span.
        if (!in_bspline_run) out.push_back({p[1]});
        out.back().push_back(p[2]);
        break;
      case SegmentKind::Line:
      case SegmentKind::EllipseArc:
        break;
    }
    in_bspline_run = seg.kind() == SegmentKind::QuasiBSpline;
  }
  return out;
}

PlotCurve plot_curve_for(const CurveSpec& spec, const std::string& name, const JointTolerances& tol) {
  const BuiltCurve built = build_curve(spec, tol);
  PlotCurve out;
  out.name = name;
  out.curve = built.curve;
  out.control_polygons = control_polygons(built.curve);
  out.joints = built.joints;
  out.declared = built.declared;
  if (spec.fair == FairMode::None) return out;
  out.before_fairing = construct_curve(spec);
  if (built.bspline) {
    const int order = built.bspline->energy_kind == FairMode::Strain ? 2 : 3;
    const QuadraticEnergy energy = quasi_bspline_energy(spec.bspline_points, order);
    Eigen::VectorXd lambdas = Eigen::VectorXd::Zero(energy.b.size());
    for (std::size_t i = 0; i < spec.bspline_lambdas.size() && i < static_cast<std::size_t>(lambdas.size());
         ++i) {
      lambdas[static_cast<Eigen::Index>(i)] = spec.bspline_lambdas[i];
    }
    out.energy_before = energy(lambdas);
    out.energy_after = built.bspline->energy;
    out.energy_name = order == 2 ? "strain" : "curvature variation";
  } else {
    out.energy_before = tbezier_energy(*out.before_fairing);
    out.energy_after = tbezier_energy(built.curve);
    out.energy_name = "curvature variation";
  }
  return out;
}

}  // namespace fabmesh
