#include "geometry/curves/segment.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>

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
  for (const Segment& s : {Segment::tbezier(p, -2, 1), Segment::hbezier(p, 0.01, -2.9, 0.9),
                           Segment::hbezier(p, 6.0, 0.5, -3), Segment::quasi_bspline_span(p, -8, 4),
                           Segment::ellipse_arc(e), Segment::rational_bezier(p, {1.0, 0.3, 2.5, 0.8})}) {
    const double bound = s.fourth_derivative_bound();
    for (int i = 1; i < 400; ++i) {
      const double t = i / 400.0, h = 1e-4;
      const double d4 = ((s.jet(t + h)[3] - s.jet(t - h)[3]) / (2 * h)).norm();
      CHECK(d4 <= bound * (1 + 1e-5) + 1e-6);
    }
  }
}

namespace {

// A rational quadratic Bézier (poles q, weights v) raised exactly to a cubic:
// the homogeneous points (v q, v) of degree 2 raised to degree 3.
Segment raised_quadratic(const std::array<Vec2, 3>& q, const std::array<double, 3>& v) {
  std::array<Eigen::Vector3d, 3> h;
  for (std::size_t i = 0; i < 3; ++i) h[i] = Eigen::Vector3d(v[i] * q[i].x(), v[i] * q[i].y(), v[i]);
  const std::array<Eigen::Vector3d, 4> c{h[0], (h[0] + 2.0 * h[1]) / 3.0, (2.0 * h[1] + h[2]) / 3.0, h[2]};
  std::array<Vec2, 4> points;
  std::array<double, 4> weights{};
  for (std::size_t i = 0; i < 4; ++i) {
    points[i] = c[i].head<2>() / c[i].z();
    weights[i] = c[i].z();
  }
  return Segment::rational_bezier(points, weights);
}

// The fourth derivative of a rational cubic Bézier at s, by Leibniz on N = r W
// with N'''' = W'''' = 0: r'''' = -(4 r''' W' + 6 r'' W'' + 4 r' W''') / W.
Vec2 rational_fourth(const Segment& s, double t) {
  const auto& w = s.rational_weights();
  const double u = 1.0 - t;
  const double d0 = w[0] * u * u * u + 3 * w[1] * t * u * u + 3 * w[2] * t * t * u + w[3] * t * t * t;
  const double d1 = 3 * ((w[1] - w[0]) * u * u + 2 * (w[2] - w[1]) * t * u + (w[3] - w[2]) * t * t);
  const double d2 = 6 * ((w[2] - 2 * w[1] + w[0]) * u + (w[3] - 2 * w[2] + w[1]) * t);
  const double d3 = 6 * (w[3] - 3 * w[2] + 3 * w[1] - w[0]);
  const CurveJet j = s.jet(t);
  return -(4 * j[3] * d1 + 6 * j[2] * d2 + 4 * j[1] * d3) / d0;
}

}  // namespace

TEST_CASE("rational bezier: a quarter circle is exact, its derivatives those of the conic",
          "[curves][rational]") {
  const double r = 250.0, k = std::sqrt(0.5);
  const Vec2 c(40, -70);
  const std::array<Vec2, 3> q{c + Vec2(r, 0), c + Vec2(r, r), c + Vec2(0, r)};
  const std::array<double, 3> v{1.0, k, 1.0};
  const Segment s = raised_quadratic(q, v);
  CHECK(s.kind() == SegmentKind::RationalBezier);
  CHECK(std::string(to_string(s.kind())) == "rational_bezier");
  for (int i = 0; i <= 200; ++i) {
    const double t = i / 200.0, u = 1.0 - t;
    const CurveJet j = s.jet(t);
    CHECK(std::abs((j[0] - c).norm() - r) <= 1e-12 * r);
    CHECK(s.curvature(t) == Approx(1.0 / r).epsilon(1e-12));  // counter-clockwise: turning left
    // The rational quadratic by hand: r = N / W with N = sum v_i q_i b_i, W = sum v_i b_i,
    // r' = (N' W - N W') / W^2.
    const double b[3] = {u * u, 2 * t * u, t * t}, db[3] = {-2 * u, 2 * (u - t), 2 * t};
    Vec2 n = Vec2::Zero(), dn = Vec2::Zero();
    double w = 0, dw = 0;
    for (std::size_t m = 0; m < 3; ++m) {
      n += v[m] * b[m] * q[m];
      dn += v[m] * db[m] * q[m];
      w += v[m] * b[m];
      dw += v[m] * db[m];
    }
    CHECK(distance(j[0], n / w) <= 1e-12 * r);
    CHECK(distance(j[1], (dn * w - n * dw) / (w * w)) <= 1e-12 * r);
  }
  // r'(0) = 2 (v1 / v0) (q1 - q0) and r'(1) = 2 (v1 / v2) (q2 - q1).
  CHECK(distance(s.jet(0.0)[1], 2 * k * (q[1] - q[0])) <= 1e-12 * r);
  CHECK(distance(s.jet(1.0)[1], 2 * k * (q[2] - q[1])) <= 1e-12 * r);
}

