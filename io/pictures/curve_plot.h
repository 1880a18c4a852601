#pragma once
// Curve plots a designer can judge: the curves true to scale with their
// control polygons, joints and curvature combs, beside their curvature
// against arc length.

#include <array>
#include <string>
#include <vector>

#include "io/pictures/plot_curve.h"

namespace fabmesh {

/// A closed outline drawn thin and grey under the curves, e.g. a vessel's
/// section as its builder made it (the profile, the rim, a shell's inner wall
/// and base, the axis), model units.
struct PlotOutline {
  std::string name;          ///< data-name, and the legend's words ("section")
  std::vector<Vec2> points;  ///< a closed polyline (the last point joins the first)
};

/// Stretches of the drawing to flag, drawn wide, red and translucent under
/// the curves (class "flag"), with one legend line: e.g. a vessel's overhangs
/// beyond its print limit.
struct PlotFlag {
  std::string name;                          ///< data-name, and the legend's words
  std::vector<std::vector<Vec2>> stretches;  ///< open polylines, model units
};

/// A dimension as a drawing gives one: the span from `from` to `to` (model
/// units) between arrowheads, with its text, set off `offset_px` pixels to
/// the left of the direction from -> to (extension lines back to the points
/// measured when set off). Class "dimension", data-name, data-value.
struct PlotDimension {
  std::string name;  ///< "height", "widest diameter"
  Vec2 from = Vec2::Zero(), to = Vec2::Zero();
  double value = 0.0;  ///< what the text says, model units
  std::string text;    ///< "height 22 cm"
  double offset_px = 0.0;
};

/// What one plot shows.
struct CurvePlot {
  std::string title;
  std::string units = "mm";  ///< model units, for the scale bar and the axes
  std::vector<PlotCurve> curves;
  /// Extra straight lines drawn dotted, e.g. a surface's control net in plan (model units).
  std::vector<std::array<Vec2, 2>> net_lines;
  std::vector<PlotOutline> outlines;  ///< drawn under the curves (class "outline")
  std::vector<PlotFlag> flags;        ///< drawn over the outlines, under the curves (class "flag")
  /// The model panel's coordinates, named on its axes with the units ("r (mm)").
  std::array<std::string, 2> axis_names = {"x", "y"};
  /// A vessel's axis of revolution, the line x = 0: drawn dash-dotted (class
  /// "axis") and always in view, so that a point at negative radius shows.
  bool revolution_axis = false;
  std::vector<PlotDimension> dimensions;  ///< drawn over the outlines, under the curves
};

struct CurvePlotOptions {
  int width = 1200;  ///< the picture's size, pixels, [200, 10000] x [150, 10000]
  int height = 600;
  /// Largest distance of a drawn polyline from its curve, as a fraction of
  /// the drawing's diagonal, (0, 0.01]. Exact arcs are drawn as SVG arcs.
  double sample_fraction = 2e-4;
  /// Longest curvature-comb tooth as a fraction of the drawing's diagonal,
  /// [0, 1] (0: no comb teeth). One scale for all curves.
  double comb_fraction = 0.1;
  int comb_teeth = 32;          ///< comb teeth per segment, [1, 1000]
  int curvature_samples = 128;  ///< curvature samples per segment, [2, 100000]
};

/// The SVG document of `plot`, `options.width` x `options.height` pixels.
///
/// Left, the model panel (a nested <svg class="model-panel"> whose viewBox is
/// in model units, y negated so that y points up): a faint grid and a scale
/// bar (class "scale-bar", data-length in model units) of the same step, the
/// grid's coordinates written along the bottom and the left (class "tick",
/// data-axis "x" or "y", data-value) with the axes' names and units (class
/// "axis-name": "x (mm)"), the axis of revolution when asked (class "axis"),
/// the outlines grey (class "outline", data-name); per
/// curve a solid path (class "curve"; the first curve red, others in
/// distinct colours), its control polygon dotted blue with marked points
/// (class "control-polygon", one group per curve even when empty), its
/// curvature comb (class "comb": teeth along -k n, scaled by curvature, and
/// their envelope) and one marker per joint (class "joint", label G0/G1/G2 or
/// "gap", class "joint lost" with the declared class where it was not
/// achieved); a faired curve's previous shape grey dashed (class
/// "curve-before") with both energies in the legend. Right, curvature against
/// arc length (class "curvature-plot"), one polyline per segment (class
/// "curvature-segment" with data-k-start/end, the curvature at its ends) and
/// the joints as vertical markers (class "joint-marker"). Every curve's
/// elements carry data-name. Output is deterministic (fixed number formats).
/// \throw RangeError for a bad option, InputError for a plot with nothing to
/// draw or joints/declared lists that do not match their curve.
std::string plot_curves_svg(const CurvePlot& plot, const CurvePlotOptions& options = {});

}  // namespace fabmesh
