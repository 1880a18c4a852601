#include "geometry/surfaces/cell_bound.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fabmesh {
namespace {

// Magnitude bounds of the four basis functions' k-th derivatives over an enclosure.
std::array<double, 4> magnitudes(const BasisEnclosure& e, int k) {
  std::array<double, 4> m{};
  for (std::size_t i = 0; i < 4; ++i) m[i] = e[k][i].magnitude();
  if (k == 0) {
    for (double& x : m) x = std::min(x, 1.0);  // a non-negative partition of unity
  }
  return m;
}

// Sup bound of |sum_ij a_i^(ka) b_j^(kb) P_ij| over the cell (ka + kb >= 1),
// weighting only the differences that survive sum_i a_i^(k) = 0 (k >= 1).
double partial_bound(const NetDifferences& d, const BasisEnclosure& u, const BasisEnclosure& v, int ka,
                     int kb) {
  const auto a = magnitudes(u, ka);
  const auto b = magnitudes(v, kb);
  double sum = 0.0;
  for (std::size_t i = 0; i < 4; ++i) {
    for (std::size_t j = 0; j < 4; ++j) {
      const double diff = ka >= 1 && kb >= 1 ? d.twists[i][j] : ka >= 1 ? d.rows[i][j] : d.columns[i][j];
      sum += a[i] * b[j] * diff;
    }
  }
  return sum;
}

Vec3 partial_at(const ControlNet& net, const UnitJet& u, const UnitJet& v, int ka, int kb) {
  Vec3 sum = Vec3::Zero();
  for (std::size_t i = 0; i < 4; ++i) {
    for (std::size_t j = 0; j < 4; ++j) sum += u[ka][i] * v[kb][j] * net[i][j];
  }
  return sum;
}

double quadratic_error(double ss, double st, double tt, double ds, double dt) {
  return (ss * ds * ds + 2.0 * st * ds * dt + tt * dt * dt) / 8.0;
}

}  // namespace

UnitJet unit_jet(double x, const HBezierParams& p, const HBezierConstants& constants) {
  const BasisJet jet = hbezier_basis(x * p.alpha, p.alpha, p.lambda, p.mu, constants);
  UnitJet out{};
  double scale = 1.0;
  for (std::size_t k = 0; k < 4; ++k) {
    for (std::size_t i = 0; i < 4; ++i) out[k][i] = jet[k][i] * scale;
    scale *= p.alpha;  // d/dx = alpha d/du
  }
  return out;
}

std::array<double, 4> unit_fourth_bound(const HBezierParams& p) {
  std::array<double, 4> b = hbezier_fourth_bound(p.alpha, p.lambda, p.mu);
  const double a4 = std::pow(p.alpha, 4);
  for (double& x : b) x *= a4;
  return b;
}

double Interval::magnitude() const { return std::max(std::abs(lo), std::abs(hi)); }

BasisEnclosure enclose(const UnitJet& a, const UnitJet& b, double h, const std::array<double, 4>& fourth) {
  BasisEnclosure e{};
  const double half = 0.5 * h;
  for (std::size_t i = 0; i < 4; ++i) e[4][i] = {-fourth[i], fourth[i]};
  for (int k = 3; k >= 0; --k) {
    for (std::size_t i = 0; i < 4; ++i) {
      const double slope = k == 3 ? fourth[i] : e[k + 1][i].magnitude();
      e[k][i] = {std::min(a[k][i], b[k][i]) - half * slope, std::max(a[k][i], b[k][i]) + half * slope};
    }
  }
  return e;
}

NetDifferences net_differences(const ControlNet& p) {
  NetDifferences d;
  for (std::size_t i = 0; i < 4; ++i) {
    for (std::size_t j = 0; j < 4; ++j) {
      d.rows[i][j] = (p[i][j] - p[0][j]).norm();
      d.columns[i][j] = (p[i][j] - p[i][0]).norm();
      d.twists[i][j] = (p[i][j] - p[i][0] - p[0][j] + p[0][0]).norm();
    }
  }
  return d;
}

namespace {

double binomial(int n, int k) { return k == 0 || k == n ? 1.0 : (n == 2 ? 2.0 : 3.0); }  // n <= 3

// A partial d^(p+q) / ds^p dt^q of N = S_s x S_t by Leibniz: the sum of
// C(p, p1) C(q, q1) product(S-side indices, S_t-side indices).
template <class Value, class Product>
Value leibniz(int p, int q, const Product& product, Value sum) {
  for (int p1 = 0; p1 <= p; ++p1) {
    for (int q1 = 0; q1 <= q; ++q1) {
      sum = sum + binomial(p, p1) * binomial(q, q1) * product(1 + p1, q1, p - p1, 1 + q - q1);
    }
  }
  return sum;
}

}  // namespace