TEST_CASE("rational bezier: derivatives agree with finite differences, weights scale out",
          "[curves][rational]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coord(-100.0, 100.0), logw(-1.5, 1.5);
  for (int trial = 0; trial < 6; ++trial) {
    const std::array<Vec2, 4> p{Vec2(coord(rng), coord(rng)), Vec2(coord(rng), coord(rng)),
                                Vec2(coord(rng), coord(rng)), Vec2(coord(rng), coord(rng))};
    const std::array<double, 4> w{std::exp(logw(rng)), std::exp(logw(rng)), std::exp(logw(rng)),
                                  std::exp(logw(rng))};
    const Segment s = Segment::rational_bezier(p, w);
    const Segment scaled = Segment::rational_bezier(p, {3 * w[0], 3 * w[1], 3 * w[2], 3 * w[3]});
    CHECK(distance(s.point(0.0), p[0]) <= 1e-13 * 100);
    CHECK(distance(s.point(1.0), p[3]) <= 1e-13 * 100);
    for (int i = 1; i < 40; ++i) {
      const double t = i / 40.0, h = 1e-5;
      const CurveJet j = s.jet(t), a = s.jet(t + h), b = s.jet(t - h);
      for (std::size_t d = 0; d < 3; ++d) {
        const Vec2 fd = (a[d] - b[d]) / (2 * h);
        CHECK(distance(j[d + 1], fd) <= 1e-6 * (1.0 + j[d + 1].norm()));
      }
      // The test's own fourth derivative agrees with the difference of the third.
      const Vec2 fd4 = (a[3] - b[3]) / (2 * h);
      CHECK(distance(rational_fourth(s, t), fd4) <= 1e-6 * (1.0 + fd4.norm()));
      const CurveJet js = scaled.jet(t);
      for (std::size_t d = 0; d < 4; ++d) CHECK(distance(js[d], j[d]) <= 1e-12 * (1.0 + j[d].norm()));
      // The rational basis is a partition of unity.
      const BasisJet basis = s.weights(t);
      CHECK(basis[0][0] + basis[0][1] + basis[0][2] + basis[0][3] == Approx(1.0).epsilon(1e-14));
    }
  }
  // Equal weights: the cubic Bézier polynomial, with a fourth derivative of 0.
  const std::array<Vec2, 4> p{Vec2(0, 0), Vec2(1, 2), Vec2(3, 3), Vec2(4, 1)};
  const Segment poly = Segment::rational_bezier(p, {2, 2, 2, 2});
  const double t = 0.3, u = 0.7;
  CHECK(distance(poly.point(t), u * u * u * p[0] + 3 * t * u * u * p[1] + 3 * t * t * u * p[2] +
                                    t * t * t * p[3]) <= 1e-15 * 10);
  CHECK(poly.fourth_derivative_bound() == 0.0);
}

TEST_CASE("rational bezier: the proven fourth-derivative bound holds and is close", "[curves][rational]") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> coord(-100.0, 100.0), logw(-1.5, 1.5);
  std::vector<Segment> segments{
      raised_quadratic({Vec2(250, 0), Vec2(250, 250), Vec2(0, 250)}, {1.0, std::sqrt(0.5), 1.0})};
  for (int trial = 0; trial < 8; ++trial) {
    const std::array<Vec2, 4> p{Vec2(coord(rng), coord(rng)), Vec2(coord(rng), coord(rng)),
                                Vec2(coord(rng), coord(rng)), Vec2(coord(rng), coord(rng))};
    segments.push_back(Segment::rational_bezier(
        p, {std::exp(logw(rng)), std::exp(logw(rng)), std::exp(logw(rng)), std::exp(logw(rng))}));
  }
  double loosest = 0.0;
  for (const Segment& s : segments) {
    const double bound = s.fourth_derivative_bound();
    double measured = 0.0;
    for (int i = 0; i <= 4000; ++i) measured = std::max(measured, rational_fourth(s, i / 4000.0).norm());
    INFO("bound " << bound << ", measured " << measured);
    CHECK(measured <= bound);
    CHECK(bound <= 10.0 * measured);  // a proof, not a guess, yet not absurdly loose
    loosest = std::max(loosest, bound / measured);
  }
  WARN("rational bezier: the fourth-derivative bound is at most " << loosest << " x the measured maximum");
}

TEST_CASE("rational bezier: weights not finite and > 0 are refused naming the weight",
          "[curves][rational][errors]") {
  const std::array<Vec2, 4> p{Vec2(0, 0), Vec2(1, 2), Vec2(3, 3), Vec2(4, 1)};
  for (const double bad : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    try {
      Segment::rational_bezier(p, {1.0, 1.0, bad, 1.0});
      FAIL("weight " << bad << " accepted");
    } catch (const RangeError& e) {
      CHECK(e.field() == "w2");
      CHECK_THAT(e.what(), Catch::Contains("weight w2 = "));
    }
  }
  CHECK_THROWS_AS(Segment::rational_bezier({Vec2(0, 0), Vec2(NAN, 2), Vec2(3, 3), Vec2(4, 1)}, {1, 1, 1, 1}),
                  RangeError);
  // Other control points, the same weights; no shape parameters.
  const Segment s = Segment::rational_bezier(p, {1, 0.5, 2, 1});
  const Segment moved = s.with_points({Vec2(1, 0), Vec2(2, 2), Vec2(4, 3), Vec2(5, 1)});
  CHECK(moved.rational_weights() == s.rational_weights());
  CHECK(distance(moved.point(0.4), s.point(0.4) + Vec2(1, 0)) <= 1e-14);
  CHECK_THROWS_AS(s.with_shape(0.0, 0.0), GeometryError);
}
