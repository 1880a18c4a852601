#pragma once
// An SVG picture of a router toolpath over the part: the part's loops solid
// (filled, holes open), each loop's tool-centre path dashed, lead-in arcs,
// plunge points (with the tool's disc), tabs, dog-bones and drilled holes marked. Same
// conventions as svg.h: coordinates in model units, y written negated so
// the picture looks as designed (y up).

#include <string>
#include <vector>

#include "geometry/sampling/cut_loop.h"
#include "geometry/toolpath/toolpath.h"

namespace fabmesh {

struct ToolpathSvgOptions {
  std::string units = "mm";  ///< the width/height unit: mm | cm | in (m is written as mm x 1000)
  double margin = 5.0;       ///< around everything drawn, model units (>= 0)
};

/// The SVG document. Element ids: "part" (the loops, even-odd filled),
/// "path-<i>" (tool-centre path of Toolpath::loops[i], dashed), "lead-<i>",
/// "plunge-<i>" (a circle of the tool radius where the tool goes down),
/// "tab-<i>-<j>", "dogbone-<i>-<k>", "drill-<k>" (Toolpath::drills[k]: the
/// drill's circle and a cross through its centre). viewBox spans all of them
/// plus the margin.
/// \throw RangeError for a negative margin
std::string encode_toolpath_svg(const std::vector<CutLoop>& part, const Toolpath& path,
                                const ToolpathSvgOptions& options = {});

/// encode_toolpath_svg written atomically to `file`. \throw FileError
void write_toolpath_svg(const std::string& file, const std::vector<CutLoop>& part, const Toolpath& path,
                        const ToolpathSvgOptions& options = {});

}  // namespace fabmesh
