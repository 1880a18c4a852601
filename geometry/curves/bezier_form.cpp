#include "geometry/curves/bezier_form.h"

#include <fmt/format.h>

#include <array>
#include <cmath>

#include "geometry/core/errors.h"
#include "geometry/curves/basis.h"

namespace fabmesh {
namespace {

template <std::size_t N>
using Poly = std::array<Vec2, N>;  // monomial coefficients of a plane curve, degree N - 1

double binomial(int n, int k) {
  double c = 1.0;
  for (int i = 1; i <= k; ++i) c = c * (n - k + i) / i;
  return c;
}

// Bernstein coefficients of sum_k a_k w^k of degree n = N - 1:
// beta_i = sum_{k <= i} C(i, k) / C(n, k) a_k.
template <class T, std::size_t N>
std::array<T, N> to_bernstein(const std::array<T, N>& a) {
  const int n = static_cast<int>(N) - 1;
  std::array<T, N> beta{};
  for (int i = 0; i <= n; ++i) {
    T sum = a[0] * 0.0;
    for (int k = 0; k <= i; ++k) sum += a[static_cast<std::size_t>(k)] * (binomial(i, k) / binomial(n, k));
    beta[static_cast<std::size_t>(i)] = sum;
  }
  return beta;
}

// docs/math/curves.md 4.1: with s = 2w / (1 + w^2) and c = (1 - w^2) / (1 + w^2),
// s^k and c^k times (1 + w^2)^3 are these sextics in w.
constexpr std::array<std::array<double, 7>, 7> kTrigTimesDenominator = {{
    {1, 0, 3, 0, 3, 0, 1},    // 1            (1 + w^2)^3
    {0, 2, 0, 4, 0, 2, 0},    // s            2w (1 + w^2)^2
    {0, 0, 4, 0, 4, 0, 0},    // s^2          4w^2 (1 + w^2)
    {0, 0, 0, 8, 0, 0, 0},    // s^3          8w^3
    {1, 0, 1, 0, -1, 0, -1},  // c            (1 - w^2) (1 + w^2)^2
    {1, 0, -1, 0, -1, 0, 1},  // c^2          (1 - w^2)^2 (1 + w^2)
    {1, 0, -3, 0, 3, 0, -1},  // c^3          (1 - w^2)^3
}};

BezierPiece tbezier_form(const Segment& segment) {
  const auto& p = segment.control_points();
  const double l = segment.lambda(), m = segment.mu();
  // r = A0 + A1 s + A2 s^2 + A3 s^3 + B1 c + B2 c^2 + B3 c^3 (the basis of
  // docs/math/curves.md 1 expanded in powers of s and c).
  const std::array<Vec2, 7> terms = {
      p[0] + p[3],       (2.0 + l) * (p[1] - p[0]), (1.0 + 2.0 * l) * p[0] - (2.0 + 2.0 * l) * p[1],
      l * (p[1] - p[0]), (2.0 + m) * (p[2] - p[3]), -(2.0 + 2.0 * m) * p[2] + (1.0 + 2.0 * m) * p[3],
      m * (p[2] - p[3]),
  };
  Poly<7> numerator;
  numerator.fill(Vec2::Zero());
  for (std::size_t term = 0; term < terms.size(); ++term) {
    for (std::size_t k = 0; k < 7; ++k) numerator[k] += kTrigTimesDenominator[term][k] * terms[term];
  }
  const Poly<7> numerator_bernstein = to_bernstein(numerator);
  const std::array<double, 7> weights = to_bernstein(kTrigTimesDenominator[0]);
  BezierPiece piece;
  for (std::size_t i = 0; i < 7; ++i) {
    piece.weights.push_back(weights[i]);
    piece.poles.push_back(numerator_bernstein[i] / weights[i]);
  }
  return piece;
}

BezierPiece quasi_bspline_form(const Segment& segment) {
  const auto& p = segment.control_points();
  const auto c = quasi_bspline_coefficients(segment.lambda(), segment.mu());
  Poly<5> monomial;
  monomial.fill(Vec2::Zero());
  for (std::size_t j = 0; j < 4; ++j) {
    for (std::size_t k = 0; k < 5; ++k) monomial[k] += c[j][k] * p[j];
  }
  const Poly<5> bernstein = to_bernstein(monomial);
  return {std::vector<Vec2>(bernstein.begin(), bernstein.end()), {}};
}

}  // namespace

Vec2 evaluate(const BezierPiece& piece, double w) {
  const std::size_t n = piece.poles.size();
  const bool rational = !piece.weights.empty();
  std::vector<Eigen::Vector3d> h(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double weight = rational ? piece.weights[i] : 1.0;
    h[i] = Eigen::Vector3d(piece.poles[i].x() * weight, piece.poles[i].y() * weight, weight);
  }
  for (std::size_t level = 1; level < n; ++level) {
    for (std::size_t i = 0; i + level < n; ++i) h[i] = (1.0 - w) * h[i] + w * h[i + 1];
  }
  return {h[0].x() / h[0].z(), h[0].y() / h[0].z()};
}

std::optional<BezierPiece> exact_bezier(const Segment& segment) {
  switch (segment.kind()) {
    case SegmentKind::Line:
      return BezierPiece{{segment.control_points()[0], segment.control_points()[1]}, {}};
    case SegmentKind::QuasiBSpline:
      return quasi_bspline_form(segment);
    case SegmentKind::TBezier:
      return tbezier_form(segment);
    case SegmentKind::RationalBezier: {
      // Already a rational cubic Bézier curve in s: its own poles and weights.
      const auto& p = segment.control_points();
      const auto& w = segment.rational_weights();
      return BezierPiece{{p.begin(), p.end()}, {w.begin(), w.end()}};
    }
    case SegmentKind::EllipseArc:
    case SegmentKind::HBezier:
      break;
  }
  return std::nullopt;
}

BezierPiece hermite_cubic(const Vec2& a, const Vec2& da, const Vec2& b, const Vec2& db, double h) {
  return {{a, a + da * (h / 3.0), b - db * (h / 3.0), b}, {}};
}

double bezier_parameter(const Segment& segment, double s) {
  return segment.kind() == SegmentKind::TBezier ? std::tan(M_PI * s / 4.0) : s;
}

BezierApproximation hermite_approximation(const Segment& segment, double tolerance, int max_pieces) {
  if (!(tolerance > 0.0)) {
    throw RangeError("tolerance", tolerance,
                     fmt::format("the approximation's tolerance must be > 0, not {}", tolerance));
  }
  const double m4 = segment.fourth_derivative_bound();
  const auto bound_for = [m4](int n) { return std::sqrt(2.0) * m4 / (384.0 * std::pow(double(n), 4)); };
  int n = std::max(1, static_cast<int>(std::ceil(std::pow(std::sqrt(2.0) * m4 / (384.0 * tolerance), 0.25))));
  while (bound_for(n) > tolerance) ++n;  // the root rounded down
  if (n > max_pieces) {
    throw GeometryError(to_string(segment.kind()),
                        fmt::format("approximating a {} segment within {:.3g} needs {} cubic pieces, more "
                                    "than {}: its fourth derivative is bounded only by {:.6g}",
                                    to_string(segment.kind()), tolerance, n, max_pieces, m4));
  }
  BezierApproximation out;
  out.bound = bound_for(n);
  const double h = 1.0 / n;
  CurveJet start = segment.jet(0.0);
  for (int i = 0; i < n; ++i) {
    const CurveJet end = segment.jet(i + 1 == n ? 1.0 : (i + 1) * h);
    out.pieces.push_back(hermite_cubic(start[0], start[1], end[0], end[1], h));
    start = end;
  }
  return out;
}

}  // namespace fabmesh
