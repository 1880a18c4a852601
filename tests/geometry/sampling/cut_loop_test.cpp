#include "geometry/sampling/cut_loop.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <map>

#include "geometry/core/errors.h"

using namespace fabmesh;

namespace {

// A rational cubic span with weights far apart: it bulges past its end
// points in x and y, so its bounds come from interior extremes.
Segment bulging_span() {
  return Segment::rational_bezier({Vec2(200, 0), Vec2(330, -60), Vec2(360, 260), Vec2(200, 200)},
                                  {1.0, 2.5, 0.4, 1.3});
}

// A closed outline: a line, the rational span, a T-Bézier, a line.
CompositeCurve mixed_outline() {
  return CompositeCurve(
      {Segment::line({0, 0}, {200, 0}), bulging_span(),
       Segment::tbezier({Vec2(200, 200), Vec2(150, 260), Vec2(50, 260), Vec2(0, 200)}, 0.5, 0.5),
       Segment::line({0, 200}, {0, 0})},
      true);
}

// The extreme of coordinate `axis` (sign +1: max, -1: min) of a segment by
// dense sampling, refined by golden-section search around the best sample.
double sampled_extreme(const Segment& seg, int axis, double sign, int samples = 20000) {
  auto f = [&](double s) { return sign * seg.point(s)[axis]; };
  int best = 0;
  for (int i = 1; i <= samples; ++i) {
    if (f(static_cast<double>(i) / samples) > f(static_cast<double>(best) / samples)) best = i;
  }
  double a = std::max(0, best - 1) / static_cast<double>(samples);
  double b = std::min(samples, best + 1) / static_cast<double>(samples);
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  for (int it = 0; it < 200 && b - a > 1e-15; ++it) {
    const double c = b - g * (b - a), d = a + g * (b - a);
    if (f(c) > f(d)) {
      b = d;
    } else {
      a = c;
    }
  }
  return sign * std::max({f(a), f(b), f(static_cast<double>(best) / samples)});
}

// Each entity of `loop` starts where the previous one ends (the last where the first starts).
void check_chained(const CutLoop& loop) {
  for (std::size_t i = 0; i < loop.entities.size(); ++i) {
    const Vec2 end = loop.entities[i].points.back();
    const Vec2 next = loop.entities[(i + 1) % loop.entities.size()].points.front();
    CHECK((end - next).norm() < 1e-9);
  }
}

}  // namespace

TEST_CASE("cut_loop: a rational Bezier segment is one Spline entity with its exact points and weights",
          "[geometry][sampling][cut_loop][rational]") {
  const CompositeCurve curve = mixed_outline();
  CutLoopOptions o;
  o.tolerance = 0.01;
  const CutLoop loop = cut_loop(curve, "outline", true, o);
  CHECK(loop.tolerance == 0.01);
  REQUIRE(loop.entities.size() == 4);
  CHECK(loop.entities[0].kind == CutKind::Line);
  CHECK(loop.entities[1].kind == CutKind::Spline);
  CHECK(loop.entities[2].kind == CutKind::Polyline);
  CHECK(loop.entities[3].kind == CutKind::Line);
  const CutEntity& spline = loop.entities[1];
  const Segment span = bulging_span();
  REQUIRE(spline.points.size() == 4);
  for (std::size_t j = 0; j < 4; ++j) {
    CHECK(spline.points[j] == span.control_points()[j]);
    CHECK(spline.weights[j] == span.rational_weights()[j]);
  }
  // Its points are the segment's.
  for (int i = 0; i <= 100; ++i)
    CHECK((spline_point(spline, i / 100.0) - span.point(i / 100.0)).norm() < 1e-12);
  // The chain closes: each entity starts where the previous one ends.
  check_chained(loop);
}

TEST_CASE("cut_loop: a reversed loop reverses a Spline's points and weights",
          "[geometry][sampling][cut_loop][rational]") {
  CutLoopOptions o;
  o.reverse = true;
  const CutLoop loop = cut_loop(mixed_outline(), "holes[0]", false, o);
  REQUIRE(loop.entities.size() == 4);
  CHECK(loop.entities[0].kind == CutKind::Line);
  CHECK(loop.entities[1].kind == CutKind::Polyline);
  CHECK(loop.entities[2].kind == CutKind::Spline);
  CHECK(loop.entities[3].kind == CutKind::Line);
  const CutEntity& spline = loop.entities[2];
  const Segment span = bulging_span();
  for (std::size_t j = 0; j < 4; ++j) {
    CHECK(spline.points[j] == span.control_points()[3 - j]);
    CHECK(spline.weights[j] == span.rational_weights()[3 - j]);
  }
  // The reversed entity runs the same points backwards.
  for (int i = 0; i <= 100; ++i)
    CHECK((spline_point(spline, i / 100.0) - span.point(1.0 - i / 100.0)).norm() < 1e-12);
  check_chained(loop);
}

