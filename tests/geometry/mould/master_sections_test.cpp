#include "geometry/mould/master_sections.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "geometry/core/errors.h"
#include "geometry/mesh/volume.h"
#include "geometry/validation/validate.h"

using namespace fabmesh;

namespace {

// The volume of a revolution of a polygon in n uniform steps: each height's
// slice is the n-gon inscribed in the exact circle, n sin(2 pi / n) / (2 pi)
// of its area.
double inscribed_factor(int n) { return n * std::sin(2.0 * M_PI / n) / (2.0 * M_PI); }

// split_master refuses `loop`: a GeometryError at `where` whose message says `says`.
void refused(const std::vector<Vec2>& loop, const MasterSplitOptions& o, const char* accepted,
             const std::string& where, const std::string& says) {
  try {
    split_master(loop, o);
    FAIL(accepted);
  } catch (const GeometryError& e) {
    CHECK(e.where() == where);
    CHECK_THAT(std::string(e.what()), Catch::Contains(says));
  }
}

}  // namespace

TEST_CASE("master sections: a cylinder taller than the bed in three sections with pins and holes",
          "[mould][master]") {
  // A solid cylinder of radius 3, 10 tall, on a bed 4.5 tall with 1 mm pins: 10 / (4.5 - 1) -> 3 sections.
  const std::vector<Vec2> loop = {{0, 0}, {3, 0}, {3, 10}, {0, 10}};
  MasterSplitOptions o;
  o.bed_height = 4.5;
  o.pin_diameter = 1.0;
  o.pin_clearance = 0.1;
  o.segments = 48;
  const MasterSplit split = split_master(loop, o);
  REQUIRE(split.sections.size() == 3);
  REQUIRE(split.cuts.size() == 2);
  CHECK(split.cuts[0] == Approx(10.0 / 3.0).epsilon(1e-12));
  CHECK(split.cuts[1] == Approx(20.0 / 3.0).epsilon(1e-12));
  CHECK(split.hole_radius == Approx(0.6));
  CHECK(split.hole_depth == Approx(1.1));
  double exact = 0.0;
  for (const MasterSection& s : split.sections) {
    INFO(s.name);
    CHECK(s.pin == (&s != &split.sections.back()));
    CHECK(s.hole == (&s != &split.sections.front()));
    // Standing on its bottom with its pin on top, it fits the bed.
    const double top = s.z_high + (s.pin ? split.pin_height : 0.0);
    CHECK(top - s.z_low <= o.bed_height);
    const ValidationReport full = validate(s.soup);  // the full 3D test, not the proof
    CHECK(full.valid());
    REQUIRE(full.genus.has_value());
    CHECK(*full.genus == 0);
    CHECK(signed_volume(s.soup) == Approx(inscribed_factor(o.segments) * s.volume).epsilon(1e-9));
    exact += s.volume;
  }
  // Together: the cylinder, plus each joint's pin, minus its hole.
  const double pin = M_PI * 0.25 * 1.0, hole = M_PI * 0.36 * 1.1;
  CHECK(exact == Approx(M_PI * 9.0 * 10.0 + 2.0 * (pin - hole)).epsilon(1e-12));
  // Each pin clears its hole by the clearance: the radius and the depth.
  const MasterSection& lower = split.sections[0];
  const MasterSection& upper = split.sections[1];
  double pin_r = 0.0, pin_top = 0.0, hole_r = 0.0, hole_top = 0.0;
  for (const Vec2& p : lower.loop) {
    if (p.y() > lower.z_high) {
      pin_r = std::max(pin_r, p.x());
      pin_top = std::max(pin_top, p.y());
    }
  }
  for (const Vec2& p : upper.loop) {
    if (p.x() < 1.0 && p.y() > upper.z_low) {
      hole_r = std::max(hole_r, p.x());
      hole_top = std::max(hole_top, p.y() < upper.z_high ? p.y() : 0.0);
    }
  }
  CHECK(hole_r - pin_r == Approx(0.1));
  CHECK(hole_top - pin_top == Approx(0.1));
}

TEST_CASE("master sections: a master that fits the bed stays whole", "[mould][master]") {
  MasterSplitOptions o;
  o.bed_height = 11.0;
  o.pin_diameter = 1.0;
  const MasterSplit split = split_master({{0, 0}, {3, 0}, {3, 10}, {0, 10}}, o);
  REQUIRE(split.sections.size() == 1);
  CHECK(split.cuts.empty());
  CHECK_FALSE(split.sections[0].pin);
  CHECK_FALSE(split.sections[0].hole);
}

TEST_CASE("master sections: bad beds, pins and cuts are refused naming the key", "[mould][master]") {
  const std::vector<Vec2> cylinder = {{0, 0}, {3, 0}, {3, 10}, {0, 10}};
  MasterSplitOptions o;
  o.pin_diameter = 1.0;
  SECTION("a bed no taller than the pin") {
    o.bed_height = 1.0;
    try {
      split_master(cylinder, o);
      FAIL("a bed shorter than a pin was accepted");
    } catch (const RangeError& e) {
      CHECK(e.field() == "print.bed");
    }
  }
  SECTION("a bed barely taller than the pin: more sections than any printer needs") {
    o.bed_height = 1.0 + 1e-9;
    refused(cylinder, o, "a billion sections were attempted", "print.bed", "fabmesh makes at most 100");
  }
  SECTION("a pin wider than the master at a cut") {
    // The hole's radius 1.3 + 0.5 and its wall 1.3 need 3.1 of the cylinder's 3.
    o.bed_height = 9.0;  // two sections of 5
    o.pin_diameter = 2.6;
    o.pin_clearance = 0.5;
    refused(cylinder, o, "a hole wider than the master's wall was accepted", "print.pin_diameter",
            "too narrow");
  }
  SECTION("a cut crossing the profile three times") {
    // Out to (4, 5), back in and down to (3, 2), then up to the rim (2, 10): z in (2, 5) is crossed thrice.
    o.bed_height = 4.0;  // 10 / 3 -> 4 sections, a cut at z = 2.5
    refused({{0, 0}, {4, 0}, {4, 5}, {3, 2}, {2, 10}, {0, 10}}, o, "a section that falls apart was accepted",
            "print.bed", "crosses the master's profile 3 times");
  }
  SECTION("a neck above the cut too close to the hole") {
    // Radius 3 at the cut z = 5, but the neck of radius 1 starts 0.6 above it: the hole (radius 0.6,
    // 1.1 deep) would leave 0.4 of wall, less than the pin's radius 0.5.
    o.bed_height = 6.0;
    o.pin_clearance = 0.1;
    refused({{0, 0}, {3, 0}, {3, 5.2}, {1, 5.6}, {1, 10}, {0, 10}}, o,
            "a hole breaking through the neck was accepted", "print.pin_diameter", "comes within 0.4");
  }
}
