#pragma once
// Options of a slip-casting mould (design key `mould:`). Lengths are model
// units of the design; the defaults suit millimetres.

#include <cstddef>
#include <vector>

#include "geometry/core/types.h"

namespace fabmesh {

/// The pour reservoir above the rim: a cylinder of the rim's radius, or a
/// cone widening upward from the rim at `spare_taper_deg` from vertical.
enum class SpareShape { Cylinder, Cone };

/// The outside of the mould: a cylinder about the axis, or a square box
/// (sides parallel to the x and y axes) centred on it.
enum class BlockShape { Cylinder, Box };

struct MouldOptions {
  int parts = 2;        ///< side parts split by half-planes through the axis: 2 or 3
  double wall = 30.0;   ///< least plaster thickness around the exact cavity (> 0)
  double spare = 25.0;  ///< height of the pour reservoir above the rim (> 0)
  SpareShape spare_shape = SpareShape::Cylinder;
  double spare_taper_deg = 15.0;  ///< cone only: wall angle from vertical, in (0, 60]
  BlockShape block = BlockShape::Cylinder;
  /// Cylinder radius or half the box's side; 0 derives the least allowed:
  /// largest cavity radius (+ sampling bound) + wall. A smaller value is a RangeError.
  double block_radius = 0.0;
  /// A separate base part under the side parts, cut by the plane
  /// z = (the vessel's base end height) + base_height; pulled down.
  bool base_part = false;
  double base_height = 0.0;    ///< >= 0; 0 cuts at the vessel's floor
  int keys = 4;                ///< registration keys per split plane (0: none)
  double key_radius = 6.0;     ///< hemispherical bump radius (> 0)
  double key_clearance = 0.2;  ///< socket radius = key_radius + key_clearance (>= 0)
  /// Least distance from a socket to the cavity and the block's edges; 0 derives key_radius / 2.
  double key_margin = 0.0;
  /// Key centres (r, z) in the split planes, master size; empty spreads
  /// `keys` evenly up the middle of the wall.
  std::vector<Vec2> key_positions;
  double shrinkage = 0.0;  ///< clay shrinkage in [0, 1): the cavity is the profile times 1 / (1 - s)
  /// Build even when a part cannot be withdrawn (the undercuts are still reported).
  bool allow_undercuts = false;
  double tolerance = 0.05;               ///< largest distance between each mesh and its exact surface (> 0)
  std::size_t max_triangles = 20000000;  ///< budget over all parts; more is a BudgetError
};

}  // namespace fabmesh
