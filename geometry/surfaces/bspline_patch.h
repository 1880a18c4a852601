#pragma once
// Bicubic H-Bézier patches as polynomial bicubic B-spline surfaces within a
// proven bound (docs/math/h-bezier.md "Patches as B-spline surfaces"): each
// direction's basis replaced by its C1 cubic Hermite interpolant on a uniform
// grid, which is a cubic B-spline with double interior knots. For STEP files.

#include <array>
#include <cstddef>
#include <vector>

#include "geometry/surfaces/hbezier_patch.h"
#include "geometry/surfaces/patch_network.h"

namespace fabmesh {

/// One direction's four basis functions h_i, each as the cubic B-spline
/// ĥ_i interpolating h_i and h_i' (unit parameter) at x_k = k / n, k = 0..n.
struct HermiteBasis {
  int intervals = 1;                ///< n
  std::vector<double> knots;        ///< the distinct knots x_0 = 0 < ... < x_n = 1
  std::vector<int> multiplicities;  ///< 4, 2, ..., 2, 4 (C1 at the interior knots)
  /// B-spline coefficients c[i][m], m = 0..2n+1: h_i(0), then per interval
  /// k the inner Bézier points h_i(x_k) + h_i'(x_k) / 3n and
  /// h_i(x_k+1) - h_i'(x_k+1) / 3n, then h_i(1).
  std::array<std::vector<double>, 4> coefficients;
  std::array<double, 4> error{};  ///< e_i >= sup |h_i - ĥ_i| over [0, 1]: M4_i / (384 n^4)
  std::array<double, 4> sup{};    ///< >= sup |h_i| over [0, 1] (at most 1)
};

/// \throw RangeError unless intervals >= 1
HermiteBasis hermite_basis(const HBezierParams& params, int intervals);

/// A patch's bicubic B-spline surface Ŝ(s, t) = sum_ij ĥ_i(s) ĝ_j(t) P_ij.
struct BSplinePatch {
  HermiteBasis u, v;  ///< along s (rows i) and along t (columns j)
  /// Poles Q_kl = sum_ij c_ik d_jl P_ij, row-major: k along u (2 n_u + 2
  /// rows), l along v (2 n_v + 2 columns), index k * (2 n_v + 2) + l.
  std::vector<Vec3> poles;
  std::size_t u_poles = 0, v_poles = 0;
  double bound = 0.0;  ///< >= sup |S - Ŝ| over [0, 1]^2, model units
};

/// The proven bound of sup |S - Ŝ| for the net with these bases: with C the
/// control points' mean, sum_ij (e_i G_j + (H_i + e_i) f_j) |P_ij - C| (e, f
/// the bases' errors, H, G their sups), plus the rounding of the poles.
double bspline_patch_bound(const ControlNet& net, const HermiteBasis& u, const HermiteBasis& v);

BSplinePatch bspline_patch(const HBezierPatch& patch, int u_intervals, int v_intervals);

/// Every patch of a network as a B-spline surface within `tolerance`: per
/// direction the fewest intervals (a power of two) that bring the patch's
/// bound within it, then the directions tied by shared borders given the
/// largest of theirs, so that both patches along a border have the same
/// border curve. \throw GeometryError (at the patch's name) when a patch
/// needs more than `max_intervals` in a direction.
struct BSplineNetwork {
  std::vector<BSplinePatch> patches;
  double max_bound = 0.0;
};
BSplineNetwork bspline_network(const PatchNetwork& network, double tolerance, int max_intervals = 1024);

}  // namespace fabmesh
