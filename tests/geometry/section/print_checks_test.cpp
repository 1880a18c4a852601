#include "geometry/section/print_checks.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "geometry/core/errors.h"

using namespace fabmesh;

namespace {

constexpr double kDeg = 180.0 / 3.14159265358979323846;

CompositeCurve lines(const std::vector<Vec2>& points) {
  std::vector<Segment> segments;
  for (std::size_t i = 0; i + 1 < points.size(); ++i)
    segments.push_back(Segment::line(points[i], points[i + 1]));
  return CompositeCurve(std::move(segments), false);
}

VesselSection section_of(const CompositeCurve& profile, BodyMode mode = BodyMode::Solid, double wall = 0.0,
                         double base = 0.0) {
  VesselSectionOptions o;
  o.mode = mode;
  o.wall = wall;
  o.base = base;
  o.tolerance = 1e-3;
  return build_vessel_section(profile, o);
}

PrintCheck check(const CompositeCurve& profile, const VesselSection& section, PrintOptions o = {}) {
  return check_print(profile, section, o);
}

}  // namespace

TEST_CASE("a straight flare overhangs atan(dr/dz) from the bed up, its ledge the whole flare", "[print]") {
  // A solid cone frustum flaring out from r 10 at the bed to r 30 at z 10: 63.43 degrees from vertical.
  const CompositeCurve p = lines({{10, 0}, {30, 10}});
  const PrintCheck c = check(p, section_of(p));
  CHECK(c.outer.angle_deg == Approx(std::atan2(20.0, 10.0) * kDeg).epsilon(1e-12));
  CHECK_FALSE(c.inner);
  CHECK_FALSE(c.rim);
  REQUIRE(c.runs.size() == 1);
  CHECK(c.runs[0].face == PrintFace::Outer);
  CHECK(c.runs[0].width == Approx(20.0).epsilon(1e-9));
  CHECK(c.runs[0].to.y() == Approx(10.0));
  REQUIRE(c.widest_ledge == std::size_t{0});
  CHECK(std::isnan(c.min_wall));  // a solid has no wall
  CHECK(c.size.x() == Approx(60.0));
  CHECK(c.size.z() == Approx(10.0));
  REQUIRE(c.findings.size() == 1);
  CHECK(c.findings[0].key == "print.max_overhang_deg");
  CHECK_THAT(c.findings[0].message, Catch::Contains("63.43 degrees"));

  // Steeper than the flare's lean, the limit finds nothing (the runs are the stretches beyond it).
  PrintOptions lenient;
  lenient.max_overhang_deg = 64.0;
  CHECK(check(p, section_of(p), lenient).runs.empty());
  CHECK(check(p, section_of(p), lenient).findings.empty());
}

TEST_CASE("a cylinder and a vessel narrowing upward do not overhang outside", "[print]") {
  const CompositeCurve cylinder = lines({{10, 0}, {10, 20}});
  const PrintCheck c = check(cylinder, section_of(cylinder));
  CHECK(c.outer.angle_deg == 0.0);
  CHECK(c.runs.empty());
  CHECK(c.findings.empty());
  const CompositeCurve narrowing = lines({{20, 0}, {10, 20}});
  CHECK(check(narrowing, section_of(narrowing)).outer.angle_deg == 0.0);
}

TEST_CASE("a sphere's lower half overhangs up to the 45-degree latitude, a ledge of r sin 45", "[print]") {
  // An exact circle from the bottom pole to the top pole, radius 10 about (0, 10).
  EllipseArcParams arc;
  arc.center = Vec2(0.0, 10.0);
  arc.a = arc.b = 10.0;
  arc.from_deg = -90.0;
  arc.to_deg = 90.0;
  const CompositeCurve sphere({Segment::ellipse_arc(arc)}, false);
  const PrintCheck c = check(sphere, section_of(sphere));
  REQUIRE(c.runs.size() == 1);
  // From the bed (where the face turns horizontal) to where it leans 45 degrees. Places within 1e-12 of
  // the height of the lowest one stand on the bed: a sphere touches it at a point, so within ~sqrt(2 R 1e-12
  // H) in r.
  CHECK(c.runs[0].from.x() == Approx(0.0).margin(1e-4));
  CHECK(c.runs[0].to.x() == Approx(10.0 * std::sqrt(0.5)).epsilon(1e-9));
  CHECK(c.runs[0].to.y() == Approx(10.0 - 10.0 * std::sqrt(0.5)).epsilon(1e-9));
  CHECK(c.runs[0].width == Approx(10.0 * std::sqrt(0.5) - c.runs[0].from.x()).epsilon(1e-9));
  CHECK(c.outer.angle_deg > 89.9);  // approaching a ceiling next to the bed
  CHECK(c.size.x() == Approx(20.0).epsilon(1e-12));
  CHECK(c.size.z() == Approx(20.0).epsilon(1e-12));
}

