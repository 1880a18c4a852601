#pragma once
// Networks of generalized bicubic H-Bézier patches (docs/math/h-bezier.md): each patch
// explicit or joined to an earlier one along one of its sides, with the
// border-to-border joint report measured on the exact surfaces.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "geometry/curves/composite.h"
#include "geometry/surfaces/hbezier_patch.h"

namespace fabmesh {

/// A side of a patch: UMin is row i = 0 (s = 0), UMax row 3 (s = 1), VMin
/// column j = 0 (t = 0), VMax column 3 (t = 1).
enum class PatchSide { UMin, UMax, VMin, VMax };

/// "u_min", "u_max", "v_min", "v_max" (the names design files use).
const char* to_string(PatchSide side);

/// How a patch is joined to an earlier one. The new patch attaches with its
/// opposite side (u_max of `to` meets u_min of the new patch); the rows next
/// to the border are computed, as many as the continuity needs (G0: 1, G1: 2, G2: 3).
struct PatchJoin {
  std::size_t to = 0;  ///< index of an earlier patch
  PatchSide side = PatchSide::UMax;
  Continuity continuity = Continuity::G1;  ///< G0, G1 or G2
  /// G1: Q_1j = P_3j + gamma (P_3j - P_2j), gamma > 0 (mirrored for u_min / v_min).
  double gamma = 1.0;
  /// G2: the curve join constants of docs/math/h-bezier.md, applied row by row (k > 0).
  double k = 1.0;
  double m = 0.0;
};

/// A patch as a designer gives it.
struct PatchSpec {
  std::string name;
  /// Its design key path ("patches[1]"), where errors about it are
  /// (messages name it "patches[1] ('name')"); empty: none.
  std::string key;
  HBezierParams u, v;
  std::optional<PatchJoin> join;
  /// Explicit: 4 rows (i = 0..3) of 4 points (j = 0..3). Joined along u
  /// (side u_min/u_max): the free rows in increasing i, each 4 points along v.
  /// Joined along v: the free columns in increasing j, each 4 points along u.
  std::vector<std::array<Vec3, 4>> points;
};

/// Two patch sides that are the same curve (same control points, same
/// parameterisation), declared by a join or found by coincidence.
struct SharedBorder {
  std::size_t a = 0, b = 0;  ///< patch indices, a < b
  PatchSide side_a = PatchSide::UMax, side_b = PatchSide::UMin;
  bool reversed = false;                   ///< b's border runs the opposite way
  Continuity declared = Continuity::None;  ///< None: found, not declared
  Continuity achieved = Continuity::None;  ///< measured: G0 gap, G1 normals, G2 cross curvature
  double gap = 0.0;                        ///< max distance of the two border curves, sampled, model units
  double normal_angle = 0.0;               ///< max angle of the two unit normals along the border, rad
  double curvature_jump =
      0.0;  ///< max jump of the cross-border curves' curvature, relative to the larger one
};

struct NetworkOptions {
  int samples = 257;  ///< samples along each shared border for the joint report
  /// Border points closer than this times the network's size coincide.
  double relative_gap_tolerance = 1e-9;
  double angle_tolerance = 1e-6;  ///< rad: G1 when the normals agree this well
  /// G2 when the cross curvatures agree to this relative tolerance.
  double relative_curvature_tolerance = 1e-6;
};

struct PatchNetwork {
  std::vector<std::string> names;
  std::vector<HBezierPatch> patches;
  std::vector<SharedBorder> borders;
  double size = 0.0;  ///< diagonal of the control points' bounding box, model units
};

/// The four control points of a side, in the direction of its parameter.
std::array<Vec3, 4> border_points(const HBezierPatch& patch, PatchSide side);
/// The shape parameters along a side (v for u sides, u for v sides).
const HBezierParams& border_params(const HBezierPatch& patch, PatchSide side);
/// (s, t) of the point at parameter x in [0, 1] along a side.
std::array<double, 2> border_uv(PatchSide side, double x);

/// Whether a side's four control points are one point within `eps` (a pole).
bool collapsed_side(const HBezierPatch& patch, PatchSide side, double eps);

/// Which sides of each patch (indexed by PatchSide) are on the network's
/// outer border: shared with no other patch and not collapsed to a point
/// (within 1e-12 of the network's size).
std::vector<std::array<bool, 4>> outer_sides(const PatchNetwork& network);

/// Control points Q_1 (G1) and Q_2 (G2) of a curve joined at the end of
/// P_0..P_3 (docs/math/h-bezier.md "Joining curves"), Q_0 = P_3. For G1 the `gamma` of
/// `join` is rho; for G2 rho = k a1(p) / a0(q) and Q_2 follows. Returns
/// {Q_0, Q_1, Q_2} (entries past the continuity are left as P_3).
std::array<Vec3, 3> join_curve_points(const std::array<Vec3, 4>& p, const HBezierParams& p_params,
                                      const HBezierParams& q_params, const PatchJoin& join);

/// Builds every patch (computing joined rows), finds every shared border and
/// measures it. \throw RangeError (parameters), GeometryError (unknown or
/// later `to`, wrong number of free rows, control points all on one line
/// (the patch is a curve), a border direction parameterised
/// differently from the patch it joins, a declared continuity the
/// measurement contradicts, a side shared by more than two patches).
PatchNetwork build_patch_network(const std::vector<PatchSpec>& specs, const NetworkOptions& options = {});

}  // namespace fabmesh
