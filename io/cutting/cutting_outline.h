#pragma once
// The cutting outline of a countertop for a CNC router: one closed loop per
// boundary, made of exact entities where the design has them (lines,
// circular and elliptic arcs) and polylines within tolerance elsewhere.

#include <string>
#include <vector>

#include "geometry/core/types.h"
#include "geometry/curves/composite.h"

namespace fabmesh {

enum class CutKind { Line, Arc, Polyline };

/// One drawing entity of a loop, in model units.
struct CutEntity {
  CutKind kind = CutKind::Line;
  /// Line: from, to. Polyline: its points in order (>= 2). Arc: start and end points.
  std::vector<Vec2> points;
  /// Arc only: the exact arc (a == b: circular); to_deg < from_deg runs clockwise.
  EllipseArcParams arc;
};

/// A closed loop: each entity starts where the previous one ends, the last ends where the first starts.
struct CutLoop {
  std::string label;   ///< "outline", "holes[0] (ellipse)", ...
  bool outer = false;  ///< the outline (else a cut-out)
  std::vector<CutEntity> entities;
};

struct CutLoopOptions {
  double tolerance = 0.01;  ///< max distance of a polyline from its curve, model units (> 0)
  bool reverse = false;     ///< run the loop against the curve's direction
};

/// The loop of a closed curve: a Line per line segment, an Arc per exact
/// ellipse arc, one Polyline per run of consecutive other segments (T-Bézier,
/// H-Bézier, B-spline spans), sampled with the proven bound of sample_curve.
/// \throw RangeError (tolerance), GeometryError (an open curve)
CutLoop cut_loop(const CompositeCurve& curve, const std::string& label, bool outer,
                 const CutLoopOptions& options);

/// The point of an exact arc at central angle `deg` (its T-Bezier angle parameter, degrees).
Vec2 arc_point(const EllipseArcParams& arc, double deg);

/// Exact bounding box of all loops (arcs included): {min, max}.
std::pair<Vec2, Vec2> cut_bounds(const std::vector<CutLoop>& loops);

}  // namespace fabmesh
