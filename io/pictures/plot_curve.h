#pragma once
// The plain data a curve plot draws for one curve, taken from a built curve
// (the plot constructs and fairs nothing itself).

#include <optional>
#include <string>
#include <vector>

#include "geometry/curves/composite.h"
#include "geometry/fairing/build_curve.h"

namespace fabmesh {

/// One curve of a plot.
struct PlotCurve {
  std::string name;
  CompositeCurve curve;  ///< as built (after fairing, if any), model units
  /// Control polygons drawn dotted: one per T-/H-Bézier segment, one for a
  /// whole run of quasi-B-spline spans (its p_0..p_n); none for lines and
  /// exact arcs. See control_polygons().
  std::vector<std::vector<Vec2>> control_polygons;
  /// Measured joints as CompositeCurve::joints(); empty: measured by the plot.
  std::vector<JointReport> joints;
  /// Declared continuity per joint (same order); empty: nothing declared.
  std::vector<Continuity> declared;
  /// The curve before fairing, drawn grey dashed under the faired one.
  std::optional<CompositeCurve> before_fairing;
  std::optional<double> energy_before, energy_after;  ///< fairing energy (energy_name), model units
  std::string energy_name;                            ///< e.g. "curvature variation", "strain"
  /// Points the curve is given to pass through (BuiltCurve::through), drawn
  /// as dots in the curve's colour on its joints.
  std::vector<Vec2> through;
};

/// The control polygons of `curve` as PlotCurve::control_polygons describes.
std::vector<std::vector<Vec2>> control_polygons(const CompositeCurve& curve);

/// The PlotCurve of a built curve: the curve as built, its control polygons,
/// its measured and declared joints, and when it was faired the curve before
/// fairing with both energies (BuiltCurve::fairing).
PlotCurve plot_curve(const BuiltCurve& built, const std::string& name);

}  // namespace fabmesh
