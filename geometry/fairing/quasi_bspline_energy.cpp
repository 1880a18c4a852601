#include "geometry/fairing/quasi_bspline_energy.h"

#include <fmt/format.h>

#include <algorithm>

#include "geometry/core/errors.h"
#include "geometry/curves/basis.h"
#include "geometry/fairing/box_qp.h"
#include "geometry/fairing/gauss_legendre.h"

namespace fabmesh {
namespace {

using Poly = std::array<double, 5>;  // t^0..t^4
using VecPoly = std::array<Vec2, 5>;

Poly derivative(const Poly& p, int order) {
  Poly d = p;
  for (int o = 0; o < order; ++o) {
    Poly next{};
    for (int i = 1; i < 5; ++i) next[i - 1] = i * d[i];
    d = next;
  }
  return d;
}

// integral_0^1 A(t) . B(t) dt for vector polynomials, exactly.
double inner(const VecPoly& a, const VecPoly& b) {
  double sum = 0.0;
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 5; ++j) sum += a[i].dot(b[j]) / (i + j + 1);
  }
  return sum;
}

// r^(k)(t) of span i split as V + l L + m M (the basis is affine in l and m).
VecPoly zero_poly() {
  VecPoly p;
  p.fill(Vec2::Zero());
  return p;
}

struct SpanTerms {
  VecPoly v = zero_poly(), l = zero_poly(), m = zero_poly();
};

SpanTerms span_terms(const std::array<Vec2, 4>& p, int order) {
  const auto c00 = quasi_bspline_coefficients(0.0, 0.0);
  const auto c10 = quasi_bspline_coefficients(1.0, 0.0);
  const auto c01 = quasi_bspline_coefficients(0.0, 1.0);
  SpanTerms s;
  for (int j = 0; j < 4; ++j) {
    Poly dl{}, dm{};
    for (int k = 0; k < 5; ++k) {
      dl[k] = c10[j][k] - c00[j][k];
      dm[k] = c01[j][k] - c00[j][k];
    }
    const Poly v = derivative(c00[j], order), l = derivative(dl, order), m = derivative(dm, order);
    for (int k = 0; k < 5; ++k) {
      s.v[k] += v[k] * p[j];
      s.l[k] += l[k] * p[j];
      s.m[k] += m[k] * p[j];
    }
  }
  return s;
}

std::vector<std::array<Vec2, 4>> span_points(const std::vector<Vec2>& p) {
  const long n = static_cast<long>(p.size()) - 1;
  auto at = [&](long i) { return p[static_cast<std::size_t>(std::clamp<long>(i, 0, n))]; };
  std::vector<std::array<Vec2, 4>> spans;
  for (long i = 0; i < n; ++i) spans.push_back({at(i - 1), at(i), at(i + 1), at(i + 2)});
  return spans;
}

void check_input(const std::vector<Vec2>& points, int order) {
  if (order != 2 && order != 3) {
    throw RangeError("order", order,
                     fmt::format("energy order {} must be 2 (strain) or 3 (curvature variation)", order));
  }
  if (points.size() < 3) {
    throw GeometryError("points",
                        fmt::format("a quasi-cubic B-spline needs at least 3 points, got {}", points.size()));
  }
}

}  // namespace

QuadraticEnergy quasi_bspline_energy(const std::vector<Vec2>& points, int order) {
  check_input(points, order);
  const auto spans = span_points(points);
  const auto n = static_cast<Eigen::Index>(spans.size());
  const Eigen::Index vars = n - 1;  // lambda_1 .. lambda_{n-1}; lambda_0 = lambda_n = 4
  QuadraticEnergy e;
  e.q = Eigen::MatrixXd::Zero(vars, vars);
  e.b = Eigen::VectorXd::Zero(vars);
  for (Eigen::Index i = 0; i < n; ++i) {
    const SpanTerms s = span_terms(spans[i], order);
    // Span i uses l = lambda_i (variable i-1, or 4 at i = 0) and m = lambda_{i+1} (variable i, or 4 at i =
    // n-1).
    const Eigen::Index li = i - 1, mi = i;
    const bool l_var = i > 0, m_var = i < n - 1;
    const double vv = inner(s.v, s.v), ll = inner(s.l, s.l), mm = inner(s.m, s.m);
    const double vl = inner(s.v, s.l), vm = inner(s.v, s.m), lm = inner(s.l, s.m);
    // |V + l L + m M|^2 = vv + l^2 ll + m^2 mm + 2 l vl + 2 m vm + 2 l m lm
    double constant = vv;
    double lin_l = vl, lin_m = vm;  // coefficients of 2 l and 2 m
    if (!l_var) constant += 16.0 * ll + 8.0 * vl, lin_m += 4.0 * lm;
    if (!m_var) constant += 16.0 * mm + 8.0 * vm, lin_l += 4.0 * lm;
    if (!l_var && !m_var) constant += 2.0 * 16.0 * lm;
    e.c += constant;
    if (l_var) e.q(li, li) += ll, e.b[li] += lin_l;
    if (m_var) e.q(mi, mi) += mm, e.b[mi] += lin_m;
    if (l_var && m_var) e.q(li, mi) += lm, e.q(mi, li) += lm;
  }
  return e;
}

double quasi_bspline_energy_by_quadrature(const std::vector<Vec2>& points, const std::vector<double>& lambdas,
                                          int order) {
  check_input(points, order);
  const auto spans = span_points(points);
  std::vector<double> lam{4.0};
  lam.insert(lam.end(), lambdas.begin(), lambdas.end());
  lam.push_back(4.0);
  const QuadratureRule rule = gauss_legendre(12);
  double sum = 0.0;
  for (std::size_t i = 0; i < spans.size(); ++i) {
    for (std::size_t q = 0; q < rule.nodes.size(); ++q) {
      const BasisJet w = quasi_bspline_basis(rule.nodes[q], lam[i], lam[i + 1]);
      Vec2 d = Vec2::Zero();
      for (int j = 0; j < 4; ++j) d += w[order][j] * spans[i][j];
      sum += rule.weights[q] * d.squaredNorm();
    }
  }
  return sum;
}

FairestLambdas quasi_bspline_fairest(const std::vector<Vec2>& points, int order) {
  const QuadraticEnergy e = quasi_bspline_energy(points, order);
  const Eigen::Index vars = e.b.size();
  // E = x'Qx + 2b'x + c = 1/2 x'(2Q)x + (2b)'x + c
  const BoxQpResult r = solve_box_qp(2.0 * e.q, 2.0 * e.b, Eigen::VectorXd::Constant(vars, -8.0),
                                     Eigen::VectorXd::Constant(vars, 1.0));
  FairestLambdas out;
  out.lambdas.assign(r.x.data(), r.x.data() + r.x.size());
  out.energy = e(r.x);
  return out;
}

}  // namespace fabmesh