TEST_CASE("a shell's inner wall overhangs where the vessel narrows upward", "[print]") {
  // Leaning in by 10 over 20: the inner face leans atan(1/2) from vertical, over the whole inner wall.
  const CompositeCurve p = lines({{20, 0}, {10, 20}});
  const VesselSection s = section_of(p, BodyMode::Shell, 2.0, 3.0);
  PrintOptions o;
  o.max_overhang_deg = 20.0;
  o.min_wall = 2.5;
  o.bed = Vec3(100, 100, 15);
  const PrintCheck c = check(p, s, o);
  CHECK(c.outer.angle_deg == 0.0);
  REQUIRE(c.inner);
  CHECK(c.inner->angle_deg == Approx(std::atan(0.5) * kDeg).epsilon(1e-12));
  REQUIRE(c.runs.size() == 1);
  CHECK(c.runs[0].face == PrintFace::Inner);
  // The inner wall runs from the square rim's inner edge (2 along the normal from (10, 20)) down to the base
  // at z 3.
  const Vec2 normal = Vec2(-20.0, -10.0) / std::sqrt(500.0);
  const Vec2 inner_top = Vec2(10, 20) + 2.0 * normal;
  CHECK(c.runs[0].from.x() == Approx(inner_top.x()).epsilon(1e-9));
  CHECK(c.runs[0].to.y() == Approx(3.0).epsilon(1e-9));
  CHECK(c.runs[0].width == Approx(0.5 * (inner_top.y() - 3.0)).epsilon(1e-9));
  // The thinnest wall, normal to the walls: the 2 of the wall (the base is 3).
  CHECK(c.min_wall == Approx(2.0).epsilon(1e-6));
  // Everything found, each at its key: overhang, wall, bed (20 tall on a 15 bed).
  REQUIRE(c.findings.size() == 3);
  CHECK(c.findings[0].key == "print.max_overhang_deg");
  CHECK_THAT(c.findings[0].message, Catch::Contains("inner wall"));
  CHECK(c.findings[1].key == "print.min_wall");
  CHECK(c.findings[2].key == "print.bed");
  CHECK(c.fits_bed == false);
  o.bed = Vec3(41, 41, 21);
  CHECK(check(p, s, o).fits_bed == true);
  o.bed = Vec3(39.9, 41, 21);  // 40 across
  CHECK(check(p, s, o).fits_bed == false);
}

TEST_CASE("a rim that turns down overhangs at its square cut", "[print]") {
  // Up, then out and down: the rim's face, square to a profile heading down, looks down.
  const CompositeCurve p = lines({{10, 0}, {10, 20}, {14, 24}, {18, 20}});
  const VesselSection s = section_of(p, BodyMode::Shell, 1.0, 1.0);
  const PrintCheck c = check(p, s);
  REQUIRE(c.rim);
  CHECK(c.rim->angle_deg == Approx(45.0).epsilon(1e-9));
  CHECK(c.outer.angle_deg == Approx(45.0).epsilon(1e-9));  // the up-and-out leg
}

TEST_CASE("print options out of range are refused", "[print]") {
  const CompositeCurve p = lines({{10, 0}, {10, 20}});
  const VesselSection s = section_of(p);
  PrintOptions o;
  o.max_overhang_deg = 90.0;
  CHECK_THROWS_AS(check(p, s, o), RangeError);
  o = {};
  o.min_wall = 0.0;
  CHECK_THROWS_AS(check(p, s, o), RangeError);
  o = {};
  o.bed = Vec3(100, 0, 100);
  CHECK_THROWS_AS(check(p, s, o), RangeError);
}
