#include "geometry/section/vessel_section.h"

#include <fmt/format.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "geometry/core/errors.h"
#include "geometry/curves/curve_spec.h"
#include "geometry/sampling/offset_curve.h"

using namespace fabmesh;

namespace {

CompositeCurve profile(std::vector<Vec2> points, std::vector<double> lambdas = {}) {
  CurveSpec spec;
  spec.family = CurveFamily::QuasiBSpline;
  spec.bspline_points = std::move(points);
  spec.bspline_lambdas = std::move(lambdas);
  return construct_curve(spec);
}

CompositeCurve golden() { return profile({{1.5, 6}, {1, 5}, {2, 4}, {3, 3}, {1.5, 2}}); }

double distance_to_loop(const Vec2& p, const std::vector<Vec2>& loop) {
  double best = INFINITY;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Vec2 a = loop[i], b = loop[(i + 1) % loop.size()], ab = b - a;
    const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (a + t * ab - p).norm());
  }
  return best;
}

VesselSectionOptions shell(double wall, double base, double tolerance) {
  VesselSectionOptions o;
  o.mode = BodyMode::Shell;
  o.wall = wall;
  o.base = base;
  o.tolerance = tolerance;
  return o;
}

}  // namespace

TEST_CASE("vessel section: every exact point of the outer and inner walls is within the reported bound",
          "[section][vessel]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> lambda(-3.0, 1.0);
  for (int trial = 0; trial < 8; ++trial) {
    const CompositeCurve p = trial == 0 ? golden()
                                        : profile({{1.5, 6}, {1, 5}, {2, 4}, {3, 3}, {1.5, 2}},
                                                  {lambda(rng), lambda(rng), lambda(rng)});
    for (double tol : {0.005, 0.0005}) {
      const VesselSectionOptions o = shell(0.15, 0.4, tol);
      VesselSection s;
      try {
        s = build_vessel_section(p, o);
      } catch (const GeometryError&) {
        continue;  // a wall too thick for these lambdas
      }
      CHECK(s.max_deviation <= tol);
      const double base_plane = 2.0 + 0.4;
      double worst = 0.0;
      for (const Segment& seg : p.segments()) {
        for (int i = 0; i <= 400; ++i) {
          const double t = i / 400.0;
          worst = std::max(worst, distance_to_loop(seg.point(t), s.loops[0]));
          const Vec2 inner = offset_jet(seg, {0.15, -1.0, "wall", ""}, t).point;  // the profile runs downward
          if (inner.y() > base_plane) worst = std::max(worst, distance_to_loop(inner, s.loops[0]));
        }
      }
      INFO("trial " << trial << ", tolerance " << tol);
      CHECK(worst <= s.max_deviation);
      CHECK(s.min_clearance <= 0.15);
      CHECK(s.min_clearance >= 0.15 - 1e-3 * tol - 1e-12);
    }
  }
}

TEST_CASE("vessel section: a base that leaves no cavity is refused, naming the base and the height available",
          "[section][vessel][errors]") {
  for (double base : {5.0, 100.0, 4.2}) {
    INFO("base " << base);
    try {
      build_vessel_section(golden(), shell(0.3, base, 0.0025));
      FAIL("a base taller than the vessel was accepted");
    } catch (const GeometryError& e) {
      CHECK(e.where() == "base");
      CHECK_THAT(std::string(e.what()), Catch::Contains(fmt::format("base {} leaves no cavity", base)) &&
                                            Catch::Contains("rises only 4.13416"));
    }
  }
  // Just below the height available: a shallow cavity, every point within the vessel's own extent.
  const VesselSection s = build_vessel_section(golden(), shell(0.3, 4.1, 0.0025));
  for (const Vec2& q : s.loops[0]) {
    CHECK(q.y() >= 2.0);
    CHECK(q.y() <= 6.135);
    CHECK(q.x() <= 2.6);
  }
}

TEST_CASE("vessel section: a level rim ends on the profile's height, a square one across the wall",
          "[section][vessel]") {
  VesselSectionOptions o = shell(0.3, 0.4, 0.0025);
  double square_top = -INFINITY, level_top = -INFINITY;
  const VesselSection square = build_vessel_section(golden(), o);
  for (const Vec2& q : square.loops[0]) square_top = std::max(square_top, q.y());
  o.rim = RimCut::Level;
  const VesselSection level = build_vessel_section(golden(), o);
  for (const Vec2& q : level.loops[0]) level_top = std::max(level_top, q.y());
  CHECK(square_top == Approx(6.134164).margin(1e-5));
  CHECK(level_top == 6.0);
  std::size_t at_top = 0;
  for (const Vec2& q : level.loops[0]) at_top += q.y() == 6.0 ? 1 : 0;
  CHECK(at_top == 2);  // the rim is one horizontal edge
  // A profile closing in at the rim: the inner wall continues along its tangent up to the rim height.
  o.wall = 0.2;
  const VesselSection closing =
      build_vessel_section(profile({{1.0, 6}, {2, 5}, {2.5, 4}, {2, 2.5}, {1.5, 2}}), o);
  double top = -INFINITY;
  for (const Vec2& q : closing.loops[0]) top = std::max(top, q.y());
  CHECK(top == 6.0);
}

TEST_CASE("vessel section: exact walls closer than the tolerance are refused", "[section][vessel][errors]") {
  // A wall thinner than the tolerance: the inner and outer surfaces are closer than it everywhere.
  CHECK_THROWS_WITH(build_vessel_section(golden(), shell(0.001, 0.4, 0.0025)),
                    Catch::Contains("the mesh is built within"));
}

TEST_CASE("vessel section: vertices crowding the axis are moved out to the axis clearance, within the bound",
          "[section][vessel]") {
  // The platter of tracker issue 23, in cm: its profile leaves the axis
  // tangent to it, so its first samples lie micrometres from the axis.
  const CompositeCurve p = profile({{0, 0}, {0, 3.5}, {4, 4.5}, {11, 2}, {15, 1.5}, {17, 2.2}});
  {
    VesselSectionOptions o = shell(0.25, 0.25, 0.0025);
    const VesselSection plain = build_vessel_section(p, o);
    double nearest = INFINITY;
    for (const Vec2& q : plain.loops[0]) {
      if (q.x() > 0.0) nearest = std::min(nearest, q.x());
    }
    REQUIRE(nearest < 1e-4);  // the crowding the clearance removes
    o.axis_clearance = 0.0005;
    const VesselSection cleared = build_vessel_section(p, o);
    REQUIRE(cleared.loops.size() == plain.loops.size());
    REQUIRE(cleared.loops[0].size() == plain.loops[0].size());  // the same vertices, moved
    for (const Vec2& q : cleared.loops[0]) CHECK((q.x() == 0.0 || q.x() >= 0.0005));
    CHECK(cleared.max_deviation <= plain.max_deviation + 0.0005);
    CHECK(cleared.max_deviation > plain.max_deviation);
    double worst = 0.0;
    for (const Segment& seg : p.segments()) {
      for (int i = 0; i <= 2000; ++i)
        worst = std::max(worst, distance_to_loop(seg.point(i / 2000.0), cleared.loops[0]));
    }
    CHECK(worst <= cleared.max_deviation);
  }
}
