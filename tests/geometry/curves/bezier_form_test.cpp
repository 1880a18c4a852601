// The Bézier forms STEP files get: T-Bézier segments exactly as rational
// Bézier curves of degree 6, quasi-B-spline spans as quartic Béziers, and
// H-Bézier segments as cubic Hermite pieces within their proven bound.

#include "geometry/curves/bezier_form.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "geometry/core/errors.h"
#include "geometry/curves/segment.h"

using namespace fabmesh;

namespace {

constexpr int kSamples = 10000;

// The largest distance between the segment at s and its form at w(s), over
// kSamples + 1 parameters, relative to the control polygon's size.
double relative_gap(const Segment& segment, const BezierPiece& form) {
  double size = 0.0, gap = 0.0;
  for (const Vec2& p : segment.control_points()) size = std::max(size, p.cwiseAbs().maxCoeff());
  for (int i = 0; i <= kSamples; ++i) {
    const double s = static_cast<double>(i) / kSamples;
    gap = std::max(gap, (segment.point(s) - evaluate(form, bezier_parameter(segment, s))).norm());
  }
  return gap / size;
}

}  // namespace

TEST_CASE("bezier form: a T-Bezier segment is exactly a rational sextic in w = tan(pi t / 4)",
          "[curves][bezier_form]") {
  const std::array<Vec2, 4> points = {Vec2(0.0, 0.0), Vec2(120.0, 310.0), Vec2(540.0, 280.0),
                                      Vec2(600.0, -40.0)};
  for (const double lambda : {-2.0, -1.0, 0.0, 0.5, 1.0}) {
    for (const double mu : {-2.0, -0.3, 0.0, 1.0}) {
      const Segment segment = Segment::tbezier(points, lambda, mu);
      const auto form = exact_bezier(segment);
      REQUIRE(form.has_value());
      CHECK(form->poles.size() == 7);
      REQUIRE(form->weights.size() == 7);
      // (1 + w^2)^3 in the Bernstein basis of degree 6: all positive.
      const std::vector<double> weights = {1.0, 1.0, 1.2, 1.6, 2.4, 4.0, 8.0};
      for (std::size_t i = 0; i < 7; ++i) CHECK(form->weights[i] == Approx(weights[i]).margin(1e-15));
      CHECK(form->poles.front() == points[0]);
      CHECK((form->poles.back() - points[3]).norm() <= 1e-12 * 600.0);
      CHECK(relative_gap(segment, *form) <= 1e-12);
    }
  }
}

TEST_CASE("bezier form: a quasi-B-spline span is exactly a quartic Bezier, a line a linear one",
          "[curves][bezier_form]") {
  const std::array<Vec2, 4> points = {Vec2(1.5, 6.0), Vec2(1.0, 5.0), Vec2(2.0, 4.0), Vec2(3.0, 3.0)};
  for (const double l : {-8.0, -1.0, 0.0, 1.0, 4.0}) {
    for (const double m : {-8.0, 0.5, 1.0}) {
      const Segment span = Segment::quasi_bspline_span(points, l, m);
      const auto form = exact_bezier(span);
      REQUIRE(form.has_value());
      CHECK(form->poles.size() == 5);
      CHECK(form->weights.empty());
      CHECK(relative_gap(span, *form) <= 1e-12);
    }
  }
  const Segment line = Segment::line(Vec2(1.0, 2.0), Vec2(-3.0, 7.5));
  const auto form = exact_bezier(line);
  REQUIRE(form.has_value());
  CHECK(form->poles.size() == 2);
  CHECK(relative_gap(line, *form) == 0.0);
  // Conics are written as conics; H-Bézier segments have no exact form.
  CHECK_FALSE(exact_bezier(Segment::ellipse_arc({})).has_value());
  CHECK_FALSE(exact_bezier(Segment::hbezier(points, 2.0, 0.0, 0.0)).has_value());
}

TEST_CASE("bezier form: a rational cubic Bezier segment is itself, poles and weights, error 0",
          "[curves][bezier_form][rational]") {
  const std::array<Vec2, 4> points = {Vec2(-320.0, 45.0), Vec2(120.0, 310.0), Vec2(540.0, -280.0),
                                      Vec2(600.0, 40.0)};
  for (const std::array<double, 4>& weights :
       {std::array<double, 4>{1.0, std::sqrt(0.5), std::sqrt(0.5), 1.0},
        std::array<double, 4>{0.2, 3.0, 0.7, 1.5}, std::array<double, 4>{5.0, 0.1, 0.1, 5.0}}) {
    const Segment segment = Segment::rational_bezier(points, weights);
    const auto form = exact_bezier(segment);
    REQUIRE(form.has_value());
    REQUIRE(form->poles.size() == 4);
    REQUIRE(form->weights.size() == 4);
    for (std::size_t i = 0; i < 4; ++i) {
      CHECK(form->poles[i] == points[i]);
      CHECK(form->weights[i] == weights[i]);
    }
    CHECK(bezier_parameter(segment, 0.37) == 0.37);
    CHECK(relative_gap(segment, *form) <= 1e-12);
  }
}

TEST_CASE("bezier form: H-Bezier segments are within the proven bound of their Hermite pieces",
          "[curves][bezier_form]") {
  const std::array<Vec2, 4> points = {Vec2(0.0, 0.0), Vec2(2.0, 6.0), Vec2(9.0, 5.0), Vec2(12.0, -1.0)};
  for (const double alpha : {0.5, 2.0, 6.0}) {
    for (const double tolerance : {1e-2, 1e-4, 1e-6}) {
      const Segment segment = Segment::hbezier(points, alpha, 0.3, -0.2);
      const BezierApproximation a = hermite_approximation(segment, tolerance);
      INFO("alpha " << alpha << ", tolerance " << tolerance << ", pieces " << a.pieces.size());
      CHECK(a.bound <= tolerance);
      CHECK(a.bound > 0.0);
      // Measured at 10000 parameters: never beyond the bound.
      const double h = 1.0 / static_cast<double>(a.pieces.size());
      double worst = 0.0;
      for (int i = 0; i <= kSamples; ++i) {
        const double s = static_cast<double>(i) / kSamples;
        const std::size_t k = std::min(a.pieces.size() - 1, static_cast<std::size_t>(s / h));
        const double local = (s - static_cast<double>(k) * h) / h;
        worst = std::max(worst, (segment.point(s) - evaluate(a.pieces[k], local)).norm());
      }
      CHECK(worst <= a.bound);
      // The pieces join where the segment is: C0 at least, and tangent.
      for (std::size_t k = 1; k < a.pieces.size(); ++k) {
        CHECK(a.pieces[k - 1].poles[3] == a.pieces[k].poles[0]);
        const Vec2 in = a.pieces[k - 1].poles[3] - a.pieces[k - 1].poles[2];
        const Vec2 out = a.pieces[k].poles[1] - a.pieces[k].poles[0];
        CHECK((in - out).norm() <= 1e-12 * (in.norm() + 1.0));
      }
    }
  }
  CHECK_THROWS_AS(hermite_approximation(Segment::hbezier(points, 2.0, 0.0, 0.0), 0.0), RangeError);
}
