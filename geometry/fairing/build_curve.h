#pragma once
// A designer's curve made ready for sampling: constructed from its spec,
// its declared continuity verified, faired when the spec asks for it.

#include <optional>
#include <string>
#include <vector>

#include "geometry/curves/curve_spec.h"
#include "geometry/fairing/fair_curve.h"

namespace fabmesh {

/// What fairing did to a curve, for plots and reports: the curve before and
/// the energy it minimised, before and after (model units).
struct FairingEffect {
  CompositeCurve before;       ///< the constructed curve, shape parameters as designed
  double energy_before = 0.0;  ///< the energy of `before`
  double energy_after = 0.0;   ///< the energy of the faired curve
  /// "strain" or "curvature variation": a quasi-B-spline's energy of the
  /// spec's fairing kind, or the T-Bézier curvature-variation energy summed
  /// over the T-Bézier segments.
  std::string energy_name;
};

/// A curve as the stages after construction use it, with what fairing did.
struct BuiltCurve {
  CompositeCurve curve;                   ///< after fairing, if any
  std::vector<Continuity> declared;       ///< per joint, as CompositeCurve::joints()
  std::vector<JointReport> joints;        ///< measured on `curve`
  std::vector<SegmentFairing> segments;   ///< T-Bézier fairing results (when faired)
  std::optional<BSplineFairing> bspline;  ///< quasi-B-spline fairing result (when faired)
  std::optional<FairingEffect> fairing;   ///< set when the spec asked for fairing
  /// A quasi-B-spline given by `through:`: the points it passes through at its
  /// joints (CurveSpec::bspline_through) and the proven largest distance
  /// from one to its joint; empty for control points given.
  std::vector<Vec2> through;
  double through_deviation = 0.0;
};

/// Constructs the curve, verifies declared continuity on the constructed
/// curve (GeometryError if contradicted), then applies spec.fair: control
/// points stay, shape parameters change; joints are measured after fairing.
/// A joint that fairing leaves below its declared continuity (or below
/// spec.fair_keeps, when the design accepts less) is a GeometryError naming
/// the joint, the curve and the shape parameters fairing changed. This is the
/// one way the stages build a designer's curve (construct_curve is its first
/// step).
/// \throw RangeError, GeometryError (at spec.key, or a segment's key)
BuiltCurve build_curve(const CurveSpec& spec, const JointTolerances& tol = {});

}  // namespace fabmesh
