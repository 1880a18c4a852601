#pragma once
// DXF (AutoCAD 2000, via dxflib) cutting outlines: LINE, ARC/CIRCLE,
// ELLIPSE, SPLINE and LWPOLYLINE entities, in model units.

#include <string>
#include <vector>

#include "geometry/sampling/cut_loop.h"
#include "io/cutting/sheet.h"

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

/// The DXF text of `sheet`: its layers (colours as given), loops as
/// encode_dxf writes them, lines, TEXT entities and each dimension as a
/// rotated DIMENSION entity with its block of geometry (*D1, *D2, ...:
/// extension and dimension lines, SOLID arrowheads, the measured text) and
/// its measurement (group 42); the dimension style's sizes from
/// `sheet.text_height`.
/// \throw FileError when dxflib cannot write its temporary file
std::string encode_dxf_sheet(const Sheet& sheet, const DxfOptions& options = {});

}  // namespace fabmesh
