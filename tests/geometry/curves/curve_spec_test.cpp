#include "geometry/curves/curve_spec.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "geometry/core/errors.h"
#include "tests/geometry/curves/segment_specs.h"

using namespace fabmesh;
using fabmesh::test::explicit_tbezier;
using fabmesh::test::joined;

namespace {

double rel(const Vec2& a, const Vec2& b) { return (a - b).norm() / std::max(a.norm(), b.norm()); }

}  // namespace

TEST_CASE("tbezier G1 join: Q1 from the formula of curves.md and r1'(1) = alpha r2'(0)", "[curves][joins]") {
  CurveSpec spec;
  spec.segments = {explicit_tbezier({{1, 0.2}, {0.2, 0.4}, {1.6, 1.4}, {2, 1}}, 0.5, -0.5),
                   joined(Continuity::G1, {{3, 1}, {4, 0}}, -1.0, 0.0, 2.0)};
  const CompositeCurve c = construct_curve(spec);
  const auto& p = c.segments()[0].control_points();
  const auto& q = c.segments()[1].control_points();
  const double k = (2 + (-0.5)) / (2.0 * (2 + (-1.0)));
  CHECK(rel(q[0], p[3]) < 1e-15);
  CHECK(rel(q[1], (1 + k) * p[3] - k * p[2]) < 1e-13);
  CHECK(rel(c.segments()[0].jet(1.0)[1], 2.0 * c.segments()[1].jet(0.0)[1]) < 1e-9);
  const auto joints = c.joints();
  REQUIRE(joints.size() == 1);
  CHECK(joints[0].tangent_angle < 1e-9);
  CHECK(joints[0].achieved >= Continuity::G1);
}

TEST_CASE("tbezier G2 join: Q2 from the formula of curves.md and matching curvature", "[curves][joins]") {
  const double mu = 0.3, lt = -0.6, mt = 0.2, alpha = 1.5, beta = 0.7;
  CurveSpec spec;
  spec.segments = {explicit_tbezier({{0, 0}, {1, 2}, {3, 2.5}, {4, 1}}, -1.0, mu),
                   joined(Continuity::G2, {{7, 3}}, lt, mt, alpha, beta)};
  const CompositeCurve c = construct_curve(spec);
  const auto& p = c.segments()[0].control_points();
  const auto& q = c.segments()[1].control_points();
  const double pi = M_PI, a2 = alpha * alpha, a3 = a2 * alpha;
  const Vec2 q2 =
      ((1 + 2 * mu) / a2 + 2 * (1 + lt) * (2 + mu) / (alpha * (2 + lt)) - beta * (2 + mu) / (a3 * pi) + 1) *
          p[3] -
      (2 * (1 + mu) / a2 + 2 * (2 + mu) * (1 + lt) / (alpha * (2 + lt)) - beta * (2 + mu) / (a3 * pi)) *
          p[2] +
      (1 / a2) * p[1];
  CHECK(rel(q[2], q2) < 1e-12);
  const CurveJet r1 = c.segments()[0].jet(1.0), r2 = c.segments()[1].jet(0.0);
  CHECK(rel(r1[2], a2 * r2[2] + beta * r2[1]) < 1e-9);
  const auto joints = c.joints();
  CHECK(joints[0].curvature_jump < 1e-9);
  CHECK(joints[0].achieved == Continuity::G2);
}

TEST_CASE("closed loop whose first segment joins the last: G2 everywhere by one solve", "[curves][joins]") {
  CurveSpec spec;
  spec.closed = true;
  spec.segments = {joined(Continuity::G2, {{10, 0}}, 0.2, -0.5, 1.0, 0.0),
                   joined(Continuity::G2, {{10, 8}}, -1.0, 0.0, 1.3, 0.4),
                   joined(Continuity::G2, {{0, 8}}, 0.5, 0.5, 0.8, -0.2),
                   joined(Continuity::G2, {{0, 0}}, 0.0, 0.0, 1.0, 0.0)};
  const CompositeCurve c = construct_curve(spec);
  const auto joints = c.joints();
  REQUIRE(joints.size() == 4);
  for (const JointReport& j : joints) {
    CHECK(j.gap < 1e-9 * c.extent());
    CHECK(j.tangent_angle < 1e-9);
    CHECK(j.curvature_jump < 1e-9);
    CHECK(j.achieved == Continuity::G2);
  }
  CHECK(joints.back().closing);
  REQUIRE_NOTHROW(verify_declared_continuity(spec, c));
}

