#pragma once
// A designer's curve made ready for sampling: constructed from its spec,
// its declared continuity verified, faired when the spec asks for it.

#include <optional>
#include <vector>

#include "geometry/curves/curve_spec.h"
#include "geometry/fairing/fair_curve.h"

namespace fabmesh {

/// A curve as the stages after construction use it, with what fairing did.
struct BuiltCurve {
  CompositeCurve curve;                   ///< after fairing, if any
  std::vector<Continuity> declared;       ///< per joint, as CompositeCurve::joints()
  std::vector<JointReport> joints;        ///< measured on `curve`
  std::vector<SegmentFairing> segments;   ///< T-Bézier fairing results (when faired)
  std::optional<BSplineFairing> bspline;  ///< quasi-B-spline fairing result (when faired)
};

/// Constructs the curve, verifies declared continuity on the constructed
/// curve (GeometryError if contradicted), then applies spec.fair: control
/// points stay, shape parameters change; joints are measured after fairing.
/// A joint that fairing leaves below its declared continuity (or below
/// spec.fair_keeps, when the design accepts less) is a GeometryError naming
/// the joint, the curve and the shape parameters fairing changed.
/// \throw RangeError, GeometryError (at spec.key, or a segment's key)
BuiltCurve build_curve(const CurveSpec& spec, const JointTolerances& tol = {});

}  // namespace fabmesh