CellDerivatives cell_derivatives(const ControlNet& net, const NetDifferences& diff, const BasisEnclosure& u,
                                 const BasisEnclosure& v, const UnitJet& u_mid, const UnitJet& v_mid,
                                 double ds, double dt) {
  CellDerivatives d;
  d.ds = ds;
  d.dt = dt;
  const double hs = 0.5 * ds, ht = 0.5 * dt;
  for (int i = 0; i <= 3; ++i) {
    for (int j = 0; i + j <= 3; ++j) d.centre[i][j] = partial_at(net, u_mid, v_mid, i, j);
  }
  // Order 4 directly; orders 3..1 the smaller of direct and centre + mean value.
  for (int order = 4; order >= 1; --order) {
    for (int i = 0; i <= order; ++i) {
      const int j = order - i;
      double bound = partial_bound(diff, u, v, i, j);
      if (order < 4) bound = std::min(bound, d.centre[i][j].norm() + hs * d.m[i + 1][j] + ht * d.m[i][j + 1]);
      d.m[i][j] = bound;
    }
  }
  d.s = d.m[1][0], d.t = d.m[0][1];
  d.ss = d.m[2][0], d.st = d.m[1][1], d.tt = d.m[0][2];
  d.sss = d.m[3][0], d.sst = d.m[2][1], d.stt = d.m[1][2], d.ttt = d.m[0][3];
  for (int p = 0; p <= 3; ++p) {
    for (int q = 0; p + q <= 3; ++q) {
      d.n[p][q] = leibniz<double>(
          p, q, [&](int a, int b, int c, int e) { return d.m[a][b] * d.m[c][e]; }, 0.0);
    }
  }
  const Vec3 normal = d.centre[1][0].cross(d.centre[0][1]);
  d.normal_low = std::max(0.0, normal.norm() - hs * d.n[1][0] - ht * d.n[0][1]);
  return d;
}

double surface_cell_error(const CellDerivatives& d, double ds, double dt) {
  return quadratic_error(d.ss, d.st, d.tt, ds, dt);
}

OffsetSecond offset_second(const CellDerivatives& d, double offset) {
  const double nu = d.normal_low;
  if (!(nu > 0.0)) {
    const double inf = std::numeric_limits<double>::infinity();
    return {inf, inf, inf};
  }
  const double a = std::abs(offset), nu2 = nu * nu;
  const auto& n = d.n;
  auto cross = [&](int p, int q) {
    return leibniz<Vec3>(
        p, q, [&](int i, int j, int k, int l) { return Vec3(d.centre[i][j].cross(d.centre[k][l])); },
        Vec3(Vec3::Zero()));
  };
  const double hs = 0.5 * d.ds, ht = 0.5 * d.dt;
  // Direct: the unit normal's second partials from N's, over the whole cell:
  // u_xy = P N_xy / |N| - (P N_y (u . N_x) + u (P N_y . P N_x) + P N_x (u . N_y)) / |N|^2
  // with P = I - u u^T, so |u_xy| <= |N_xy| / nu + (p_y |N_x| + p_y p_x + p_x |N_y|) / nu^2,
  // p_x >= sup |P N_x| = sup |N_x x N| / |N|. Near a singular corner N_x turns
  // with N, so p_x is much smaller than |N_x|: bound sup |N_x x N| by its
  // value at the centre plus the half-widths times its partials' bounds,
  // (N_s x N)_s = N_ss x N, (N_s x N)_t = N_st x N + N_s x N_t (and alike
  // for t), sup |N_s x N_t| again by its centre value and its partials.
  const Vec3 c00 = cross(0, 0), c10 = cross(1, 0), c01 = cross(0, 1);
  const double n0 = n[0][0];
  const double twist = c10.cross(c01).norm() + hs * (n[2][0] * n[0][1] + n[1][0] * n[1][1]) +
                       ht * (n[1][1] * n[0][1] + n[1][0] * n[0][2]);
  const double ps =
      std::min(n[1][0], (c10.cross(c00).norm() + hs * n[2][0] * n0 + ht * (n[1][1] * n0 + twist)) / nu);
  const double pt =
      std::min(n[0][1], (c01.cross(c00).norm() + ht * n[0][2] * n0 + hs * (n[1][1] * n0 + twist)) / nu);
  const OffsetSecond direct{d.ss + a * (n[2][0] / nu + (2.0 * ps * n[1][0] + ps * ps) / nu2),
                            d.st + a * (n[1][1] / nu + (pt * n[1][0] + pt * ps + ps * n[0][1]) / nu2),
                            d.tt + a * (n[0][2] / nu + (2.0 * pt * n[0][1] + pt * pt) / nu2)};
  // Mean value: the exact second partials of S + offset u (u = N / |N|) at the centre ...
  const Vec3& big_n = c00;
  const double length = big_n.norm();
  if (!(length > 0.0)) return direct;
  const Vec3 unit = big_n / length;
  const Vec3& ns = c10;
  const Vec3& nt = c01;
  const Vec3 us = (ns - unit.dot(ns) * unit) / length, ut = (nt - unit.dot(nt) * unit) / length;
  // u_xy = (N_xy - (u_y . N_x + u . N_xy) u - (u . N_x) u_y) / |N| - (u . N_y) / |N| u_x
  auto second = [&](const Vec3& nx, const Vec3& ux, const Vec3& ny, const Vec3& uy, const Vec3& nxy) {
    return Vec3((nxy - (uy.dot(nx) + unit.dot(nxy)) * unit - unit.dot(nx) * uy) / length -
                unit.dot(ny) / length * ux);
  };
  const Vec3 uss = second(ns, us, ns, us, cross(2, 0)), ust = second(ns, us, nt, ut, cross(1, 1)),
             utt = second(nt, ut, nt, ut, cross(0, 2));
  // ... plus the half-widths times the bounds of the third partials (third derivatives of N / |N|).
  const double n1 = std::max(n[1][0], n[0][1]), n2 = std::max({n[2][0], n[1][1], n[0][2]}),
               n3 = std::max({n[3][0], n[2][1], n[1][2], n[0][3]});
  const double third = a * (n3 / nu + 9.0 * n2 * n1 / nu2 + 21.0 * n1 * n1 * n1 / (nu2 * nu));
  const OffsetSecond mean{
      (d.centre[2][0] + offset * uss).norm() + hs * (d.sss + third) + ht * (d.sst + third),
      (d.centre[1][1] + offset * ust).norm() + hs * (d.sst + third) + ht * (d.stt + third),
      (d.centre[0][2] + offset * utt).norm() + hs * (d.stt + third) + ht * (d.ttt + third)};
  return {std::min(direct.ss, mean.ss), std::min(direct.st, mean.st), std::min(direct.tt, mean.tt)};
}