TEST_CASE("hbezier G1/G2 join: the test vector of h-bezier.md, coordinate by coordinate",
          "[curves][joins][hbezier]") {
  // The join formulas act on each coordinate alone, so the 3D vector is checked
  // through its (x, y) and (x, z) projections.
  const std::array<Vec3, 4> p3{Vec3(0, 0, 0), Vec3(1, 2, 0), Vec3(3, 3, 1), Vec3(4, 1, 0)};
  std::array<CurveJet, 2> end{}, start{};
  for (int proj = 0; proj < 2; ++proj) {
    const int c = proj == 0 ? 1 : 2;
    CurveSpec spec;
    spec.family = CurveFamily::HBezier;
    SegmentSpec a;
    a.kind = SegmentKind::HBezier;
    for (const Vec3& v : p3) a.points.emplace_back(v.x(), v[c]);
    a.alpha = 1.0;
    a.lambda = 0.5;
    a.mu = 0.5;
    SegmentSpec b;
    b.kind = SegmentKind::HBezier;
    b.alpha = 2.0;
    b.lambda = 0.0;
    b.mu = -1.0;
    b.join = JoinSpec{Continuity::G2, 1.0, 0.0, 1.0, 0.0};
    b.points = {Vec2(8, 0)};
    spec.segments = {a, b};
    const CompositeCurve curve = construct_curve(spec);
    const auto& q = curve.segments()[1].control_points();
    CHECK(q[1].x() == Approx(6.11046163281).epsilon(1e-11));
    CHECK(q[2].x() == Approx(7.46485801734).epsilon(1e-11));
    CHECK(q[1].y() == Approx(proj == 0 ? -3.22092326562 : -2.11046163281).epsilon(1e-11));
    CHECK(q[2].y() == Approx(proj == 0 ? -25.0226570331 : -14.9206226164).epsilon(1e-11));
    end[proj] = curve.segments()[0].jet(1.0);
    start[proj] = curve.segments()[1].jet(0.0);
  }
  // Curvature in space at the joint, from both sides: 0.1912156585.
  auto curvature = [](const std::array<CurveJet, 2>& j) {
    const Vec3 d1(j[0][1].x(), j[0][1].y(), j[1][1].y()), d2(j[0][2].x(), j[0][2].y(), j[1][2].y());
    return d1.cross(d2).norm() / std::pow(d1.norm(), 3);
  };
  CHECK(curvature(end) == Approx(0.1912156585).epsilon(1e-9));
  CHECK(curvature(start) == Approx(0.1912156585).epsilon(1e-9));
}

TEST_CASE("declared continuity that the joint contradicts is an error", "[curves][joins][errors]") {
  CurveSpec spec;
  spec.key = "outline";
  SegmentSpec second = explicit_tbezier({{4, 1}, {5, 3}, {6, 2}, {7, 0}}, 0, 0);
  second.declared = Continuity::G1;  // the tangents at (4, 1) are not parallel
  spec.segments = {explicit_tbezier({{0, 0}, {1, 2}, {3, 2.5}, {4, 1}}, 0, 0), second};
  const CompositeCurve c = construct_curve(spec);
  REQUIRE_THROWS_AS(verify_declared_continuity(spec, c), GeometryError);
  REQUIRE_THROWS_WITH(verify_declared_continuity(spec, c), Catch::Contains("declared G1"));
  try {
    verify_declared_continuity(spec, c);
  } catch (const GeometryError& e) {
    CHECK(e.where() == "outline");  // at the curve's key
  }
}

TEST_CASE("a closed curve that does not close is an error naming the closing joint",
          "[curves][joins][errors]") {
  CurveSpec spec;
  spec.closed = true;
  spec.segments = {explicit_tbezier({{0, 0}, {1, 2}, {3, 2.5}, {4, 1}}, 0, 0)};
  SegmentSpec line;
  line.kind = SegmentKind::Line;
  line.points = {Vec2(0.5, 0)};
  spec.segments.push_back(line);
  const CompositeCurve c = construct_curve(spec);
  REQUIRE_THROWS_WITH(verify_declared_continuity(spec, c),
                      Catch::Contains("closing joint") && Catch::Contains("does not close"));
}

TEST_CASE("a join that is given the wrong number of free points is an error", "[curves][joins][errors]") {
  CurveSpec spec;
  spec.segments = {explicit_tbezier({{0, 0}, {1, 2}, {3, 2.5}, {4, 1}}, 0, 0),
                   joined(Continuity::G1, {{3, 1}, {4, 0}, {5, 5}}, 0, 0, 1)};
  REQUIRE_THROWS_WITH(construct_curve(spec), Catch::Contains("takes 2 point(s), got 3"));
}

