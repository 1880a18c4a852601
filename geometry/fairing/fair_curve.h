#pragma once
// A designer's curve made ready for sampling: constructed from its spec,
// its declared continuity verified, faired when the spec asks for it.

#include <optional>
#include <vector>

#include "geometry/curves/curve_spec.h"

namespace fabmesh {

/// The fairest shape of one T-Bézier segment of a composite.
struct SegmentFairing {
  std::size_t index = 0;  ///< segment index in the composite
  double lambda = 0.0, mu = 0.0, energy = 0.0;
};

/// The fairest local parameters of a quasi-cubic B-spline.
struct BSplineFairing {
  FairMode energy_kind = FairMode::CurvatureVariation;
  std::vector<double> lambdas;  ///< lambda_1 .. lambda_{n-1}
  double energy = 0.0;
};

struct BuiltCurve {
  CompositeCurve curve;                   ///< after fairing, if any
  std::vector<Continuity> declared;       ///< per joint, as CompositeCurve::joints()
  std::vector<JointReport> joints;        ///< measured on `curve`
  std::vector<SegmentFairing> segments;   ///< T-Bézier fairing results (when faired)
  std::optional<BSplineFairing> bspline;  ///< quasi-B-spline fairing result (when faired)
};

/// Fairest parameters for every T-Bézier segment of `curve` (control points fixed).
std::vector<SegmentFairing> fair_tbezier_segments(const CompositeCurve& curve);

/// Fairest lambdas of a quasi_bspline spec for `kind` (Strain or CurvatureVariation).
BSplineFairing fair_bspline(const CurveSpec& spec, FairMode kind);

/// Constructs the curve, verifies declared continuity on the constructed
/// curve (GeometryError if contradicted), then applies spec.fair: control
/// points stay, shape parameters change; joints are measured after fairing
/// (a G2 joint may be lost and the report says so).
BuiltCurve build_curve(const CurveSpec& spec, const JointTolerances& tol = {});

}  // namespace fabmesh
