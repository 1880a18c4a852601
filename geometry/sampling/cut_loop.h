#pragma once
// The drawing of a curve at true size (a countertop's cutting outline, a
// vessel's profile template, a curve design): one chain per curve, made of
// exact entities where the curve has them (lines, circular and elliptic
// arcs, rational cubic Bézier spans) and polylines sampled within a proven
// tolerance elsewhere.

#include <array>
#include <string>
#include <vector>

#include "geometry/core/types.h"
#include "geometry/curves/composite.h"

namespace fabmesh {

enum class CutKind { Line, Arc, Polyline, Spline };

/// One drawing entity of a loop, in model units.
struct CutEntity {
  CutKind kind = CutKind::Line;
  /// Line: from, to. Polyline: its points in order (>= 2). Arc: start and end points.
  /// Spline: the 4 control points P0..P3 of a rational cubic Bézier span
  /// (it starts at P0 and ends at P3).
  std::vector<Vec2> points;
  /// Arc only: the exact arc (a == b: circular); to_deg < from_deg runs clockwise.
  EllipseArcParams arc;
  /// Spline only: the weights w0..w3 of points[0..3], each finite and > 0:
  /// r(s) = sum w_j P_j B_j(s) / sum w_j B_j(s), B_j the cubic Bernstein
  /// polynomials, s in [0, 1] (docs/math/curves.md 5). All equal: the
  /// polynomial cubic Bézier curve. Unused (all 1) for the other kinds.
  std::array<double, 4> weights{1.0, 1.0, 1.0, 1.0};
};

/// A chain of entities, each starting where the previous one ends; when
/// closed (a loop) the last ends where the first starts.
struct CutLoop {
  std::string label;   ///< "outline", "holes[0] (ellipse)", ...
  bool outer = false;  ///< the outline (else a cut-out)
  bool closed = true;  ///< an open curve (a kind: curve design) is drawn as an open chain
  std::vector<CutEntity> entities;
  /// The distance its polylines keep from the curve (CutLoopOptions::tolerance):
  /// a writer that cannot draw a rational Spline exactly (SVG) samples it within this.
  double tolerance = 0.01;
};

struct CutLoopOptions {
  double tolerance = 0.01;  ///< max distance of a polyline from its curve, model units (> 0)
  bool reverse = false;     ///< run the loop against the curve's direction
};

/// The chain of a curve: a Line per line segment, an Arc per exact ellipse
/// arc, a Spline per rational cubic Bézier segment (its control points and
/// weights, exactly) and per quasi-cubic span with both local parameters 0
/// (the uniform cubic B-spline span: a polynomial cubic, its Bézier points
/// with equal weights), one Polyline per run of consecutive other segments
/// (T-Bézier, H-Bézier, other quasi-cubic B-spline spans), sampled with the proven
/// bound of sample_curve. A closed curve gives a closed loop, an open one an
/// open chain; `options.reverse` reverses the entities, their points and
/// (Spline) their weights.
/// \throw RangeError (tolerance)
CutLoop cut_loop(const CompositeCurve& curve, const std::string& label, bool outer,
                 const CutLoopOptions& options);

/// The point of an exact arc at central angle `deg` (its T-Bezier angle parameter, degrees).
Vec2 arc_point(const EllipseArcParams& arc, double deg);

/// The point of a Spline entity at s in [0, 1] (its rational cubic Bézier).
Vec2 spline_point(const CutEntity& spline, double s);

/// The points of a Spline entity sampled from P0 to P3 so that every chord
/// stays within `tolerance` of the curve (the proven bound of
/// sample_segment_parameters). \throw RangeError (tolerance, weights)
std::vector<Vec2> spline_polyline(const CutEntity& spline, double tolerance);

/// Exact bounding box of all loops: {min, max}. Arcs and Splines contribute
/// their extreme points in x and y, not only their ends (a Spline's are roots
/// of a polynomial of degree <= 4, found to the last bits).
std::pair<Vec2, Vec2> cut_bounds(const std::vector<CutLoop>& loops);

}  // namespace fabmesh
