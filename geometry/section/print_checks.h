#pragma once
// Whether a vessel prints upright (FDM or clay printing): its steepest
// overhangs, its thinnest wall, its widest unsupported ledge and its size
// against a printer's bed, from the exact profile and a shell's exact inner
// wall (docs/math/print-checks.md).
//
// The section's boundary, walked with the material on its left (up the
// profile, across the rim, down the inner wall), has unit tangent t. A face
// looks down where t leans outward: its angle from vertical is
// asin(t_r) for t_r > 0 (0 for a vertical wall, 90 degrees for a ceiling),
// and it is supported where it lies on the bed (the lowest height). A
// stretch steeper than the limit is an overhang; along it r grows strictly
// (t_r > 0), so the ledge a layer must bridge there is r(end) - r(start).

#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "geometry/core/types.h"
#include "geometry/curves/composite.h"
#include "geometry/section/vessel_section.h"

namespace fabmesh {

/// A vessel design's `print:` keys, model units.
struct PrintOptions {
  double max_overhang_deg = 45.0;  ///< (0, 90): a face leaning further from vertical overhangs
  double min_wall = 1.2;           ///< > 0, model units (the reader converts the 1.2 mm default)
  std::optional<Vec3> bed;         ///< the printer's build volume X, Y, Z, model units (> 0)
  bool strict = false;             ///< findings are bad input rather than warnings
  /// A master taller than the bed is printed in sections joined by a pin on
  /// the axis (geometry/mould/master_sections.h); model units (the reader
  /// converts the 6 mm and 0.2 mm defaults).
  double pin_diameter = 6.0;
  double pin_clearance = 0.2;
  std::string units = "mm";  ///< model units, for messages
};

/// Which face of the section a place is on.
enum class PrintFace { Outer, Rim, Inner };

/// "outer wall", "rim", "inner wall".
const char* to_string(PrintFace face);

/// The steepest downward-looking place of one face.
struct Overhang {
  double angle_deg = 0.0;  ///< from vertical, in [0, 90]; 0 when no place of the face looks down
  Vec2 at{0.0, 0.0};       ///< (r, z) where it is steepest
};

/// A stretch of the boundary beyond the overhang limit, unsupported.
struct OverhangRun {
  PrintFace face = PrintFace::Outer;  ///< where it starts
  Vec2 from{0.0, 0.0}, to{0.0, 0.0};  ///< its ends, along the boundary (r grows from `from` to `to`)
  double width = 0.0;                 ///< the ledge: to.x - from.x
  double max_angle_deg = 0.0;         ///< its steepest place
  std::vector<Vec2> points;           ///< along the exact boundary, for drawing
};

/// A finding against a limit of PrintOptions: the key it is about
/// ("print.max_overhang_deg", "print.min_wall", "print.bed") and the sentence.
struct PrintFinding {
  std::string key;
  std::string message;
};

struct PrintCheck {
  double limit_deg = 45.0;  ///< the overhang limit the runs were found with
  Overhang outer;
  std::optional<Overhang> inner;            ///< a shell's inner wall
  std::optional<Overhang> rim;              ///< a shell's square rim, when it looks down
  std::vector<OverhangRun> runs;            ///< beyond the limit, in boundary order
  std::optional<std::size_t> widest_ledge;  ///< the run of the widest ledge
  /// A shell's thinnest wall, normal to the walls (the section's proven
  /// clearance of the exact surfaces); NaN for a solid.
  double min_wall = std::numeric_limits<double>::quiet_NaN();
  std::string min_wall_where;
  Vec3 size{0.0, 0.0, 0.0};      ///< (2 R, 2 R, height): the exact largest radius and height
  std::optional<bool> fits_bed;  ///< with PrintOptions::bed
  std::vector<PrintFinding> findings;
};

/// The checks of `section` (built from `profile` by build_vessel_section)
/// printed upright. Extremes are located on the exact curves (sampled, then
/// refined by golden-section search to the parameter's rounding); run ends
/// are the exact crossings of the limit (bisection).
/// \throw RangeError for options out of range
PrintCheck check_print(const CompositeCurve& profile, const VesselSection& section,
                       const PrintOptions& options);

}  // namespace fabmesh
