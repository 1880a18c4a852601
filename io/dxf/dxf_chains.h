#pragma once
// The pieces of a drawing's loops (lines, exact arcs, exact splines) chained
// end to end into closed curve specs: drawn in any order and direction, ends
// joined within a gap, arcs kept exact (docs/design-files.md, "Outlines and
// holes from a DXF drawing").

#include <cstddef>
#include <string>
#include <vector>

#include "geometry/curves/curve_spec.h"
#include "geometry/curves/segment.h"
#include "io/dxf/dxf_spline.h"

namespace fabmesh {

/// One piece of a loop, in the drawing's direction: a line from `start` to
/// `end`, an exact arc (`ellipse`), or an exact spline (`beziers`).
struct DxfPiece {
  bool arc = false;
  bool spline = false;
  Vec2 start{0.0, 0.0}, end{0.0, 0.0};  ///< an arc's and a spline's as they evaluate
  EllipseArcParams ellipse;             ///< arcs
  std::vector<BezierSpan> beziers;      ///< splines: cubic Bézier spans, in order
  std::string entity;                   ///< "LINE #2F", "LWPOLYLINE #30 vertex 4"
  bool closed = false;                  ///< a whole circle, ellipse or closed spline: a loop by itself
  std::size_t order = 0;                ///< its entity's line in the file (file order)
  bool wall = false;                    ///< a line along a wall (its segment gets SegmentSpec::wall)
};

/// The closed loops the pieces make.
struct DxfChains {
  std::vector<CurveSpec> loops;  ///< closed, joints declared G0, in file order of their first piece
  std::vector<std::string> first_entities;  ///< each loop's first piece's entity
  std::size_t skipped = 0;                  ///< lines no longer than the gap, left out
  std::size_t bridges = 0;                  ///< gaps between exact pieces joined by short lines
};

/// Chains `pieces` (design units; `extent` their largest coordinate) into
/// closed loops: ends at most `max_gap` apart are joined (a line's end moves
/// onto the exact end it meets; two exact ends apart get a short line).
/// `where` ("kitchen.dxf layer HOLES") starts messages. \throw InputError: an
/// end meeting no other end (naming the nearest), three or more ends at one
/// point, pieces that meet twice
DxfChains chain_pieces(const std::vector<DxfPiece>& pieces, double max_gap, double extent,
                       const std::string& where);

}  // namespace fabmesh