TEST_CASE("cut_loop: a Spline breaks a polyline run, and the runs across a closed loop's start join",
          "[geometry][sampling][cut_loop][rational]") {
  // T-Bézier, rational, T-Bézier, rational, T-Bézier: the first and the last
  // T-Bézier are one run across the loop's start.
  const Vec2 a(0, 0), b(100, 0), c(100, 100), d(50, 150), e(0, 100);
  const CompositeCurve curve({Segment::tbezier({a, Vec2(30, -20), Vec2(70, -20), b}, 0, 0),
                              Segment::rational_bezier({b, Vec2(130, 20), Vec2(130, 80), c}, {1, 3, 3, 1}),
                              Segment::tbezier({c, Vec2(90, 120), Vec2(70, 140), d}, 0, 0),
                              Segment::rational_bezier({d, Vec2(30, 160), Vec2(10, 130), e}, {2, 2, 2, 2}),
                              Segment::tbezier({e, Vec2(-20, 70), Vec2(-20, 30), a}, 0, 0)},
                             true);
  const CutLoop loop = cut_loop(curve, "outline", true, {});
  std::vector<CutKind> kinds;
  for (const CutEntity& en : loop.entities) kinds.push_back(en.kind);
  CHECK(kinds ==
        std::vector<CutKind>{CutKind::Spline, CutKind::Polyline, CutKind::Spline, CutKind::Polyline});
  REQUIRE(loop.entities.size() == 4);
  CHECK(loop.entities[0].points.front() == b);
  CHECK((loop.entities[1].points.front() - c).norm() < 1e-9);
  CHECK((loop.entities[1].points.back() - d).norm() < 1e-9);
  CHECK(loop.entities[2].weights == std::array<double, 4>{2, 2, 2, 2});  // equal weights are kept as given
  const std::vector<Vec2>& run = loop.entities[3].points;
  CHECK((run.front() - e).norm() < 1e-9);
  CHECK((run.back() - b).norm() < 1e-9);
  CHECK(std::any_of(run.begin(), run.end(), [&](const Vec2& q) { return (q - a).norm() < 1e-9; }));
}

TEST_CASE("cut_bounds: a Spline's box is its extremes, as dense sampling finds them, within 1e-9",
          "[geometry][sampling][cut_loop][rational]") {
  const double kQuarterWeight = (1 + 2 * std::sqrt(0.5)) / 3;
  const double kInner = 2 * std::sqrt(0.5) / (1 + 2 * std::sqrt(0.5));
  const std::vector<Segment> spans{
      bulging_span(),
      // A circle's quarter of radius 50 (the quadratic NURBS raised to a
      // cubic, docs/math/curves.md 5): the extremes are its ends.
      Segment::rational_bezier({Vec2(50, 0), Vec2(50, 50 * kInner), Vec2(50 * kInner, 50), Vec2(0, 50)},
                               {1.0, kQuarterWeight, kQuarterWeight, 1.0}),
      // An S with two interior extremes in y and weights three orders apart.
      Segment::rational_bezier({Vec2(0, 0), Vec2(40, 300), Vec2(80, -300), Vec2(120, 0)},
                               {1.0, 0.05, 20.0, 1.0}),
      // A loop (self-crossing span): extremes on both sides in x.
      Segment::rational_bezier({Vec2(0, 0), Vec2(300, 200), Vec2(-200, 200), Vec2(100, 0)},
                               {1.0, 1.7, 0.6, 2.0}),
      // Polynomial (equal weights), far from the origin.
      Segment::rational_bezier(
          {Vec2(1e4, 5e3), Vec2(1e4 + 90, 5e3 + 10), Vec2(1e4 - 30, 5e3 + 80), Vec2(1e4 + 5, 5e3)},
          {3.0, 3.0, 3.0, 3.0}),
  };
  for (const Segment& span : spans) {
    CutLoop loop;
    loop.closed = false;
    const std::array<Vec2, 4>& p = span.control_points();
    loop.entities.push_back({CutKind::Spline, {p[0], p[1], p[2], p[3]}, {}, span.rational_weights()});
    const auto [lo, hi] = cut_bounds({loop});
    const double size = (hi - lo).maxCoeff();
    INFO("span from " << p[0].transpose() << " to " << p[3].transpose());
    for (int axis = 0; axis < 2; ++axis) {
      CHECK(std::abs(lo[axis] - sampled_extreme(span, axis, -1.0)) <= 1e-9 * size);
      CHECK(std::abs(hi[axis] - sampled_extreme(span, axis, 1.0)) <= 1e-9 * size);
    }
    // Every sample lies in the box.
    for (int i = 0; i <= 100000; ++i) {
      const Vec2 q = span.point(i / 100000.0);
      CHECK_FALSE((q.x() < lo.x() - 1e-12 * size || q.y() < lo.y() - 1e-12 * size ||
                   q.x() > hi.x() + 1e-12 * size || q.y() > hi.y() + 1e-12 * size));
    }
  }
}

