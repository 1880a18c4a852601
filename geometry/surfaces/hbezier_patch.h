#pragma once
// Generalized bicubic H-Bézier patches (docs/math/h-bezier.md "Bicubic surfaces"):
// S(u, v) = sum_ij h_i(u) h_j(v) P_ij, each direction with its own
// (alpha, lambda, mu). Evaluated in unit parameters s = u / alpha_u and
// t = v / alpha_v in [0, 1]; derivatives are with respect to s and t.

#include <array>
#include <string>

#include "geometry/core/types.h"
#include "geometry/curves/basis.h"

namespace fabmesh {

/// The shape parameters of one direction of a patch (or of one H-Bézier curve).
struct HBezierParams {
  double alpha = 1.0;   ///< in (0, 10]
  double lambda = 0.0;  ///< in (lambda*(alpha), 1], acts near the second control point
  double mu = 0.0;      ///< in (lambda*(alpha), 1], acts near the third control point

  /// The same basis run backwards: (alpha, mu, lambda).
  HBezierParams reversed() const { return {alpha, mu, lambda}; }
  bool operator==(const HBezierParams& o) const {
    return alpha == o.alpha && lambda == o.lambda && mu == o.mu;
  }
  bool operator!=(const HBezierParams& o) const { return !(*this == o); }
};

/// Throws RangeError unless alpha is in (0, 10] and lambda, mu are in
/// (lambda*(alpha), 1]; `where` prefixes the field names ("u.alpha").
void require_valid_params(const HBezierParams& params, const std::string& where);

/// Control net: P[i][j], i along u (rows), j along v. Model units.
using ControlNet = std::array<std::array<Vec3, 4>, 4>;

/// Point and derivatives of a patch at (s, t): d/ds, d/dt and second orders.
struct PatchJet {
  Vec3 point, ds, dt, dss, dst, dtt;
};

/// One bicubic generalized H-Bézier patch.
class HBezierPatch {
 public:
  /// \throw RangeError for parameters out of range or non-finite control points.
  HBezierPatch(const ControlNet& points, const HBezierParams& u, const HBezierParams& v);

  const ControlNet& points() const { return points_; }
  const HBezierParams& u() const { return u_; }
  const HBezierParams& v() const { return v_; }

  /// Point and first and second partial derivatives at (s, t) in [0, 1]^2.
  PatchJet jet(double s, double t) const;
  Vec3 point(double s, double t) const;
  /// Unit normal (S_s x S_t normalised). Where that cross product vanishes (a
  /// collapsed border or a cusp) the normal is taken a little inside the
  /// patch; a patch degenerate everywhere near (s, t) gives the zero vector.
  Vec3 normal(double s, double t) const;

  /// On a grid, each direction's weights computed once per grid line:
  /// w[k][i] = d^k h_i / dx^k at s (u_weights) or t (v_weights), and the jet
  /// and normal from them, the same numbers as jet(s, t) and normal(s, t).
  using Weights = std::array<std::array<double, 4>, 3>;
  Weights u_weights(double s) const;
  Weights v_weights(double t) const;
  PatchJet jet(const Weights& at_s, const Weights& at_t) const;
  /// normal(s, t) given the jet there (jet(s, t)).
  Vec3 normal(const PatchJet& at, double s, double t) const;

 private:
  ControlNet points_;
  HBezierParams u_, v_;
  HBezierConstants ku_, kv_;  ///< hbezier_constants of u_.alpha and v_.alpha, computed once
};

/// The four H-Bézier weights of one direction at unit parameter x in [0, 1]
/// and their first two derivatives with respect to x: w[k][i] = d^k h_i / dx^k.
std::array<std::array<double, 4>, 3> unit_hbezier_weights(double x, const HBezierParams& params);

/// The same with the constants of params.alpha computed once by the caller.
std::array<std::array<double, 4>, 3> unit_hbezier_weights(double x, const HBezierParams& params,
                                                          const HBezierConstants& constants);

}  // namespace fabmesh
