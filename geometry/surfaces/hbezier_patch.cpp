#include "geometry/surfaces/hbezier_patch.h"

#include <fmt/format.h>

#include <cmath>

#include "geometry/core/error_checks.h"
#include "geometry/curves/basis.h"

namespace fabmesh {

void require_valid_params(const HBezierParams& p, const std::string& where) {
  const std::string prefix = where.empty() ? "" : where + ".";
  require_in_range(prefix + "alpha", p.alpha, 0.0, 10.0);
  if (p.alpha == 0.0) throw RangeError(prefix + "alpha", p.alpha, prefix + "alpha = 0 is outside (0, 10]");
  const double lo = hbezier_lambda_min(p.alpha);
  for (auto [name, value] : {std::pair{"lambda", p.lambda}, std::pair{"mu", p.mu}}) {
    const std::string field = prefix + name;
    if (!std::isfinite(value) || value <= lo || value > 1.0) {
      throw RangeError(
          field, value,
          fmt::format("{} = {} is outside ({:.6g}, 1] for alpha = {}", field, value, lo, p.alpha));
    }
  }
}

std::array<std::array<double, 4>, 3> unit_hbezier_weights(double x, const HBezierParams& p) {
  return unit_hbezier_weights(x, p, hbezier_constants(p.alpha));
}

std::array<std::array<double, 4>, 3> unit_hbezier_weights(double x, const HBezierParams& p,
                                                          const HBezierConstants& constants) {
  const BasisJet jet = hbezier_basis(x * p.alpha, p.alpha, p.lambda, p.mu, constants);
  std::array<std::array<double, 4>, 3> w{};
  for (int i = 0; i < 4; ++i) {
    const auto k = static_cast<std::size_t>(i);
    w[0][k] = jet[0][k];
    w[1][k] = jet[1][k] * p.alpha;  // d/dx = alpha d/du
    w[2][k] = jet[2][k] * p.alpha * p.alpha;
  }
  return w;
}

HBezierPatch::HBezierPatch(const ControlNet& points, const HBezierParams& u, const HBezierParams& v)
    : points_(points), u_(u), v_(v) {
  require_valid_params(u, "u");
  require_valid_params(v, "v");
  ku_ = hbezier_constants(u.alpha);
  kv_ = hbezier_constants(v.alpha);
  for (std::size_t i = 0; i < 4; ++i) {
    for (std::size_t j = 0; j < 4; ++j) {
      if (!points[i][j].allFinite()) {
        throw RangeError(fmt::format("points[{}][{}]", i, j), points[i][j].sum(),
                         fmt::format("control point P[{}][{}] is not finite", i, j));
      }
    }
  }
}

HBezierPatch::Weights HBezierPatch::u_weights(double s) const { return unit_hbezier_weights(s, u_, ku_); }

HBezierPatch::Weights HBezierPatch::v_weights(double t) const { return unit_hbezier_weights(t, v_, kv_); }

PatchJet HBezierPatch::jet(double s, double t) const { return jet(u_weights(s), v_weights(t)); }

PatchJet HBezierPatch::jet(const Weights& a, const Weights& b) const {
  PatchJet out{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  for (std::size_t i = 0; i < 4; ++i) {
    // Row sums against the v weights, then the u weights.
    Vec3 r0 = Vec3::Zero(), r1 = Vec3::Zero(), r2 = Vec3::Zero();
    for (std::size_t j = 0; j < 4; ++j) {
      r0 += b[0][j] * points_[i][j];
      r1 += b[1][j] * points_[i][j];
      r2 += b[2][j] * points_[i][j];
    }
    out.point += a[0][i] * r0;
    out.ds += a[1][i] * r0;
    out.dss += a[2][i] * r0;
    out.dt += a[0][i] * r1;
    out.dst += a[1][i] * r1;
    out.dtt += a[0][i] * r2;
  }
  return out;
}

Vec3 HBezierPatch::point(double s, double t) const { return jet(s, t).point; }

Vec3 HBezierPatch::normal(double s, double t) const { return normal(jet(s, t), s, t); }

Vec3 HBezierPatch::normal(const PatchJet& j, double s, double t) const {
  const Vec3 n = j.ds.cross(j.dt);
  const double scale = j.ds.squaredNorm() + j.dt.squaredNorm();
  if (n.norm() > 1e-12 * scale && scale > 0.0) return n.normalized();
  // A collapsed border: the limit of the normal from inside the patch.
  for (double step : {1e-7, 1e-5, 1e-3}) {
    const double si = s + (s < 0.5 ? step : -step), ti = t + (t < 0.5 ? step : -step);
    const PatchJet k = jet(si, ti);
    const Vec3 m = k.ds.cross(k.dt);
    if (m.norm() > 1e-12 * (k.ds.squaredNorm() + k.dt.squaredNorm())) return m.normalized();
  }
  return Vec3::Zero();
}

}  // namespace fabmesh
