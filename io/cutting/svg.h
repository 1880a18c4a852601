#pragma once
// SVG cutting outlines: one <path> per loop, A arc commands for exact arcs,
// L for lines and polylines, coordinates in model units (mm).

#include <string>
#include <vector>

#include "geometry/sampling/cut_loop.h"

namespace fabmesh {

struct SvgOptions {
  std::string units = "mm";  ///< the width/height unit: mm | cm | in (m is written as mm x 1000)
  double margin = 5.0;       ///< around the outline, model units (>= 0)
};

/// The SVG document of `loops`. The model's y axis points up, SVG's down: y is
/// written negated, so the drawing looks as designed. viewBox spans the
/// loops' bounds plus the margin, in model units.
std::string encode_svg(const std::vector<CutLoop>& loops, const SvgOptions& options = {});

}  // namespace fabmesh
