#pragma once
// Fairing a designer's curve: the shape parameters that minimise an energy
// with every control point kept where the design put it.

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

/// Fairest parameters for every T-Bézier segment of `curve` (control points fixed).
std::vector<SegmentFairing> fair_tbezier_segments(const CompositeCurve& curve);

/// Fairest lambdas of a quasi_bspline spec for `kind` (Strain or CurvatureVariation).
BSplineFairing fair_bspline(const CurveSpec& spec, FairMode kind);

}  // namespace fabmesh
