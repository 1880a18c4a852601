#pragma once
// A casting master taller than the printer's bed, cut by horizontal planes
// into sections that each fit it, registered by a pin on the axis: every
// section but the top one carries a cylindrical pin rising from its top,
// every section but the bottom one a matching hole in its bottom (wider by
// the clearance all round, deeper by it). A solid of revolution needs no
// more than concentricity to go back together, so one pin per joint does.
// Each section is the master's section clipped to its slab, notched for the
// pin and the hole, and revolved: proven like the master
// (docs/math/moulds.md 4).

#include <string>
#include <vector>

#include "geometry/core/proofs.h"
#include "geometry/core/soup.h"
#include "geometry/core/types.h"

namespace fabmesh {

struct MasterSplitOptions {
  double bed_height = 0.0;     ///< the printer's build height (> pin_diameter), model units
  double pin_diameter = 6.0;   ///< the pin's diameter; it rises as far as it is wide
  double pin_clearance = 0.2;  ///< hole radius = pin radius + clearance; hole depth = pin height + clearance
  int segments = 64;           ///< angular segments of the revolution (the master's)
};

struct MasterSection {
  std::string name;                  ///< "section-1" (the bottom), ...
  double z_low = 0.0, z_high = 0.0;  ///< the slab it is cut to (the pin rises above z_high)
  bool pin = false;                  ///< a pin on its top
  bool hole = false;                 ///< a hole in its bottom
  std::vector<Vec2> loop;            ///< its section: simple, counter-clockwise, on the axis along one edge
  TriangleSoup soup;                 ///< the revolution of `loop`
  TopologyProof topology;
  EmbeddingProof proof;
  double volume = 0.0;  ///< exact volume of the revolved polygon `loop` (Pappus)
};

struct MasterSplit {
  std::vector<double> cuts;  ///< heights of the cuts, upward
  std::vector<MasterSection> sections;
  double pin_height = 0.0, hole_radius = 0.0, hole_depth = 0.0;
};

/// The fewest equal slabs of the master's section `loop` (one simple
/// counter-clockwise loop meeting the axis along one edge, as a solid
/// vessel's section) that each fit `bed_height` with the pin on top.
/// \throw RangeError at "print.bed" (bed no taller than a pin) or at
///        "print.pin_diameter" / "print.pin_clearance" (not positive, negative);
///        GeometryError at "print.bed" (a cut that crosses the profile more
///        than once, a section shorter than its hole) or "print.pin_diameter"
///        (the master too narrow at a cut for the hole and its wall).
MasterSplit split_master(const std::vector<Vec2>& loop, const MasterSplitOptions& options);

}  // namespace fabmesh
