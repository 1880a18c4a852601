#pragma once
// DXF (AutoCAD 2000, via dxflib) cutting outlines: LINE, ARC/CIRCLE,
// ELLIPSE, SPLINE and LWPOLYLINE entities, in model units.

#include <string>
#include <vector>

#include "geometry/sampling/cut_loop.h"

namespace fabmesh {

struct DxfOptions {
  std::string units = "mm";  ///< mm | cm | m | in: the header's $INSUNITS
};

/// The DXF text of `loops`: the outline on layer OUTLINE, cut-outs on layer
/// HOLES; lines as LINE, circular arcs as ARC (CIRCLE when whole), elliptic
/// arcs as ELLIPSE, splines as SPLINE (one cubic Bézier span each: degree 3,
/// knots 0 0 0 0 1 1 1 1, the weights when they differ), polylines as
/// LWPOLYLINE (closed when a loop is one polyline).
/// \throw FileError when dxflib cannot write its temporary file
std::string encode_dxf(const std::vector<CutLoop>& loops, const DxfOptions& options = {});

}  // namespace fabmesh
