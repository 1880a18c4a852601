#pragma once
// RS-274 G-code (as LinuxCNC and GRBL read it; file extension .nc) of a
// router toolpath: the tool-centre path itself (no controller cutter
// compensation), absolute coordinates, arcs in the XY plane with centres
// relative to their start (I, J).

#include <string>

#include "geometry/core/units.h"
#include "geometry/toolpath/toolpath.h"

namespace fabmesh {

struct GcodeOptions {
  std::string name = "part";       ///< the design's name, for the header comment
  std::string model_units = "mm";  ///< units of the toolpath: mm | cm | m | in
  std::string units = "mm";        ///< units of the program: mm (G21) | in (G20)
  /// Digits after the decimal point, 0: the fewest (3 to 6) whose rounding
  /// moves a point by at most cnc.tolerance / 20.
  int decimals = 0;
};

/// The program: a header comment (design, tool, units, depths, feeds, the
/// proven deviation), G21|G20 G90 G94 G17, G0 to safe height, M3 S<spindle>,
/// then every move of `path` (G0 rapids and retracts, G1 plunges and tab
/// steps at the plunge feed, G1/G2/G3 cuts at the cutting feed; a comment on
/// lead-in, lead-out, tab and dog-bone lines and before every pass), M5, M30.
/// A path that drills (Toolpath::drills) or has a tool table
/// (CncOptions::tools) changes tools: the header lists them, and before the
/// spindle starts, for each drill in turn, `M6 T<n>` and M3 (after G0 to
/// safe height and M5 when the spindle runs), one canned cycle block per hole
/// with every word (`G98 G81 X Y Z R F`, or `G98 G83 X Y Z R Q F` with
/// pecks), G80; then `M6 T<end mill>` and M3 for the routing, whose first
/// feed move states its F again.
/// Arcs over 180 degrees are split; an arc whose sagitta is below the
/// resolution is written as G1. Numbers have fixed decimals with trailing
/// zeros removed and never read "-0". Deterministic: same path, same bytes.
/// \throw InputError for unknown units, RangeError for decimals outside [0, 9]
std::string encode_gcode(const Toolpath& path, const GcodeOptions& options = {});

/// encode_gcode written atomically to `path`. \throw FileError
void write_gcode(const std::string& file, const Toolpath& path, const GcodeOptions& options = {});

}  // namespace fabmesh