TEST_CASE("cut_bounds: a Spline's interior extremes count, not only its ends (the check can fail)",
          "[geometry][sampling][cut_loop][rational]") {
  const Segment span = bulging_span();
  CutLoop loop;
  const std::array<Vec2, 4>& p = span.control_points();
  loop.entities.push_back({CutKind::Spline, {p[0], p[1], p[2], p[3]}, {}, span.rational_weights()});
  const auto [lo, hi] = cut_bounds({loop});
  // Beyond both end points in x and in y, and inside the control polygon's box.
  CHECK(hi.x() > 200.0 + 100.0);  // 307.06
  CHECK(lo.y() < -25.0);          // -29.95
  CHECK(hi.y() > 200.0 + 0.4);    // 200.50
  CHECK(hi.x() < 360.0);
  CHECK(lo.y() > -60.0);
  CHECK(hi.y() < 260.0);
  // The same span as a polyline of its ends only would miss them.
  CutLoop ends;
  ends.entities.push_back({CutKind::Polyline, {p[0], p[3]}, {}});
  CHECK(cut_bounds({ends}).second.x() < hi.x() - 100.0);
}

TEST_CASE("spline_polyline: the points run from P0 to P3 on the curve, each chord within the tolerance",
          "[geometry][sampling][cut_loop][rational]") {
  const Segment span = bulging_span();
  const std::array<Vec2, 4>& p = span.control_points();
  const CutEntity e{CutKind::Spline, {p[0], p[1], p[2], p[3]}, {}, span.rational_weights()};
  for (const double tolerance : {1.0, 0.01}) {
    const std::vector<Vec2> pts = spline_polyline(e, tolerance);
    REQUIRE(pts.size() >= 3);
    CHECK(pts.front() == p[0]);
    CHECK(pts.back() == p[3]);
    // Dense points of the curve lie within the tolerance of the polyline.
    for (int i = 0; i <= 4000; ++i) {
      const Vec2 q = span.point(i / 4000.0);
      double nearest = INFINITY;
      for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
        const Vec2 ab = pts[k + 1] - pts[k];
        const double t = std::clamp((q - pts[k]).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
        nearest = std::min(nearest, (pts[k] + t * ab - q).norm());
      }
      CHECK(nearest <= tolerance);
    }
  }
  CHECK(spline_polyline(e, 0.01).size() > spline_polyline(e, 1.0).size());
  CHECK_THROWS_AS(spline_polyline(e, 0.0), RangeError);
}

TEST_CASE("cut_loop: a uniform cubic B-spline span is a polynomial Spline, other quasi-cubic spans polylines",
          "[geometry][sampling][cut_loop]") {
  const std::array<Vec2, 4> b{Vec2(0, 0), Vec2(100, 40), Vec2(200, -30), Vec2(260, 90)};
  const Segment cubic = Segment::quasi_bspline_span(b, 0.0, 0.0);
  const Segment shaped = Segment::quasi_bspline_span(b, -2.0, 0.5);  // a quartic: not a cubic Bézier
  const CompositeCurve curve({cubic, shaped.with_points({b[1], b[2], b[3], Vec2(300, 0)})}, false);
  CutLoopOptions o;
  o.tolerance = 0.01;
  const CutLoop loop = cut_loop(curve, "curve", false, o);
  REQUIRE(loop.entities.size() == 2);
  const CutEntity& spline = loop.entities[0];
  REQUIRE(spline.kind == CutKind::Spline);
  CHECK(spline.weights == std::array<double, 4>{1.0, 1.0, 1.0, 1.0});
  double worst = 0.0;
  for (int i = 0; i <= 1000; ++i) {
    const double s = i / 1000.0;
    worst = std::max(worst, (spline_point(spline, s) - cubic.point(s)).norm());
  }
  INFO("largest distance " << worst);
  CHECK(worst <= 1e-12 * 300);
  CHECK(loop.entities[1].kind == CutKind::Polyline);
}
