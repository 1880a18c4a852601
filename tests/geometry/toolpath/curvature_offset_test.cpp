// The proven curvature bound and the proven chord bound of offsets, against
// dense evaluation of the exact curves.

#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "geometry/toolpath/curvature_bound.h"
#include "geometry/toolpath/offset_segment.h"

using namespace fabmesh;

namespace {

// Segments of every family with some curvature of both signs.
std::vector<Segment> test_segments() {
  std::vector<Segment> out;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coord(-100.0, 100.0), shape(-2.0, 1.0);
  for (int i = 0; i < 6; ++i) {
    std::array<Vec2, 4> p{Vec2(coord(rng), coord(rng)), Vec2(coord(rng), coord(rng)),
                          Vec2(coord(rng), coord(rng)), Vec2(coord(rng), coord(rng))};
    out.push_back(Segment::tbezier(p, shape(rng), shape(rng)));
  }
  out.push_back(Segment::hbezier({Vec2(0, 0), Vec2(40, 60), Vec2(90, -30), Vec2(130, 20)}, 1.5, 0.3, -0.2));
  out.push_back(
      Segment::quasi_bspline_span({Vec2(0, 0), Vec2(50, 40), Vec2(100, -10), Vec2(150, 30)}, -3.0, 0.5));
  EllipseArcParams e;
  e.center = Vec2(10, 20);
  e.a = 80;
  e.b = 30;
  e.rotation_deg = 25;
  e.from_deg = -40;
  e.to_deg = 200;
  out.push_back(Segment::ellipse_arc(e));
  e.from_deg = 300;
  e.to_deg = 100;  // clockwise
  out.push_back(Segment::ellipse_arc(e));
  return out;
}

double curvature(const Segment& s, double t) {
  const CurveJet j = s.jet(t);
  return cross2(j[1], j[2]) / std::pow(j[1].norm(), 3);
}

}  // namespace

TEST_CASE(
    "least_curvature: the proven bound lies below every dense sample and is attained within the precision",
    "[geometry][toolpath][curvature]") {
  const double precision = 1e-7;
  for (const Segment& seg : test_segments()) {
    for (double sign : {1.0, -1.0}) {
      INFO(to_string(seg.kind()) << " sign " << sign);
      const CurvatureBound b = least_curvature(seg, sign, precision);
      double dense = INFINITY;
      for (int i = 0; i <= 20000; ++i) dense = std::min(dense, sign * curvature(seg, i / 20000.0));
      CHECK(b.least <= dense + 1e-15);
      CHECK(b.attained <= dense + precision);
      CHECK(b.attained >= b.least);
      CHECK(sign * curvature(seg, b.s) == Approx(b.attained).epsilon(1e-9));
    }
  }
}

TEST_CASE("least_curvature: lines are flat, circles exact", "[geometry][toolpath][curvature]") {
  CHECK(least_curvature(Segment::line({0, 0}, {3, 4}), 1.0, 1e-9).least == 0.0);
  EllipseArcParams c;
  c.a = c.b = 8;
  c.from_deg = 90;
  c.to_deg = -90;
  const CurvatureBound b = least_curvature(Segment::ellipse_arc(c), 1.0, 1e-9);
  CHECK(b.least == Approx(-1.0 / 8));  // clockwise: turning right
  CHECK(least_curvature(Segment::ellipse_arc(c), -1.0, 1e-9).least == Approx(1.0 / 8));
}

TEST_CASE("offset_segment: chords stay within their proven bound of the exact offset, ends on it",
          "[geometry][toolpath][offset]") {
  const double r = 6.0;
  int tested = 0;
  for (const Segment& seg : test_segments()) {
    for (bool reversed : {false, true}) {
      const double sign = reversed ? -1.0 : 1.0;
      // Offsets exist where the tool fits: skip segments curving away tighter than r.
      if (least_curvature(seg, sign, 1e-9).least < -1.0 / r) continue;
      INFO(to_string(seg.kind()) << (reversed ? " reversed" : ""));
      ++tested;
      SegmentOffsetOptions o;
      o.radius = r;
      o.tolerance = 0.01;
      double achieved = 0.0;
      const std::vector<PathPiece> chain = offset_segment(seg, reversed, 3, o, &achieved);
      CHECK(achieved <= o.tolerance);
      CHECK(chain.front().from.isApprox(exact_offset_point(seg, reversed, r, reversed ? 1.0 : 0.0), 1e-12));
      CHECK(chain.back().to.isApprox(exact_offset_point(seg, reversed, r, reversed ? 0.0 : 1.0), 1e-12));
      // Every chord point is within `achieved` of the exact offset: the exact offset near it
      // is the level set {distance to the curve = r}, found by Newton on the segment.
      double worst = 0.0;
      for (const PathPiece& p : chain) {
        CHECK(p.segment == 3);
        for (int k = 1; k < 8; ++k) {
          const Vec2 q = piece_point(p, piece_length(p) * k / 8.0);
          double best = INFINITY;
          for (int i = 0; i <= 10; ++i) {  // seeds every tenth of the segment
            double s = i / 10.0;
            for (int it = 0; it < 30; ++it) {
              const CurveJet j = seg.jet(s);
              const double f = (j[0] - q).dot(j[1]), fp = j[1].squaredNorm() + (j[0] - q).dot(j[2]);
              s = std::clamp(s - f / fp, 0.0, 1.0);
            }
            best = std::min(best, (seg.point(s) - q).norm());
          }
          worst = std::max(worst, std::abs(best - r));
        }
      }
      CHECK(worst <= achieved + 1e-9);
    }
  }
  CHECK(tested >= 8);
}

TEST_CASE("offset_segment: circle arcs give arcs of radius R + r turning left, R - r turning right",
          "[geometry][toolpath][offset]") {
  EllipseArcParams c;
  c.center = Vec2(5, -3);
  c.a = c.b = 20;
  c.from_deg = 0;
  c.to_deg = 120;
  const Segment arc = Segment::ellipse_arc(c);
  SegmentOffsetOptions o;
  o.radius = 6;
  const auto left = offset_segment(arc, false, 0, o);
  REQUIRE(left.size() == 1);
  CHECK(left[0].kind == PieceKind::Arc);
  CHECK(piece_radius(left[0]) == Approx(26));
  CHECK(left[0].sweep == Approx(2 * M_PI / 3));
  const auto right = offset_segment(arc, true, 0, o);
  CHECK(piece_radius(right[0]) == Approx(14));
  CHECK(right[0].sweep == Approx(-2 * M_PI / 3));
  CHECK(right[0].from.isApprox(c.center + 14.0 * Vec2(std::cos(2 * M_PI / 3), std::sin(2 * M_PI / 3))));
  const auto line = offset_segment(Segment::line({0, 0}, {10, 0}), false, 0, o);
  REQUIRE(line.size() == 1);
  CHECK(line[0].from.isApprox(Vec2(0, -6)));
  CHECK(line[0].to.isApprox(Vec2(10, -6)));
}
