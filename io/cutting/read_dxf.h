#pragma once
// Reading DXF drawings back (dxflib): the entities a cutting outline is made
// of, with their end points, so outlines can be checked after a round trip.

#include <string>
#include <vector>

#include "geometry/core/types.h"

namespace fabmesh {

/// One drawing entity read from a DXF file, in model units.
struct DxfEntity {
  std::string type;  ///< LINE, ARC, CIRCLE, ELLIPSE, SPLINE or POLYLINE (an LWPOLYLINE or a POLYLINE)
  std::string layer;
  /// LINE/ARC/ELLIPSE: start and end point (counter-clockwise for arcs);
  /// CIRCLE: one point on it, twice; polylines: their vertices; SPLINE: its
  /// control points (a clamped spline, as fabmesh writes, starts at the first
  /// and ends at the last).
  std::vector<Vec2> points;
  bool closed = false;  ///< a polyline or SPLINE with the closed flag, a CIRCLE, or an ELLIPSE of 2 pi
  /// SPLINE only: its degree, flags (group 70), knots and the control points'
  /// weights (1 where the file gives none).
  int degree = 0;
  int flags = 0;
  std::vector<double> knots;
  std::vector<double> weights;
};

/// The LINE, ARC, CIRCLE, ELLIPSE, SPLINE and polyline entities of a DXF
/// text, in file order; other entities are ignored. \throw FileError when dxflib cannot parse it
std::vector<DxfEntity> parse_dxf(const std::string& bytes, const std::string& what);

}  // namespace fabmesh
