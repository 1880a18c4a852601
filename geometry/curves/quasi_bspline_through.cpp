// The control points of a quasi-cubic B-spline through given points
// (docs/math/curves.md 2.3). At joint i the curve is
//   r_i(0) = ((4 - l) p(i-1) + 2 (8 + l) p(i) + (4 - l) p(i+1)) / 24,  l = lambda_i,
// so q0..qn fix p0 = q0, pn = qn and a tridiagonal system for p1..p(n-1).

#include "geometry/curves/quasi_bspline_through.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <boost/multiprecision/cpp_int.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "geometry/core/error_checks.h"
#include "geometry/core/errors.h"

namespace fabmesh {
namespace {

namespace mp = boost::multiprecision;
using Integer = mp::cpp_int;
using Rational = mp::cpp_rational;

// A finite double as m * 2^e with m a whole number (exactly).
struct Dyadic {
  std::int64_t mantissa = 0;
  int exponent = 0;
};

Dyadic dyadic(double x) {
  if (x == 0.0) return {};
  int e = 0;
  const double m = std::frexp(x, &e);
  return {static_cast<std::int64_t>(std::ldexp(m, 53)), e - 53};
}

Rational exact(double x) {
  const Dyadic d = dyadic(x);
  Integer m = d.mantissa;
  if (d.exponent >= 0) return Rational(m << d.exponent);
  return Rational(m, Integer(1) << -d.exponent);
}

// The smallest double >= |r|.
double magnitude_up(const Rational& r) {
  const Rational a = mp::abs(r);
  double d = a.convert_to<double>();
  while (exact(d) < a) d = std::nextafter(d, std::numeric_limits<double>::infinity());
  return d;
}

// Row i (1..n-1) of the system: sub[i] p(i-1) + diag[i] p(i) + sub[i] p(i+1) = 24 q(i).
struct Rows {
  std::vector<double> off, diag;  // index 0..n, interior entries used
};

Rows rows_of(const std::vector<double>& lam) {
  Rows r;
  r.off.resize(lam.size());
  r.diag.resize(lam.size());
  for (std::size_t i = 0; i < lam.size(); ++i) {
    r.off[i] = 4.0 - lam[i];           // exact: lam in [-8, 1] with 53-bit mantissa
    r.diag[i] = 2.0 * (8.0 + lam[i]);  // exact likewise
  }
  return r;
}

// The (n-1) x (n-1) system's determinant is the continuant
//   D_1 = d_1,  D_k = d_k D_(k-1) - a_k a_(k-1) D_(k-2)
// of its rows, every lambda scaled to a whole number by one power of two.
// Whether it is 0 is decided exactly, in three steps that each prove what
// they say: with every lambda >= -2 the matrix is irreducibly diagonally
// dominant, so not singular; else a determinant that is not 0 modulo one
// of three primes is not 0; else (a singular system, or a rare multiple
// of all three) the continuant in arbitrary-precision integers.
constexpr std::uint64_t kPrimes[] = {2147483647u, 2147483629u, 2147483587u};

std::uint64_t power_of_two(long e, std::uint64_t p) {
  std::uint64_t result = 1 % p, base = 2 % p;
  for (; e > 0; e >>= 1) {
    if ((e & 1) != 0) result = result * base % p;
    base = base * base % p;
  }
  return result;
}

// A scaled lambda, m * 2^(exponent + shift), modulo p.
std::uint64_t modulo(const Dyadic& d, int shift, std::uint64_t p) {
  const auto sp = static_cast<std::int64_t>(p);
  const std::int64_t m = ((d.mantissa % sp) + sp) % sp;
  return static_cast<std::uint64_t>(m) * power_of_two(d.exponent + shift, p) % p;
}

// Work of the exact continuant: about n^2 / 2 limb products of numbers
// growing by the scaled rows' bits per step. Above this, refused.
constexpr double kMaxExactWork = 1e9;

bool singular(const std::vector<double>& lam, const std::string& key) {
  const std::size_t n = lam.size() - 1;
  if (std::all_of(lam.begin() + 1, lam.end() - 1, [](double l) { return l >= -2.0; })) return false;
  int shift = 0;
  for (std::size_t i = 1; i < n; ++i) {
    if (lam[i] != 0.0) shift = std::max(shift, -dyadic(lam[i]).exponent);
  }
  for (const std::uint64_t p : kPrimes) {
    const std::uint64_t one = power_of_two(shift, p);
    std::vector<std::uint64_t> a(n), b(n);
    for (std::size_t i = 1; i < n; ++i) {
      const std::uint64_t l = lam[i] == 0.0 ? 0 : modulo(dyadic(lam[i]), shift, p);
      a[i] = (4 * one + p - l) % p;
      b[i] = (16 * one + 2 * l) % p;
    }
    std::uint64_t before = 1, det = b[1];
    for (std::size_t i = 2; i < n; ++i) {
      const std::uint64_t next = (b[i] * det % p + p - a[i] * a[i - 1] % p * before % p) % p;
      before = det;
      det = next;
    }
    if (det != 0) return false;
  }
  const double steps = static_cast<double>(n);
  if (0.5 * steps * steps * (static_cast<double>(shift) + 8.0) / 64.0 > kMaxExactWork) {
    throw GeometryError(key,
                        fmt::format("deciding exactly whether these {} through points and lambdas make a "
                                    "singular system would take too long (lambdas with up to {} binary "
                                    "digits); lambdas of -2 or more always make a solvable one",
                                    n + 1, shift));
  }
  const Integer one = Integer(1) << shift;
  auto scaled = [&](double x) {
    const Dyadic d = dyadic(x);
    return Integer(d.mantissa) << (d.exponent + shift);  // exponent + shift >= 0
  };
  std::vector<Integer> a(n), b(n);
  for (std::size_t i = 1; i < n; ++i) {
    const Integer l = lam[i] == 0.0 ? Integer(0) : scaled(lam[i]);
    a[i] = 4 * one - l;
    b[i] = 16 * one + 2 * l;
  }
  Integer before = 1, det = b[1];
  for (std::size_t i = 2; i < n; ++i) {
    Integer next = b[i] * det - a[i] * a[i - 1] * before;
    before = std::move(det);
    det = std::move(next);
  }
  return det == 0;
}

// Solves rows 1..n-1 for p(1)..p(n-1) given rhs (24 q(i) minus the known
// ends' terms) by Gaussian elimination with partial pivoting, which keeps
// the upper band at two entries. False when a pivot is 0 in floating point.
bool solve_rows(const Rows& rows, std::vector<Vec2> rhs, std::vector<Vec2>& x) {
  const std::size_t m = rhs.size();  // unknowns p(1)..p(m)
  struct Upper {
    double d0 = 0.0, d1 = 0.0, d2 = 0.0;  // at columns k, k + 1, k + 2
    Vec2 rhs = Vec2::Zero();
  };
  std::vector<Upper> u(m);
  // Row k (0-based) is the equation of joint k + 1.
  auto original = [&](std::size_t k) {
    const std::size_t i = k + 1;
    return Upper{rows.diag[i], k + 1 < m ? rows.off[i] : 0.0, 0.0, rhs[k]};
  };
  Upper active = original(0);
  for (std::size_t k = 0; k < m; ++k) {
    if (k + 1 == m) {
      u[k] = active;
      break;
    }
    const Upper next = original(k + 1);
    const double sub = rows.off[k + 2];  // row k + 1's entry at column k
    Upper pivot = active, other{sub, next.d0, next.d1, next.rhs};
    if (std::abs(sub) > std::abs(active.d0)) std::swap(pivot, other);
    if (pivot.d0 == 0.0) return false;
    u[k] = pivot;
    const double f = other.d0 / pivot.d0;
    active = Upper{other.d1 - f * pivot.d1, other.d2 - f * pivot.d2, 0.0, other.rhs - f * pivot.rhs};
  }
  x.assign(m, Vec2::Zero());
  for (std::size_t k = m; k-- > 0;) {
    if (u[k].d0 == 0.0) return false;
    Vec2 s = u[k].rhs;
    if (k + 1 < m) s -= u[k].d1 * x[k + 1];
    if (k + 2 < m) s -= u[k].d2 * x[k + 2];
    x[k] = s / u[k].d0;
  }
  return std::all_of(x.begin(), x.end(),
                     [](const Vec2& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); });
}

// 24 q(i) - (row i applied to p), exactly, for i = 1..n-1 (x and y).
std::vector<std::array<Rational, 2>> exact_residuals(const Rows& rows, const std::vector<Vec2>& q,
                                                     const std::vector<Vec2>& p) {
  const std::size_t n = q.size() - 1;
  std::vector<std::array<Rational, 2>> out(n - 1);
  for (std::size_t i = 1; i < n; ++i) {
    for (int c = 0; c < 2; ++c) {
      out[i - 1][static_cast<std::size_t>(c)] =
          24 * exact(q[i][c]) - exact(rows.off[i]) * (exact(p[i - 1][c]) + exact(p[i + 1][c])) -
          exact(rows.diag[i]) * exact(p[i][c]);
    }
  }
  return out;
}

// The largest |residual| / 24 as a distance, rounded up; its joint.
std::pair<double, std::size_t> worst(const std::vector<std::array<Rational, 2>>& residuals) {
  double most = 0.0;
  std::size_t at = 0;
  for (std::size_t i = 0; i < residuals.size(); ++i) {
    const double dx = magnitude_up(residuals[i][0]), dy = magnitude_up(residuals[i][1]);
    // Three roundings of at most 2^-53 each: a relative margin of 1e-15 covers them.
    const double d =
        std::sqrt(dx * dx + dy * dy) / 24.0 * (1.0 + 1e-15) + std::numeric_limits<double>::denorm_min();
    if (d > most) {
      most = d;
      at = i + 1;
    }
  }
  if (residuals.empty()) return {0.0, 0};
  return {most, at};
}

}  // namespace

