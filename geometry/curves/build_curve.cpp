#include "geometry/curves/build_curve.h"

#include <fmt/format.h>

#include "geometry/core/errors.h"

namespace fabmesh {

BuiltCurve build_curve(const CurveSpec& spec, const JointTolerances& tol) {
  BuiltCurve out;
  out.curve = construct_curve(spec);
  verify_declared_continuity(spec, out.curve, tol);
  out.declared = declared_continuity(spec);
  if (spec.fair != FairMode::None && spec.family == CurveFamily::HBezier) {
    throw GeometryError(spec.label, spec.label +
                                        ": fairing is defined for tbezier and quasi_bspline curves, "
                                        "not for hbezier");
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
      throw GeometryError(spec.label,
                          fmt::format("{}: fair: {} applies to quasi_bspline curves; T-Bézier curves "
                                      "take curvature_variation",
                                      spec.label, to_string(spec.fair)));
    }
  }
  out.joints = out.curve.joints(tol);
  return out;
}

}  // namespace fabmesh
