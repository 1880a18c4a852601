#pragma once
// A casting master wider than the printer's bed, cut by vertical planes
// through its axis into two halves or four quarters. A sector is a section
// of the master (its (radius, height) loop) swept over its quarter turns and
// capped on both cut half-planes by that loop, triangulated. Cut planes at
// multiples of 90 degrees are exact (x = 0 or y = 0), so the caps of
// neighbouring sectors are the same polygon in the same plane. Each joint
// carries one registration pin, perpendicular to it, on one sector's cap
// and the matching hole in the other's: every sector has the pin of the
// joint after it (counter-clockwise) and the hole of the joint before it.

#include <string>
#include <vector>

#include "geometry/core/soup.h"
#include "geometry/core/types.h"

namespace fabmesh {

struct SectorOptions {
  int sectors = 2;           ///< 2 (halves) or 4 (quarters)
  int segments = 64;         ///< the master's angular segments over 360 degrees
  int pin_sides = 24;        ///< sides of the pins' and holes' polygons
  double pin_radius = 0.0;   ///< the joint pin's radius
  double pin_length = 0.0;   ///< how far it stands out of its cap
  double hole_radius = 0.0;  ///< pin radius + clearance
  double hole_depth = 0.0;   ///< pin length + clearance
};

/// The unit direction at `quadrant` quarter turns from x, exactly: the cut
/// planes' directions, which the sectors' sweeps and exact solids share.
Vec2 quadrant_direction(int quadrant);

/// One sector of a master's section.
struct MasterSector {
  int index = 0;                           ///< 0 .. sectors - 1, counter-clockwise from angle 0
  int from_quadrant = 0, to_quadrant = 0;  ///< its angles in quarter turns
  TriangleSoup soup;                       ///< closed and outward; validated in full, not proven
};

/// Where the joint pins of a section stand in its caps: one (radius, height)
/// point of the loop, the same for every joint of the section.
/// \throw GeometryError at "print.pin_diameter" when no point of the loop
///        keeps the hole (hole_radius, hole_depth deep) the pin's radius
///        inside the master and, for quarters, off the other cut plane.
Vec2 place_joint_pin(const std::vector<Vec2>& loop, const SectorOptions& options, const std::string& name);

/// The sectors of the section `loop` (a simple counter-clockwise loop in
/// the (radius, height) half-plane along the axis on one or more edges),
/// each joint's pin and hole at `pin` in its caps.
std::vector<MasterSector> cut_sectors(const std::vector<Vec2>& loop, const Vec2& pin,
                                      const SectorOptions& options);

}  // namespace fabmesh