TEST_CASE("quasi-cubic B-spline: golden data of curves.md and interpolation of the ends",
          "[curves][quasi_bspline]") {
  CurveSpec spec;
  spec.family = CurveFamily::QuasiBSpline;
  spec.bspline_points = {{1.5, 6}, {1, 5}, {2, 4}, {3, 3}, {1.5, 2}};
  const CompositeCurve c = construct_curve(spec);
  REQUIRE(c.size() == 4);
  const std::array<Vec2, 4> golden{Vec2(1.296875, 5.53125), Vec2(1.53125, 4.5), Vec2(2.447916666667, 3.5),
                                   Vec2(2.151041666667, 2.46875)};
  for (int i = 0; i < 4; ++i) {
    CHECK(c.segments()[i].point(0.5).x() == Approx(golden[i].x()).margin(1e-12));
    CHECK(c.segments()[i].point(0.5).y() == Approx(golden[i].y()).margin(1e-12));
  }
  CHECK((c.segments().front().point(0.0) - Vec2(1.5, 6)).norm() < 1e-15);
  CHECK((c.segments().back().point(1.0) - Vec2(1.5, 2)).norm() < 1e-15);
  for (const JointReport& j : c.joints()) CHECK(j.achieved == Continuity::G2);
}

TEST_CASE("quasi-cubic B-spline: changing lambda_i changes only the two spans at joint i",
          "[curves][quasi_bspline]") {
  CurveSpec spec;
  spec.family = CurveFamily::QuasiBSpline;
  spec.bspline_points = {{0, 0}, {1, 2}, {2, 0}, {3, 3}, {4, 1}, {5, 2}};
  spec.bspline_lambdas = {0, 0, 0, 0};
  const CompositeCurve a = construct_curve(spec);
  spec.bspline_lambdas[1] = -5;  // lambda_2: spans 1 and 2 meet there
  const CompositeCurve b = construct_curve(spec);
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double diff = (a.segments()[i].point(0.3) - b.segments()[i].point(0.3)).norm();
    if (i == 1 || i == 2) {
      CHECK(diff > 1e-3);
    } else {
      CHECK(diff == 0.0);
    }
  }
}

TEST_CASE("quasi-cubic B-spline: too few points or lambdas out of range are errors",
          "[curves][quasi_bspline][errors]") {
  CurveSpec spec;
  spec.family = CurveFamily::QuasiBSpline;
  spec.bspline_points = {{0, 0}, {1, 1}};
  REQUIRE_THROWS_WITH(construct_curve(spec), Catch::Contains("at least 3 points"));
  spec.bspline_points = {{0, 0}, {1, 1}, {2, 0}};
  spec.bspline_lambdas = {1.5};
  REQUIRE_THROWS_AS(construct_curve(spec), RangeError);
}

TEST_CASE("a composite mixing families: T-Bezier, then an H-Bezier joined G2, then an ellipse arc",
          "[curves][joins]") {
  CurveSpec spec;
  spec.segments = {explicit_tbezier({{0, 0}, {1, 2}, {3, 2.5}, {4, 1}}, -0.5, 0.3)};
  SegmentSpec h;
  h.kind = SegmentKind::HBezier;
  h.alpha = 2.0;
  h.lambda = 0.4;
  h.mu = -1.0;
  h.join = JoinSpec{Continuity::G2, 1.0, 0.0, 0.8, 0.3};  // H-Bezier convention: k = 0.8, m = 0.3
  h.points = {Vec2(9, 0)};
  spec.segments.push_back(h);
  SegmentSpec e;
  e.kind = SegmentKind::EllipseArc;
  e.ellipse.center = Vec2(7, 0);
  e.ellipse.a = 2;
  e.ellipse.b = 1;
  e.ellipse.from_deg = 0;
  e.ellipse.to_deg = -90;  // starts at (9, 0), where the H-Bezier segment ends
  spec.segments.push_back(e);
  const CompositeCurve c = construct_curve(spec);
  REQUIRE(c.segments()[1].kind() == SegmentKind::HBezier);
  const auto joints = c.joints();
  REQUIRE(joints.size() == 2);
  CHECK(joints[0].achieved == Continuity::G2);
  CHECK(joints[0].curvature_jump < 1e-9);
  // Native derivatives: Q'(0) = k P'(end) and Q''(0) = k^2 P''(end) + m P'(end)
  // (docs/math/h-bezier.md "Joining curves").
  const CurveJet p = c.segments()[0].jet(1.0);
  const CurveJet q = c.segments()[1].jet(0.0);
  const double a = c.segments()[1].native_scale();
  CHECK(rel(q[1] / a, 0.8 * p[1]) < 1e-12);
  CHECK(rel(q[2] / (a * a), 0.64 * p[2] + 0.3 * p[1]) < 1e-12);
  CHECK(joints[1].gap < 1e-12);  // the explicit arc starts where the H-Bezier segment ends
}
