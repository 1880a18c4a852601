#include "io/dxf/dxf_spline.h"

#include <algorithm>

namespace fabmesh {
namespace {

// The point at u of the B-spline of degree p on its span k (knots[k] <= u <=
// knots[k + 1]), by de Boor's algorithm on the span's p + 1 control points.
Vec2 de_boor(const std::vector<double>& knots, const std::vector<Vec2>& points, int p, std::size_t k,
             double u) {
  const std::size_t q = static_cast<std::size_t>(p);
  std::array<Vec2, 4> d;
  for (std::size_t j = 0; j <= q; ++j) d[j] = points[k - q + j];
  for (std::size_t r = 1; r <= q; ++r) {
    for (std::size_t j = q; j >= r; --j) {
      const std::size_t i = k - q + j;
      const double den = knots[i + q + 1 - r] - knots[i];
      const double a = den > 0.0 ? (u - knots[i]) / den : 0.0;
      d[j] = (1.0 - a) * d[j - 1] + a * d[j];
    }
  }
  return d[q];
}

// The cubic Bézier control points of span k of a non-rational B-spline of
// degree 1..3: the span is a polynomial of degree <= 3, so its cubic Bézier
// is fixed by its points at t = 0, 1/3, 2/3, 1 (de Boor on the span's own
// control points: the degree raised exactly).
std::array<Vec2, 4> span_bezier(const std::vector<double>& knots, const std::vector<Vec2>& points, int p,
                                std::size_t k) {
  const double a = knots[k], b = knots[k + 1];
  const Vec2 p0 = de_boor(knots, points, p, k, a), p3 = de_boor(knots, points, p, k, b);
  const Vec2 s1 = de_boor(knots, points, p, k, a + (b - a) / 3.0);
  const Vec2 s2 = de_boor(knots, points, p, k, a + 2.0 * (b - a) / 3.0);
  // B(1/3) = (8 P0 + 12 P1 + 6 P2 + P3) / 27 and B(2/3) = (P0 + 6 P1 + 12 P2 + 8 P3) / 27.
  const Vec2 u = 27.0 * s1 - 8.0 * p0 - p3, v = 27.0 * s2 - p0 - 8.0 * p3;
  return {p0, (2.0 * u - v) / 18.0, (2.0 * v - u) / 18.0, p3};
}

// The blossom f(u_1, ..., u_p) of span k of a B-spline of degree p: de Boor's
// algorithm with u_r at level r. With every u_r in the span each step is a
// convex combination, so the weights of homogeneous points stay positive
// and keep their relative precision however far apart they are.
Eigen::Vector3d blossom(const std::vector<double>& knots, const std::vector<Eigen::Vector3d>& points, int p,
                        std::size_t k, const std::array<double, 3>& u) {
  const std::size_t q = static_cast<std::size_t>(p);
  std::array<Eigen::Vector3d, 4> d;
  for (std::size_t j = 0; j <= q; ++j) d[j] = points[k - q + j];
  for (std::size_t r = 1; r <= q; ++r) {
    for (std::size_t j = q; j >= r; --j) {
      const std::size_t i = k - q + j;
      const double den = knots[i + q + 1 - r] - knots[i];
      const double a = den > 0.0 ? (u[r - 1] - knots[i]) / den : 0.0;
      d[j] = (1.0 - a) * d[j - 1] + a * d[j];
    }
  }
  return d[q];
}

// The cubic Bézier control points (homogeneous) of span k = [a, b] of a NURBS
// of degree 1..3: F(a, a, a), F(a, a, b), F(a, b, b), F(b, b, b) of the cubic
// blossom F(x, y, z), the mean of f over the p-element subsets of (x, y, z)
// (the degree raised exactly), each a convex combination of control points.
std::array<Eigen::Vector3d, 4> rational_span_bezier(const std::vector<double>& knots,
                                                    const std::vector<Eigen::Vector3d>& points, int p,
                                                    std::size_t k) {
  const double a = knots[k], b = knots[k + 1];
  std::array<Eigen::Vector3d, 4> out;
  for (std::size_t i = 0; i < 4; ++i) {
    const std::array<double, 3> args{i > 2 ? b : a, i > 1 ? b : a, i > 0 ? b : a};  // 3 - i a's, i b's
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    int count = 0;
    for (unsigned mask = 0; mask < 8; ++mask) {
      std::array<double, 3> u{};
      int size = 0;
      for (std::size_t m = 0; m < 3; ++m) {
        if ((mask >> m) & 1u) u[static_cast<std::size_t>(size++)] = args[m];
      }
      if (size != p) continue;
      sum += blossom(knots, points, p, k, u);
      ++count;
    }
    out[i] = sum / count;
  }
  return out;
}

}  // namespace

// A rational span's poles are the homogeneous Bézier points (w x, w y, w)
// divided by their w, its weights the w.
std::vector<BezierSpan> bezier_spans(const std::vector<double>& knots, const std::vector<Vec2>& points,
                                     const std::vector<double>& weights, int degree) {
  const int p = degree;
  std::vector<BezierSpan> out;
  const std::size_t n = points.size(), q = static_cast<std::size_t>(p);
  std::vector<Eigen::Vector3d> homogeneous;
  for (std::size_t k = q; k < n; ++k) {
    if (!(knots[k + 1] > knots[k])) continue;
    BezierSpan span;
    const auto first = weights.begin() + static_cast<std::ptrdiff_t>(k - q);
    const auto last = weights.begin() + static_cast<std::ptrdiff_t>(k + 1);
    if (std::all_of(first, last, [&](double w) { return w == *first; })) {
      span.points = span_bezier(knots, points, p, k);
      out.push_back(span);
      continue;
    }
    if (homogeneous.empty()) {
      for (std::size_t i = 0; i < n; ++i)
        homogeneous.emplace_back(weights[i] * points[i].x(), weights[i] * points[i].y(), weights[i]);
    }
    const std::array<Eigen::Vector3d, 4> h = rational_span_bezier(knots, homogeneous, p, k);
    span.rational = true;
    for (std::size_t i = 0; i < 4; ++i) {
      span.weights[i] = h[i].z();
      span.points[i] = h[i].head<2>() / h[i].z();
    }
    out.push_back(span);
  }
  return out;
}

std::array<Vec2, 4> bspline_span_of(const std::array<Vec2, 4>& z) {
  return {6.0 * z[0] - 7.0 * z[1] + 2.0 * z[2], 2.0 * z[1] - z[2], -z[1] + 2.0 * z[2],
          2.0 * z[1] - 7.0 * z[2] + 6.0 * z[3]};
}

}  // namespace fabmesh