QuasiBSplineThrough quasi_bspline_through(const std::vector<Vec2>& through,
                                          const std::vector<double>& lambdas, const std::string& key) {
  if (through.size() < 3) {
    throw GeometryError(key, fmt::format("a quasi-cubic B-spline through points needs at least 3 points "
                                         "q0..qn (n >= 2), got {}",
                                         through.size()));
  }
  const std::size_t n = through.size() - 1;
  if (!lambdas.empty() && lambdas.size() != n - 1) {
    throw GeometryError(key, fmt::format("lambdas has {} values; {} points need n - 1 = {}", lambdas.size(),
                                         through.size(), n - 1));
  }
  std::vector<double> lam(n + 1, 0.0);
  lam.front() = lam.back() = 4.0;
  for (std::size_t i = 1; i < n && !lambdas.empty(); ++i) {
    lam[i] = lambdas[i - 1];
    try {
      require_in_range(fmt::format("lambda_{}", i), lam[i], -8.0, 1.0);
    } catch (const RangeError& e) {
      throw RangeError(e.field(), e.value(), e.what(), ErrorLocation{key});
    }
  }
  for (const Vec2& q : through) {
    if (!std::isfinite(q.x()) || !std::isfinite(q.y()))
      throw GeometryError(key, "a through point is not finite");
  }
  if (singular(lam, key)) {
    throw GeometryError(
        key, fmt::format("no quasi-cubic B-spline with these lambdas passes through these {} points: the "
                         "system for its control points is singular (its determinant is exactly 0; a lambda "
                         "of -2 or more at every joint always gives a solution)",
                         through.size()));
  }
  const Rows rows = rows_of(lam);
  std::vector<Vec2> rhs(n - 1);
  for (std::size_t i = 1; i < n; ++i) rhs[i - 1] = 24.0 * through[i];
  rhs.front() -= rows.off[1] * through.front();
  rhs.back() -= rows.off[n - 1] * through.back();

  QuasiBSplineThrough out;
  out.points.assign(through.begin(), through.end());  // p0 = q0, pn = qn; the rest solved
  std::vector<Vec2> x;
  const auto unsolvable = [&](double missed, std::size_t joint) {
    return GeometryError(
        key, fmt::format("the system for the control points through these points is too close to singular "
                         "for these lambdas: the solved curve misses point {} by {:.3g}, more than 1e-9 of "
                         "the points' extent (raise the lambdas near it toward 0)",
                         joint, missed));
  };
  if (!solve_rows(rows, rhs, x)) throw unsolvable(std::numeric_limits<double>::infinity(), 1);
  std::copy(x.begin(), x.end(), out.points.begin() + 1);
  auto residuals = exact_residuals(rows, through, out.points);
  auto [deviation, joint] = worst(residuals);
  // Refinement: solve for the correction with the exact residual, keep it if it helps.
  for (int round = 0; round < 3 && deviation > 0.0; ++round) {
    std::vector<Vec2> r(n - 1), dx;
    for (std::size_t i = 0; i + 1 < n; ++i)
      r[i] = Vec2(residuals[i][0].convert_to<double>(), residuals[i][1].convert_to<double>());
    if (!solve_rows(rows, r, dx)) break;
    std::vector<Vec2> refined = out.points;
    for (std::size_t i = 0; i + 1 < n; ++i) refined[i + 1] += dx[i];
    auto refined_residuals = exact_residuals(rows, through, refined);
    const auto [d, j] = worst(refined_residuals);
    if (d >= deviation) break;
    out.points = std::move(refined);
    residuals = std::move(refined_residuals);
    deviation = d;
    joint = j;
  }
  Vec2 lo = through.front(), hi = through.front();
  for (const Vec2& q : through) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
  const double extent = (hi - lo).norm();
  if (deviation > 1e-9 * extent) throw unsolvable(deviation, joint);
  out.deviation = deviation;
  return out;
}

}  // namespace fabmesh
