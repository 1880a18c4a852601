#pragma once
// A casting master taller than the printer's bed, cut by horizontal planes
// into sections that each fit it, registered by a pin on the axis: every
// section but the top one carries a cylindrical pin rising from its top,
// every section but the bottom one a matching hole in its bottom (wider by
// the clearance all round, deeper by it). A solid of revolution needs no
// more than concentricity to go back together, so one pin per joint does.
// Each section is the master's section clipped to its slab, notched for the
// pin and the hole, and revolved: proven like the master
// (docs/math/moulds.md 4). A master wider than the bed is also cut into
// halves or quarters through its axis (master_sectors.h), each joint
// registered by a pin across it.

#include <optional>
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
  /// 1, or 2 or 4: each section cut by vertical planes through the axis into
  /// halves or quarters (master_sectors.h), for a master wider than the bed.
  int sectors = 1;
};

struct MasterSection {
  /// "section-1" (the bottom), ...; cut into sectors "section-1-half-1",
  /// "section-1-quarter-2", ... ("half-1", ... when the master is one section)
  std::string name;
  double z_low = 0.0, z_high = 0.0;  ///< the slab it is cut to (the pin rises above z_high)
  bool pin = false;                  ///< a pin on its top
  bool hole = false;                 ///< a hole in its bottom
  std::vector<Vec2> loop;            ///< its section: simple, counter-clockwise, on the axis along one edge
  /// Cut into sectors: its quarter turns (0 .. 4 when whole), and where its
  /// joints' pins stand in its caps, (radius, height): the pin of the joint
  /// at to_quadrant, the hole of the joint at from_quadrant.
  int from_quadrant = 0, to_quadrant = 4;
  Vec2 joint_pin{0.0, 0.0};
  TriangleSoup soup;  ///< the revolution of `loop` (a sector's sweep, capped)
  /// Whole sections: what the revolution proves. Sectors carry none and are
  /// validated in full.
  std::optional<TopologyProof> topology;
  std::optional<EmbeddingProof> proof;
  /// Exact volume of its solid: the revolved polygon `loop` (Pappus), for a
  /// sector its share plus its joint pin less its joint hole (cylinders)
  double volume = 0.0;
  bool sector() const { return to_quadrant - from_quadrant < 4; }
};

struct MasterSplit {
  std::vector<double> cuts;  ///< heights of the cuts, upward
  int sectors = 1;           ///< each section's pieces: 1, 2 (halves) or 4 (quarters)
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
