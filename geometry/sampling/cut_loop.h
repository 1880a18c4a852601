#pragma once
// The drawing of a curve at true size (a countertop's cutting outline, a
// vessel's profile template, a curve design): one chain per curve, made of
// exact entities where the curve has them (lines, circular and elliptic
// arcs) and polylines sampled within a proven tolerance elsewhere.

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

/// A chain of entities, each starting where the previous one ends; when
/// closed (a loop) the last ends where the first starts.
struct CutLoop {
  std::string label;   ///< "outline", "holes[0] (ellipse)", ...
  bool outer = false;  ///< the outline (else a cut-out)
  bool closed = true;  ///< an open curve (a kind: curve design) is drawn as an open chain
  std::vector<CutEntity> entities;
};

struct CutLoopOptions {
  double tolerance = 0.01;  ///< max distance of a polyline from its curve, model units (> 0)
  bool reverse = false;     ///< run the loop against the curve's direction
};

/// The chain of a curve: a Line per line segment, an Arc per exact ellipse
/// arc, one Polyline per run of consecutive other segments (T-Bézier,
/// H-Bézier, B-spline spans), sampled with the proven bound of sample_curve.
/// A closed curve gives a closed loop, an open one an open chain.
/// \throw RangeError (tolerance)
CutLoop cut_loop(const CompositeCurve& curve, const std::string& label, bool outer,
                 const CutLoopOptions& options);

/// The point of an exact arc at central angle `deg` (its T-Bezier angle parameter, degrees).
Vec2 arc_point(const EllipseArcParams& arc, double deg);

/// Exact bounding box of all loops (arcs included): {min, max}.
std::pair<Vec2, Vec2> cut_bounds(const std::vector<CutLoop>& loops);

}  // namespace fabmesh
