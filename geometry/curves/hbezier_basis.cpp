#include <cmath>

#include "geometry/curves/basis.h"

namespace fabmesh {
namespace {

// Below this |x| the cancelling differences are summed as series.
constexpr double kSeriesLimit = 1.0;
constexpr int kSeriesTerms = 14;

// sum_{k >= k0} x^(2k + parity) / (2k + parity)!
double even_odd_series(double x, int k0, int parity) {
  double term = 1.0;
  const int first = 2 * k0 + parity;
  for (int i = 1; i <= first; ++i) term *= x / i;
  double sum = 0.0;
  for (int k = k0; k < k0 + kSeriesTerms; ++k) {
    sum += term;
    // All terms have the sign of the first and shrink: stop once they no longer change the sum.
    if (std::abs(term) <= 1e-17 * std::abs(sum)) break;
    const int n = 2 * k + parity;
    term *= x * x / ((n + 1) * (n + 2));
  }
  return sum;
}

// The hyperbolic functions the basis takes of one argument x, each computed
// once (the same functions, so the same numbers, as called one by one).
struct Hyperbolic {
  double sinh, cosh, sinh_minus_x, cosh_minus_1, cosh_minus_1_minus_half_x2;
};

Hyperbolic hyperbolic(double x) {
  Hyperbolic h{std::sinh(x), std::cosh(x), 0.0, cosh_minus_1(x), 0.0};
  const bool series = std::abs(x) < kSeriesLimit;
  h.sinh_minus_x = series ? even_odd_series(x, 1, 1) : h.sinh - x;
  h.cosh_minus_1_minus_half_x2 = series ? even_odd_series(x, 2, 0) : h.cosh - 1.0 - 0.5 * x * x;
  return h;
}

// The numerator N(u) of H2 and its first three u-derivatives:
// N = sinh(a-u) - (a-u) + sinh(u) - u - (sinh a - a) + u (cosh a - 1) - a (cosh u - 1),
// which equals the spec's a - u + sinh(a-u) + sinh u - sinh a + u cosh a - a cosh u.
// For a >= kSeriesLimit from the hyperbolic functions of u and of v = a - u
// (hu, hv) and the constants S = sinh a - a, C = cosh a - 1.
std::array<double, 4> h2_numerator(double u, double a, const Hyperbolic& hu, const Hyperbolic& hv,
                                   const HBezierConstants& constants) {
  if (a >= kSeriesLimit) {
    const double s = constants.s, c = constants.c;
    return {hv.sinh_minus_x + hu.sinh_minus_x - s + u * c - a * hu.cosh_minus_1,
            -hv.cosh_minus_1 + hu.cosh_minus_1 + c - a * hu.sinh, hv.sinh + hu.sinh - a * hu.cosh,
            -hv.cosh + hu.cosh - a * hu.sinh};
  }
  // Small alpha: N = sum_{k>=2} a^(2k+1) f_k(t), t = u/a, where
  // f_k(t) = ((1-t)^(2k+1) + t^(2k+1) - 1)/(2k+1)! + (t - t^(2k))/(2k)!  (the k = 1 term is 0).
  // Derivatives in u: d^j N/du^j = sum a^(2k+1-j) f_k^(j)(t).
  const double t = u / a;
  const double w = 1.0 - t;
  std::array<double, 4> n{};
  // fact[i] = 1/i!
  double inv_fact[2 * (kSeriesTerms + 2) + 2];
  inv_fact[0] = 1.0;
  for (int i = 1; i < static_cast<int>(std::size(inv_fact)); ++i) inv_fact[i] = inv_fact[i - 1] / i;
  for (int k = 2; k < 2 + kSeriesTerms; ++k) {
    const int m = 2 * k;
    const double wm3 = std::pow(w, m - 3), tm3 = std::pow(t, m - 3);
    const double wm2 = wm3 * w, tm2 = tm3 * t;
    const double wm1 = wm2 * w, tm1 = tm2 * t;
    const double wm = wm1 * w, tm = tm1 * t;
    const double f0 = (wm * w + tm * t - 1.0) * inv_fact[m + 1] + (t - tm) * inv_fact[m];
    const double f1 = (1.0 - wm + tm - m * tm1) * inv_fact[m];
    const double f2 = (wm1 + tm1) * inv_fact[m - 1] - tm2 * inv_fact[m - 2];
    const double f3 = (tm2 - wm2) * inv_fact[m - 2] - tm3 * inv_fact[m - 3];
    const double ak = std::pow(a, m - 2);  // a^(2k+1-j) = a^(2k-2) * a^(3-j)
    n[0] += ak * a * a * a * f0;
    n[1] += ak * a * a * f1;
    n[2] += ak * a * f2;
    n[3] += ak * f3;
  }
  return n;
}

}  // namespace

double sinh_minus_x(double x) {
  return std::abs(x) < kSeriesLimit ? even_odd_series(x, 1, 1) : std::sinh(x) - x;
}
double cosh_minus_1(double x) {
  // cosh x - 1 = 2 sinh^2(x/2): no cancellation at any x.
  const double h = std::sinh(0.5 * x);
  return 2.0 * h * h;
}
double cosh_minus_1_minus_half_x2(double x) {
  return std::abs(x) < kSeriesLimit ? even_odd_series(x, 2, 0) : std::cosh(x) - 1.0 - 0.5 * x * x;
}

HBezierConstants hbezier_constants(double alpha) {
  const double a = alpha;
  double e = 0.0;
  if (a < kSeriesLimit) {
    // E = sum_{k>=1} a^(2k+1) (1/(2k)! - 2/(2k+1)!)
    double power = a * a * a, fact_even = 2.0;  // a^(2k+1), (2k)!
    for (int k = 1; k <= kSeriesTerms; ++k) {
      e += power * (1.0 / fact_even - 2.0 / (fact_even * (2 * k + 1)));
      power *= a * a;
      fact_even *= (2.0 * k + 1) * (2.0 * k + 2);
    }
  } else {
    e = a * (1.0 + std::cosh(a)) - 2.0 * std::sinh(a);
  }
  return {sinh_minus_x(a), cosh_minus_1(a), cosh_minus_1_minus_half_x2(a), e};
}

BasisJet hbezier_basis(double u, double alpha, double lambda, double mu) {
  return hbezier_basis(u, alpha, lambda, mu, hbezier_constants(alpha));
}

BasisJet hbezier_basis(double u, double alpha, double lambda, double mu, const HBezierConstants& constants) {
  const double a = alpha;
  const auto [s, c, d, e] = constants;
  const double v = a - u;
  const Hyperbolic hu = hyperbolic(u), hv = hyperbolic(v);
  // Classical basis and quartic end functions with u-derivatives 0..3.
  const std::array<double, 4> h0{hv.sinh_minus_x / s, -hv.cosh_minus_1 / s, hv.sinh / s, -hv.cosh / s};
  const std::array<double, 4> h3{hu.sinh_minus_x / s, hu.cosh_minus_1 / s, hu.sinh / s, hu.cosh / s};
  const std::array<double, 4> k0{hv.cosh_minus_1_minus_half_x2 / d, -hv.sinh_minus_x / d, hv.cosh_minus_1 / d,
                                 -hv.sinh / d};
  const std::array<double, 4> k3{hu.cosh_minus_1_minus_half_x2 / d, hu.sinh_minus_x / d, hu.cosh_minus_1 / d,
                                 hu.sinh / d};
  const double scale = std::sinh(a) / (s * e);
  const auto n2 = h2_numerator(u, a, hu, hv, constants);
  // H1(u) = H2(a - u): derivatives alternate in sign. Its own v is a - v,
  // which rounding may set apart from u.
  const double w = a - v;
  const auto n1 = h2_numerator(v, a, hv, w == u ? hu : hyperbolic(w), constants);
  BasisJet jet{};
  for (int k = 0; k < 4; ++k) {
    const double h2k = scale * n2[k];
    const double h1k = scale * n1[k] * ((k % 2 == 0) ? 1.0 : -1.0);
    jet[k][0] = (1.0 - lambda) * h0[k] + lambda * k0[k];
    jet[k][1] = h1k + lambda * (h0[k] - k0[k]);
    jet[k][2] = h2k + mu * (h3[k] - k3[k]);
    jet[k][3] = (1.0 - mu) * h3[k] + mu * k3[k];
  }
  return jet;
}

std::array<double, 4> hbezier_fourth_bound(double alpha, double lambda, double mu) {
  const double a = alpha;
  const auto [s, c, d, e] = hbezier_constants(a);
  const double sh = std::sinh(a), ch = std::cosh(a);
  // |H0''''|, |H3''''| <= sinh a / S; |K0''''|, |K3''''| <= cosh a / D;
  // |H1''''|, |H2''''| <= sinh a (2 sinh a + a cosh a) / (S E).
  const double bh = sh / s, bk = ch / d, bmid = sh * (2.0 * sh + a * ch) / (s * e);
  return {std::abs(1.0 - lambda) * bh + std::abs(lambda) * bk, bmid + std::abs(lambda) * (bh + bk),
          bmid + std::abs(mu) * (bh + bk), std::abs(1.0 - mu) * bh + std::abs(mu) * bk};
}

HBezierEndConstants hbezier_end_constants(double alpha, double lambda, double mu) {
  const auto [s, c, d, e] = hbezier_constants(alpha);
  const double sh = std::sinh(alpha);
  return {(1.0 - lambda) * c / s + lambda * s / d, (1.0 - mu) * c / s + mu * s / d,
          (1.0 - lambda) * sh / s + lambda * c / d, (1.0 - mu) * sh / s + mu * c / d, sh / e};
}

double hbezier_lambda_min(double alpha) {
  const auto [s, c, d, e] = hbezier_constants(alpha);
  return -c * d / (s * s - c * d);
}

}  // namespace fabmesh
