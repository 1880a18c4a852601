#pragma once
// Slip-casting moulds built by construction: the vessel's outer surface
// (scaled for shrinkage) plus a pour reservoir as the cavity of a plaster
// block split into parts that are closed, outward, embedded meshes without
// any boolean operation, with registration keys on the split faces and a
// check that every part can be withdrawn.

#include <cstddef>
#include <string>
#include <vector>

#include "geometry/core/stage_timer.h"
#include "geometry/core/tolerance_budget.h"
#include "geometry/curves/composite.h"
#include "geometry/mould/keys.h"
#include "geometry/mould/mould_options.h"
#include "geometry/mould/mould_part.h"
#include "geometry/mould/mould_section.h"
#include "geometry/mould/release.h"

namespace fabmesh {

/// The vessel as designed (fired) and as modelled for casting (master = fired x factor).
struct MouldSizes {
  double factor = 1.0;          ///< shrinkage_factor(options.shrinkage)
  double fired_height = 0.0;    ///< rim height - base end height, model units
  double fired_diameter = 0.0;  ///< largest diameter of the sampled profile
  double master_height = 0.0;
  double master_diameter = 0.0;
};

struct Mould {
  std::vector<MouldPart> parts;  ///< side parts in angular order, then the base part if any
  MouldSection section;          ///< master-size section, block and cut
  KeyLayout keys;
  std::vector<SplitPlane> splits;  ///< the split planes (each carries every key)
  MouldSizes sizes;
  double vessel_volume = 0.0;  ///< exact solid of the master profile (Pappus, Gauss-Legendre)
  double spare_volume = 0.0;   ///< exact reservoir (cylinder or truncated cone)
  double cavity_volume = 0.0;  ///< vessel + spare: the slip needed to fill the mould
  double block_volume = 0.0;   ///< exact block (cylinder or box)
  /// Exact net key volume over every split plane: bumps add (2/3) pi r^3,
  /// sockets remove (2/3) pi r_s^3.
  double key_volume = 0.0;
  double plaster_volume = 0.0;  ///< sum of the parts' mesh volumes (signed_volume): the plaster needed
  /// |plaster + cavity - block - key_volume| <= this, to first order in the
  /// deviation: every mesh lies within max_deviation of its exact surface and
  /// only curved surfaces deviate (caps, cut, top, bottom and a box's sides are
  /// exact planes), so the bound is max_deviation x (exact cavity lateral area
  /// + a cylinder block's side + the keys' hemispheres).
  double volume_error_bound = 0.0;
  double max_deviation = 0.0;  ///< proven: largest distance between a part's mesh and its exact surface
  /// How the tolerance was divided among the cavity and block surfaces: the
  /// section (half) and the revolution (what the section left). The keys'
  /// hemispheres are surfaces of their own, each within half the tolerance.
  std::vector<ToleranceShare> tolerance_shares;
  double max_angular_step = 0.0;      ///< radians
  std::vector<Undercut> undercuts;    ///< empty unless options.allow_undercuts (otherwise they throw)
  std::vector<std::string> warnings;  ///< release problems accepted by allow_undercuts
  std::string release_proof;          ///< why every part can be withdrawn (or what cannot)
  StageTimings timings_ms;
};

/// Builds the mould of the vessel whose fired outer profile is `profile`
/// ((radius, height) plane, the higher end is the rim), scaled by
/// shrinkage_factor(options.shrinkage). The parts are not validated here:
/// validate each part's soup with its embedding proof
/// (ValidationOptions::embedding) before writing it.
/// \throw RangeError (options, naming the option), GeometryError (profile;
///        keys, where = "keys[i]"; undercuts, where = "profile", naming the
///        points and heights, unless allow_undercuts; keys that bind with 3
///        parts, where = "key_clearance"), BudgetError (max_triangles).
Mould build_mould(const CompositeCurve& profile, const MouldOptions& options = {});

/// The volume of the solid that `profile` (in the (r, z) half-plane, an open
/// profile closed to the axis at its ends' heights) sweeps about the axis:
/// Pappus, pi |int r^2 dz|, by 40-point Gauss-Legendre on each segment.
double solid_of_revolution_volume(const CompositeCurve& profile);

}  // namespace fabmesh
