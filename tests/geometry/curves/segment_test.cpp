#include "geometry/curves/segment.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "geometry/core/errors.h"
#include "geometry/curves/composite.h"

using namespace fabmesh;

namespace {

const std::array<Vec2, 4> kP{Vec2(1, 0.2), Vec2(0.2, 0.4), Vec2(1.6, 1.4), Vec2(1, 0.2)};

double distance(const Vec2& a, const Vec2& b) { return (a - b).norm(); }

}  // namespace

TEST_CASE("tbezier: endpoint derivatives match the formulas of curves.md", "[curves][tbezier]") {
  const double pi = M_PI;
  for (auto [l, m] : {std::pair{0.0, 0.0}, std::pair{-1.7, 0.4}, std::pair{1.0, -2.0}}) {
    const Segment s = Segment::tbezier(kP, l, m);
    const Vec2 d0 = kP[1] - kP[0], d2 = kP[3] - kP[2];
    const CurveJet a = s.jet(0.0), b = s.jet(1.0);
    CHECK(distance(a[0], kP[0]) <= 1e-15);
    CHECK(distance(b[0], kP[3]) <= 1e-15);
    CHECK(distance(a[1], pi / 2 * (2 + l) * d0) <= 1e-12);
    CHECK(distance(b[1], pi / 2 * (2 + m) * d2) <= 1e-12);
    CHECK(distance(a[2], pi * pi / 2 * ((1 + 2 * l) * kP[0] - 2 * (1 + l) * kP[1] + kP[2])) <= 1e-12);
    CHECK(distance(b[2], pi * pi / 2 * (kP[1] - 2 * (1 + m) * kP[2] + (1 + 2 * m) * kP[3])) <= 1e-12);
    CHECK(distance(a[3], pi * pi * pi / 8 * (5 * l - 2) * d0) <= 1e-11);
    CHECK(distance(b[3], pi * pi * pi / 8 * (5 * m - 2) * d2) <= 1e-11);
  }
}

TEST_CASE("tbezier: shape parameters out of [-2, 1] are rejected with the value",
          "[curves][tbezier][errors]") {
  REQUIRE_THROWS_AS(Segment::tbezier(kP, 1.7, 0.0), RangeError);
  REQUIRE_THROWS_WITH(Segment::tbezier(kP, 0.0, -2.5), Catch::Contains("mu = -2.5"));
  REQUIRE_THROWS_WITH(Segment::tbezier(kP, std::nan(""), 0.0), Catch::Contains("not a finite"));
}

TEST_CASE("ellipse arcs are exact to 1e-12", "[curves][ellipse]") {
  EllipseArcParams p;
  p.center = Vec2(3, -2);
  p.a = 5;
  p.b = 2;
  p.rotation_deg = 30;
  p.from_deg = -45;
  p.to_deg = 250;
  const Segment s = Segment::ellipse_arc(p);
  const double c = std::cos(M_PI / 6), sn = std::sin(M_PI / 6);
  for (int i = 0; i <= 1000; ++i) {
    const double sp = i / 1000.0;
    const Vec2 q = s.point(sp) - p.center;
    const double x = c * q.x() + sn * q.y(), y = -sn * q.x() + c * q.y();  // back into the ellipse frame
    CHECK((x / p.a) * (x / p.a) + (y / p.b) * (y / p.b) == Approx(1.0).margin(1e-12));
    // And the point is the one at the expected central angle.
    const double theta = (p.from_deg + sp * (p.to_deg - p.from_deg)) * M_PI / 180;
    CHECK(x == Approx(p.a * std::cos(theta)).margin(1e-12));
    CHECK(y == Approx(p.b * std::sin(theta)).margin(1e-12));
  }
}

TEST_CASE("a full circle is closed and has constant curvature", "[curves][ellipse]") {
  EllipseArcParams p;
  p.a = p.b = 2.5;
  const Segment s = Segment::ellipse_arc(p);
  CHECK(distance(s.point(0.0), s.point(1.0)) <= 1e-12);
  for (double t : {0.0, 0.13, 0.5, 0.77, 1.0}) CHECK(s.curvature(t) == Approx(1 / 2.5).epsilon(1e-12));
  const CompositeCurve c({s}, true);
  const auto joints = c.joints();
  REQUIRE(joints.size() == 1);
  CHECK(joints[0].achieved == Continuity::G2);
}

TEST_CASE("quasi-cubic B-spline span: endpoint identities", "[curves][quasi_bspline]") {
  const std::array<Vec2, 4> p{Vec2(0, 0), Vec2(1, 2), Vec2(3, 1), Vec2(4, 4)};
  for (double l : {-8.0, -1.0, 0.0, 1.0, 4.0}) {
    const Segment s = Segment::quasi_bspline_span(p, l, 0.5);
    const CurveJet a = s.jet(0.0);
    CHECK(distance(a[1], (p[2] - p[0]) / 2) <= 1e-12);
    CHECK(distance(a[2], (2 + l) / 2 * (p[0] - 2 * p[1] + p[2])) <= 1e-12);
  }
  REQUIRE_THROWS_AS(Segment::quasi_bspline_span(p, 1.5, 0.0), RangeError);
}

TEST_CASE("hbezier segment: derivative scaling to the unit parameter", "[curves][hbezier]") {
  const std::array<Vec2, 4> p{Vec2(0, 0), Vec2(1, 2), Vec2(3, 3), Vec2(4, 1)};
  const Segment s = Segment::hbezier(p, 2.0, 0.5, -1.0);
  const HBezierEndConstants c = hbezier_end_constants(2.0, 0.5, -1.0);
  CHECK(distance(s.jet(0.0)[1], 2.0 * c.a0 * (p[1] - p[0])) <= 1e-12);
  CHECK(distance(s.jet(1.0)[1], 2.0 * c.a1 * (p[3] - p[2])) <= 1e-12);
  REQUIRE_THROWS_AS(Segment::hbezier(p, 0.0, 0.0, 0.0), RangeError);
  REQUIRE_THROWS_AS(Segment::hbezier(p, 11.0, 0.0, 0.0), RangeError);
  REQUIRE_THROWS_AS(Segment::hbezier(p, 1.0, -3.3, 0.0), RangeError);  // below lambda*(1) = -3.2053
  REQUIRE_NOTHROW(Segment::hbezier(p, 1.0, -3.2, 0.0));
}

TEST_CASE("fourth-derivative bounds hold for every family", "[curves][sampling]") {
  const std::array<Vec2, 4> p{Vec2(0, 0), Vec2(1, 2), Vec2(3, 3), Vec2(4, 1)};
  EllipseArcParams e;
  e.a = 3;
  e.b = 1;
  e.to_deg = 300;
  for (const Segment& s :
       {Segment::tbezier(p, -2, 1), Segment::hbezier(p, 0.01, -2.9, 0.9), Segment::hbezier(p, 6.0, 0.5, -3),
        Segment::quasi_bspline_span(p, -8, 4), Segment::ellipse_arc(e)}) {
    const double bound = s.fourth_derivative_bound();
    for (int i = 1; i < 400; ++i) {
      const double t = i / 400.0, h = 1e-4;
      const double d4 = ((s.jet(t + h)[3] - s.jet(t - h)[3]) / (2 * h)).norm();
      CHECK(d4 <= bound * (1 + 1e-5) + 1e-6);
    }
  }
}
