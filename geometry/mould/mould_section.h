#pragma once
// The section of a slip-casting mould in the (radius, height) half-plane:
// the block's outline minus the cavity (the vessel's solid with the pour
// reservoir on its rim, open at the top), optionally cut by a horizontal
// plane into the side parts' section and the base part's section.

#include <cstddef>
#include <string>
#include <vector>

#include "geometry/curves/composite.h"
#include "geometry/mesh/sweep.h"
#include "geometry/mould/mould_options.h"

namespace fabmesh {

struct MouldSection {
  /// The cavity's boundary, walking down: the opening corner (r_open, z_top),
  /// the reservoir's wall, the sampled profile from the rim to the base end,
  /// then the axis point (0, z_base) under the floor (unless the base end is
  /// on the axis). Master size, model units.
  std::vector<Vec2> cavity;
  std::size_t profile_begin = 0;  ///< index in `cavity` of the rim
  std::size_t profile_end = 0;    ///< one past the index of the base end
  double max_deviation = 0.0;     ///< proven bound between the sampled profile and the exact one
  double cavity_radius = 0.0;     ///< bound on the exact cavity's largest radius (vertices + max_deviation)
  double block_radius = 0.0;      ///< cylinder radius, or half the box's side
  double z_bottom = 0.0;          ///< block bottom: lowest cavity point - max_deviation - wall
  double z_top = 0.0;             ///< block top = rim height + spare
  double rim_radius = 0.0, rim_z = 0.0, base_radius = 0.0, base_z = 0.0, opening_radius = 0.0;
  bool has_cut = false;
  double z_cut = 0.0;  ///< height of the base cut (when has_cut)
  /// Side parts' section: counter-clockwise, simple; on_outline marks the
  /// block's outer vertices (their radius follows a box's outline).
  SweepSection side;
  SweepSection base;  ///< base part's section (empty loop when no cut)
  /// The cavity's boundary within each section, walking down from the top
  /// of that section (for the release check and the key clearances).
  std::vector<Vec2> side_cavity, base_cavity;
  std::string proof;  ///< why the sections are simple
};

/// Samples the master profile (proven deviation <= `profile_tolerance`) and
/// builds the sections. The profile's higher end is the rim.
/// \throw RangeError (an option out of range; block_radius smaller than the
///        cavity radius + wall, naming both), GeometryError (closed profile,
///        rim on the axis, profile touching the axis, profile above the top of
///        the reservoir, a section that is not simple, a base cut crossing the
///        cavity more than once), BudgetError (sampling).
MouldSection build_mould_section(const CompositeCurve& master_profile, const MouldOptions& options,
                                 double profile_tolerance);

/// Checks the options' ranges (everything but the geometry). \throw RangeError naming the option.
void check_mould_options(const MouldOptions& options);

}  // namespace fabmesh
