#include "geometry/fairing/tbezier_energy.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/curves/basis.h"
#include "geometry/fairing/gauss_legendre.h"

namespace fabmesh {
namespace {

constexpr double kLo = -2.0, kHi = 1.0;

// Exact minimiser of q(x) = a x^2 + 2 b x over [kLo, kHi] (a >= 0).
double minimise_1d(double a, double b) {
  if (a > 0.0) return std::clamp(-b / a, kLo, kHi);
  return b > 0.0 ? kLo : (b < 0.0 ? kHi : std::clamp(0.0, kLo, kHi));
}

}  // namespace

TBezierEnergy tbezier_curvature_variation_energy(const std::array<Vec2, 4>& p) {
  const double pi5 = std::pow(M_PI, 5);
  const double k1 = pi5 * (13515.0 * M_PI - 29696.0) / 15360.0;
  const double k2 = pi5 * (960.0 * M_PI - 3367.0) / 1920.0;
  const double k3 = pi5 * (1065.0 * M_PI - 3136.0) / 3840.0;
  const double k4 = pi5 * (29.0 - 15.0 * M_PI) / 60.0;
  const double k5 = pi5 * (240.0 * M_PI - 529.0) / 960.0;
  const Vec2 d0 = p[1] - p[0], d1 = p[2] - p[1], d2 = p[3] - p[2];
  TBezierEnergy e;
  e.a0 = k1 * d0.squaredNorm();
  e.a1 = k1 * d2.squaredNorm();
  e.a2 = k2 * d0.dot(d2);
  e.a3 = k3 * d0.squaredNorm() + k4 * d0.dot(d1) + k5 * d0.dot(d2);
  e.a4 = k5 * d0.dot(d2) + k4 * d1.dot(d2) + k3 * d2.squaredNorm();
  const QuadratureRule rule = gauss_legendre(32);
  for (std::size_t i = 0; i < rule.nodes.size(); ++i) {
    const BasisJet w = tbezier_basis(rule.nodes[i], 0.0, 0.0);
    Vec2 r3 = Vec2::Zero();
    for (int j = 0; j < 4; ++j) r3 += w[3][j] * p[j];
    e.c += rule.weights[i] * r3.squaredNorm();
  }
  return e;
}

FairestShape tbezier_fairest(const TBezierEnergy& e) {
  FairestShape best;
  best.energy = std::numeric_limits<double>::infinity();
  auto consider = [&](double l, double m) {
    const double v = e(l, m);
    if (v < best.energy) best = {l, m, v};
  };
  const double det = e.a0 * e.a1 - e.a2 * e.a2;
  if (det > 0.0) {
    const double l = (e.a2 * e.a4 - e.a1 * e.a3) / det;
    const double m = (e.a2 * e.a3 - e.a0 * e.a4) / det;
    if (l >= kLo && l <= kHi && m >= kLo && m <= kHi) {
      consider(l, m);
      return best;
    }
  }
  // On an edge one variable is fixed; the other solves a 1-D quadratic exactly.
  for (double l : {kLo, kHi}) consider(l, minimise_1d(e.a1, e.a2 * l + e.a4));
  for (double m : {kLo, kHi}) consider(minimise_1d(e.a0, e.a2 * m + e.a3), m);
  return best;
}

}  // namespace fabmesh
