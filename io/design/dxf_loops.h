#pragma once
// Closed loops of a DXF drawing (shop templates, CAD): the LINE, ARC, CIRCLE,
// ELLIPSE and LWPOLYLINE/POLYLINE entities of one layer, chained end to end
// into closed curve specs of exact segments (lines, circle and ellipse arcs;
// a polyline's bulges are exact arcs). docs/design-files.md, "Outlines from DXF".

#include <cstddef>
#include <string>
#include <vector>

#include "geometry/curves/curve_spec.h"

namespace fabmesh {

/// Which loops to read, and how.
struct DxfLoopQuery {
  std::string layer;     ///< the layer's name; empty: the entities of every layer
  double max_gap = 0.0;  ///< ends at most this far apart (design units) are joined; >= 0
  std::string units;     ///< the design's units (mm, cm, m, in): the loops are scaled into them
  /// A layer of lines marking the loops' wall edges (a kitchen template's
  /// WALLS): a line of the loops that lies on one of them (both ends within
  /// max_gap of it, or within the drawing's flatness) is a wall
  /// (SegmentSpec::wall). Empty: none.
  std::string walls;
  /// Whether the walls layer must have lines (the design named it); else a
  /// drawing without the layer has no walls.
  bool walls_required = false;
};

/// One closed loop, in drawing order of its entities.
struct DxfLoop {
  /// Closed, joints declared G0 (verified when built); each segment's `name`
  /// is its entity ("LINE #2F", "LWPOLYLINE #30 vertex 4"), a bridged gap's
  /// "gap between ARC #31 and ARC #32".
  CurveSpec curve;
  std::string first_entity;  ///< the entity it was started from, for messages
};

/// The loops of a drawing's layer and how the drawing was read.
struct DxfLoops {
  std::vector<DxfLoop> loops;  ///< in the order of their first entity in the file
  /// Facts for the report: the units ("$INSUNITS 4 (mm)" or the assumption
  /// made without it), entities of other kinds left out, bridged gaps.
  std::vector<std::string> notes;
};

/// A drawing is flat to this fraction of its size (its largest coordinate):
/// an entity whose z is larger is off the XY plane (bad input), and a
/// polyline span whose bulge lifts its arc at most this far off its chord
/// (the sagitta, bulge x chord / 2: CAD's rounding noise of a straight span,
/// 1e-12 ... 1e-300) is read as the straight line it is within that distance.
inline constexpr double kDxfFlatness = 1e-9;

/// Reads the DXF file at `path` (ASCII DXF, at most 64 MiB, read by
/// io/dxf/dxf_reader.h) and returns every closed loop on the query's layer,
/// in the design's units. Ends are joined when they are at most `max_gap`
/// apart: a line's end moves to the exact arc's end it meets (or to the other
/// line's end); two arcs whose ends are apart are joined by a short line (noted).
/// \throw FileError naming `path`, the line, the layer, the entities by handle and the
/// place: whatever read_dxf refuses (not a DXF, a binary DXF, a file cut
/// short, a value that is not a number, a count that disagrees with its
/// entries, more than kMaxDxfItems items), an unknown $INSUNITS, a SPLINE it cannot
/// read (degree above 3, a weight not finite and > 0, fit points only) or an
/// INSERT on the layer, an entity off the XY plane (kDxfFlatness), a layer with no entity in model
/// space, a walls layer with an arc or a spline or a line that lies on no line
/// of the loops, or (walls_required) with no line, an open chain (an end meeting no other end within
/// max_gap), three or more ends at one point (overlapping or branching entities).
DxfLoops read_dxf_loops(const std::string& path, const DxfLoopQuery& query);

/// The same from the file's bytes; `path` names it in messages. \throw FileError
DxfLoops parse_dxf_loops(const std::string& bytes, const std::string& path, const DxfLoopQuery& query);

}  // namespace fabmesh
