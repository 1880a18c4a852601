#pragma once
// Proven bounds of a bicubic H-Bézier patch over a parameter cell
// [s0, s1] x [t0, t1]: enclosures of the basis functions and their
// derivatives, sup bounds of the patch's partial derivatives, and from them
// the deviation of the two-triangle interpolation of the cell from the exact
// surface and from its offset surfaces.

#include <array>

#include "geometry/surfaces/hbezier_patch.h"

namespace fabmesh {

/// d^k h_i / dx^k, k = 0..3, of one direction's basis in the unit parameter x.
using UnitJet = std::array<std::array<double, 4>, 4>;

/// The unit jet at x in [0, 1].
UnitJet unit_jet(double x, const HBezierParams& params, const HBezierConstants& constants);

/// Upper bounds over [0, 1] of |d^4 h_i / dx^4| (hbezier_fourth_bound scaled by alpha^4).
std::array<double, 4> unit_fourth_bound(const HBezierParams& params);

/// A closed interval.
struct Interval {
  double lo = 0.0, hi = 0.0;
  double magnitude() const;  ///< max(|lo|, |hi|)
};

/// Enclosures of d^k h_i / dx^k over an interval of length h, [k][i], k = 0..4.
using BasisEnclosure = std::array<std::array<Interval, 4>, 5>;

/// From the jets at both ends: each derivative lies within the hull of its
/// end values widened by h/2 times the bound of the next derivative (the
/// fourth bound for k = 3, the enclosure of k + 1 below); k = 4 is +-fourth.
BasisEnclosure enclose(const UnitJet& at_start, const UnitJet& at_end, double h,
                       const std::array<double, 4>& fourth);

/// Norms of the control net's differences the bounds use: rows
/// |P_ij - P_0j|, columns |P_ij - P_i0| and twists |P_ij - P_i0 - P_0j + P_00|
/// (the basis derivatives sum to zero, so a derivative weights only these).
struct NetDifferences {
  std::array<std::array<double, 4>, 4> rows{}, columns{}, twists{};
};
NetDifferences net_differences(const ControlNet& net);

/// Sup bounds over a cell of the norms of the patch's partial derivatives
/// (s: d/ds, ...), and a lower bound of |S_s x S_t| (0 when none).
struct CellDerivatives {
  double s = 0.0, t = 0.0;
  double ss = 0.0, st = 0.0, tt = 0.0;
  double sss = 0.0, sst = 0.0, stt = 0.0, ttt = 0.0;
  double normal_low = 0.0;
  /// m[i][j] >= sup |d^(i+j) S / ds^i dt^j| over the cell, 1 <= i + j <= 4.
  std::array<std::array<double, 5>, 5> m{};
  /// The partials at the cell's centre, i + j <= 3.
  std::array<std::array<Vec3, 4>, 4> centre{};
  /// n[p][q] >= sup |d^(p+q) N / ds^p dt^q| of N = S_s x S_t over the cell, p + q <= 3.
  std::array<std::array<double, 4>, 4> n{};
  double ds = 0.0, dt = 0.0;
};

/// The bounds over the cell [s0, s0 + ds] x [t0, t0 + dt] from the basis
/// enclosures of its two intervals and the jets at their midpoints: each
/// second partial is the smaller of its direct enclosure and its value at the
/// centre plus the half-widths times the third partials' bounds.
CellDerivatives cell_derivatives(const ControlNet& net, const NetDifferences& diff, const BasisEnclosure& u,
                                 const BasisEnclosure& v, const UnitJet& u_mid, const UnitJet& v_mid,
                                 double ds, double dt);

/// Deviation of either two-triangle split of the cell from the surface:
/// (M_ss ds^2 + 2 M_st ds dt + M_tt dt^2) / 8 (linear interpolation on a
/// right triangle, Taylor with integral remainder at its circumcentre).
double surface_cell_error(const CellDerivatives& d, double ds, double dt);

/// Second partial bounds of the offset surface S + a n over the cell, each
/// the smaller of a direct bound |S_xy| + |a| (|N_xy| / nu + (p_y |N_x| +
/// p_y p_x + p_x |N_y|) / nu^2), p_x >= sup |N_x x N| / |N| (the part of N_x
/// across N, small near a singular corner where N_x turns with N: bounded
/// by its centre value and its partials' bounds, at most |N_x|), and a
/// mean-value one: the exact value at the centre plus the half-widths
/// times |S_xyz| + |a| (N3 / nu + 9 N2 N1 / nu^2 + 21 N1^3 / nu^3), N = S_s x S_t,
/// Nk >= its k-th partials, nu its lower bound; +infinity when nu is not > 0.
struct OffsetSecond {
  double ss, st, tt;
};
OffsetSecond offset_second(const CellDerivatives& d, double offset);

/// Deviation of the cell's triangles from the offset surface S + offset n
/// (the same formula with the offset's second partial bounds).
double offset_cell_error(const CellDerivatives& d, double offset, double ds, double dt);

/// The partials d^(i+j) S / ds^i dt^j at one point, i + j <= 3.
using PointPartials = std::array<std::array<Vec3, 4>, 4>;
PointPartials point_partials(const ControlNet& net, const UnitJet& u, const UnitJet& v);

/// Half-angle of a cone that holds every unit normal of a cell where the
/// normal may vanish (a singular corner of the parametrisation, e.g. a
/// smoothly rounded rim corner). With v the cell corner whose partials are
/// `at`, and h >= 0 the offsets into the cell (H = h_s + h_t):
/// N(v + h) = N(v) + h_s A + h_t B + Q(h) + R with A, B = +-N_s(v), +-N_t(v),
/// Q the exact quadratic term at v and |R| <= N3 H^3 / 6 (N3 bounds the third
/// partials of N over the cell). With u the mean direction of the
/// generators (N(v) counted when S_s and S_t are not parallel to 1e-8):
/// tan(angle) <= (T0 + e_perp) / (1 - e_along), T0 = max |g_perp| / (g . u),
/// e = (q H + N3 H^2 / 6) / min(A . u, B . u) with q half the largest
/// component (across / along u) of N's second partials at v. +infinity when
/// not provable. Then |(S + a n) - interpolation| <= surface error + |a| 2 sin(angle).
double normal_cone_angle(const PointPartials& at, bool corner_at_s1, bool corner_at_t1,
                         const CellDerivatives& d);

/// Upper bound of the surface's principal curvatures' magnitude over the
/// cell: (M_s^2 + M_t^2) sqrt(M_ss^2 + 2 M_st^2 + M_tt^2) / nu^2 (+infinity
/// when nu is not > 0), 1 / model units.
double curvature_bound(const CellDerivatives& d);

}  // namespace fabmesh
