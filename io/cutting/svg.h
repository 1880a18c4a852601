#pragma once
// SVG cutting outlines: one <path> per loop, A arc commands for exact arcs,
// C for polynomial cubic splines, L for lines, polylines and rational
// splines (sampled within the loop's tolerance), coordinates in model units (mm).

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