double offset_cell_error(const CellDerivatives& d, double offset, double ds, double dt) {
  const OffsetSecond o = offset_second(d, offset);
  return quadratic_error(o.ss, o.st, o.tt, ds, dt);
}

PointPartials point_partials(const ControlNet& net, const UnitJet& u, const UnitJet& v) {
  PointPartials out{};
  for (int i = 0; i <= 3; ++i) {
    for (int j = 0; i + j <= 3; ++j) out[i][j] = partial_at(net, u, v, i, j);
  }
  return out;
}

double normal_cone_angle(const PointPartials& at, bool corner_at_s1, bool corner_at_t1,
                         const CellDerivatives& d) {
  const double inf = std::numeric_limits<double>::infinity();
  auto cross = [&](int p, int q) {
    return leibniz<Vec3>(
        p, q, [&](int i, int j, int k, int l) { return Vec3(at[i][j].cross(at[k][l])); }, Vec3(Vec3::Zero()));
  };
  Vec3 n0 = cross(0, 0);
  // S_s and S_t parallel up to rounding (sine of their angle below 1e-8): a
  // singular corner by construction, N(v) = 0.
  if (n0.norm() <= 1e-8 * at[1][0].norm() * at[0][1].norm()) n0 = Vec3::Zero();
  const Vec3 a = cross(1, 0) * (corner_at_s1 ? -1.0 : 1.0);
  const Vec3 b = cross(0, 1) * (corner_at_t1 ? -1.0 : 1.0);
  if (!(a.norm() > 0.0) || !(b.norm() > 0.0)) return inf;
  Vec3 axis = a.normalized() + b.normalized();
  if (n0.norm() > 0.0) axis += n0.normalized();
  if (!(axis.norm() > 0.0)) return inf;
  axis.normalize();
  double tan0 = 0.0, along_min = inf;
  const std::array<Vec3, 3> generators{a, b, n0};
  for (std::size_t k = 0; k < 3; ++k) {
    const Vec3& g = generators[k];
    if (g.norm() == 0.0) continue;
    const double along = g.dot(axis);
    if (!(along > 0.0)) return inf;
    tan0 = std::max(tan0, (g - along * axis).norm() / along);
    if (k < 2) along_min = std::min(along_min, along);
  }
  // The quadratic term, exact at v: across and along the axis (|Q| <= q H^2).
  double q_across = 0.0, q_along = 0.0;
  for (const Vec3& second : {cross(2, 0), cross(1, 1), cross(0, 2)}) {
    const double along = second.dot(axis);
    q_across = std::max(q_across, 0.5 * (second - along * axis).norm());
    q_along = std::max(q_along, 0.5 * std::abs(along));
  }
  const double n3 = std::max({d.n[3][0], d.n[2][1], d.n[1][2], d.n[0][3]});
  const double h = d.ds + d.dt, cubic = n3 * h * h / 6.0;
  const double e_across = (q_across * h + cubic) / along_min, e_along = (q_along * h + cubic) / along_min;
  if (!(e_along < 1.0)) return inf;
  return std::atan((tan0 + e_across) / (1.0 - e_along));
}

double curvature_bound(const CellDerivatives& d) {
  const double nu = d.normal_low;
  if (!(nu > 0.0)) return std::numeric_limits<double>::infinity();
  return (d.s * d.s + d.t * d.t) * std::sqrt(d.ss * d.ss + 2.0 * d.st * d.st + d.tt * d.tt) / (nu * nu);
}

}  // namespace fabmesh
