#include "geometry/sampling/sample_curve.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "geometry/core/errors.h"
#include "geometry/curves/curve_spec.h"

using namespace fabmesh;

namespace {

double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

// Largest distance from densely evaluated curve points to the polyline (each
// segment's dense points against the chords that sample that segment).
double dense_deviation(const Segment& seg, const SampleOptions& opt) {
  const auto params = sample_segment_parameters(seg, opt);
  double worst = 0.0;
  for (std::size_t k = 0; k + 1 < params.size(); ++k) {
    const Vec2 a = seg.point(params[k]), b = seg.point(params[k + 1]);
    for (int i = 1; i < 50; ++i) {
      const double s = params[k] + (params[k + 1] - params[k]) * i / 50.0;
      worst = std::max(worst, distance_to_segment(seg.point(s), a, b));
    }
  }
  return worst;
}

std::vector<Segment> test_segments() {
  const std::array<Vec2, 4> p{Vec2(0, 0), Vec2(10, 25), Vec2(30, -5), Vec2(40, 10)};
  EllipseArcParams e;
  e.center = Vec2(5, 5);
  e.a = 50;
  e.b = 8;
  e.rotation_deg = 20;
  e.from_deg = 10;
  e.to_deg = 350;
  return {Segment::tbezier(p, -2, 1),
          Segment::tbezier(p, 1, -1.5),
          Segment::hbezier(p, 0.001, 0.5, -2),
          Segment::hbezier(p, 8.0, -3, 1),
          Segment::quasi_bspline_span(p, 4, -8),
          Segment::ellipse_arc(e)};
}

}  // namespace

TEST_CASE("sampled polylines stay within tolerance of the exact curve", "[sampling]") {
  for (double tol : {0.5, 0.01, 1e-4}) {
    SampleOptions opt;
    opt.tolerance = tol;
    for (const Segment& seg : test_segments()) {
      double achieved = 0.0;
      sample_segment_parameters(seg, opt, &achieved);
      CHECK(achieved <= tol);
      CHECK(dense_deviation(seg, opt) <= tol);
    }
  }
}

TEST_CASE("sampling is adaptive: a tighter tolerance gives about sqrt(10) times more points", "[sampling]") {
  const Segment seg = test_segments()[0];
  SampleOptions coarse, fine;
  coarse.tolerance = 1e-2;
  fine.tolerance = 1e-4;
  const double n1 = static_cast<double>(sample_segment_parameters(seg, coarse).size());
  const double n2 = static_cast<double>(sample_segment_parameters(seg, fine).size());
  // Chordal error ~ h^2: 100x tighter needs ~10x the points; a bound-driven method stays near that.
  CHECK(n2 / n1 > 5.0);
  CHECK(n2 / n1 < 20.0);
}

TEST_CASE("sample_curve joins segments without duplicate points and reports the bound", "[sampling]") {
  CurveSpec spec;
  spec.family = CurveFamily::QuasiBSpline;
  spec.bspline_points = {{1.5, 6}, {1, 5}, {2, 4}, {3, 3}, {1.5, 2}};
  const CompositeCurve c = construct_curve(spec);
  SampleOptions opt;
  opt.tolerance = 1e-3;
  const Polyline2 line = sample_curve(c, opt);
  CHECK_FALSE(line.closed);
  CHECK(line.max_deviation <= 1e-3);
  CHECK(line.max_deviation > 0.0);
  CHECK((line.points.front() - Vec2(1.5, 6)).norm() < 1e-15);
  CHECK((line.points.back() - Vec2(1.5, 2)).norm() < 1e-15);
  for (std::size_t i = 1; i < line.points.size(); ++i)
    CHECK((line.points[i] - line.points[i - 1]).norm() > 0.0);
}

TEST_CASE("a closed curve's polyline does not repeat its first point", "[sampling]") {
  EllipseArcParams e;
  e.a = 2;
  e.b = 1;
  const CompositeCurve c({Segment::ellipse_arc(e)}, true);
  SampleOptions opt;
  opt.tolerance = 1e-3;
  const Polyline2 line = sample_curve(c, opt);
  CHECK(line.closed);
  CHECK((line.points.front() - line.points.back()).norm() > 1e-3);
}

TEST_CASE("sampling rejects a bad tolerance and one beyond the point budget", "[sampling][errors]") {
  const CompositeCurve c({test_segments()[0]}, false);
  SampleOptions opt;
  opt.tolerance = 0.0;
  REQUIRE_THROWS_AS(sample_curve(c, opt), RangeError);
  opt.tolerance = -1;
  REQUIRE_THROWS_AS(sample_curve(c, opt), RangeError);
  opt.tolerance = 1e-9;
  opt.max_points = 1000;
  REQUIRE_THROWS_AS(sample_curve(c, opt), BudgetError);
}
