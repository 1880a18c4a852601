#include "geometry/mould/master_sectors.h"

#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <cmath>

#include "geometry/core/errors.h"
#include "geometry/mesh/interpenetration.h"
#include "geometry/mesh/volume.h"
#include "geometry/mould/master_sections.h"
#include "geometry/validation/validate.h"

using namespace fabmesh;

namespace {

bool interpenetrate(const TriangleSoup& a, const TriangleSoup& b) {
  return !interpenetrating_pairs({&a, &b}).pairs.empty();
}

TriangleSoup moved(TriangleSoup soup, const Vec3& by) {
  for (Vec3& p : soup.vertices) p += by;
  return soup;
}

// The volume of a prism over the regular n-gon inscribed in a circle of radius r, `length` long.
double polygon_prism(double r, int n, double length) {
  return 0.5 * n * r * r * std::sin(2.0 * M_PI / n) * length;
}

MasterSplitOptions options(int sectors) {
  MasterSplitOptions o;
  o.bed_height = 100.0;
  o.pin_diameter = 4.0;
  o.pin_clearance = 0.2;
  o.segments = 64;
  o.sectors = sectors;
  return o;
}

}  // namespace

TEST_CASE("master sectors: a wide cylinder in halves and quarters, each joint pinned across",
          "[mould][master]") {
  // A solid cylinder of radius 30, 20 tall: one section (the bed is taller), cut through its axis.
  const std::vector<Vec2> loop = {{0, 0}, {30, 0}, {30, 20}, {0, 20}};
  const double cylinder = M_PI * 30 * 30 * 20;
  for (const int sectors : {2, 4}) {
    INFO(sectors << " sectors");
    const MasterSplitOptions o = options(sectors);
    const MasterSplit split = split_master(loop, o);
    REQUIRE(split.sectors == sectors);
    REQUIRE(split.sections.size() == static_cast<std::size_t>(sectors));
    const double pin = M_PI * 2.0 * 2.0 * split.pin_height;
    const double hole = M_PI * split.hole_radius * split.hole_radius * split.hole_depth;
    double exact = 0.0;
    const int steps = 64 / sectors;  // the sweep's angular steps over one sector
    const double wedge = 0.5 * steps * 30 * 30 * std::sin(2.0 * M_PI / sectors / steps) * 20;
    for (std::size_t k = 0; k < split.sections.size(); ++k) {
      const MasterSection& s = split.sections[k];
      INFO(s.name);
      CHECK(s.name == fmt::format("{}-{}", sectors == 2 ? "half" : "quarter", k + 1));
      CHECK(s.sector());
      CHECK(s.to_quadrant - s.from_quadrant == 4 / sectors);
      CHECK_FALSE(s.proof.has_value());  // validated in full
      const ValidationReport full = validate(s.soup);
      CHECK(full.valid());
      REQUIRE(full.genus.has_value());
      CHECK(*full.genus == 0);
      CHECK(full.components == 1);
      // The polygonal sector, its pin's prism added and its hole's taken.
      const double mesh = wedge + polygon_prism(2.0, 24, split.pin_height) -
                          polygon_prism(split.hole_radius, 24, split.hole_depth);
      CHECK(signed_volume(s.soup) == Approx(mesh).epsilon(1e-12));
      CHECK(s.volume == Approx(cylinder / sectors + pin - hole).epsilon(1e-14));
      exact += s.volume;
    }
    CHECK(exact == Approx(cylinder + sectors * (pin - hole)).epsilon(1e-14));
    // Assembled, no two pieces share volume (their caps touch, each pin stands in its hole with the
    // clearance); slid along a joint by more than the clearance, a pin hits its hole's wall.
    for (std::size_t k = 0; k < split.sections.size(); ++k) {
      const TriangleSoup& a = split.sections[k].soup;
      const TriangleSoup& b = split.sections[(k + 1) % split.sections.size()].soup;
      INFO("pieces " << k << " and the next");
      CHECK_FALSE(interpenetrate(a, b));
      CHECK_FALSE(interpenetrate(a, moved(b, {0, 0, 0.1})));
      CHECK(interpenetrate(a, moved(b, {0, 0, 0.5})));
    }
  }
}

TEST_CASE("master sectors: sections both stacked and cut through the axis", "[mould][master]") {
  // A solid cylinder of radius 20, 10 tall, on a bed 4.5 tall with 1 mm pins: 3 sections of 4 quarters.
  const std::vector<Vec2> loop = {{0, 0}, {20, 0}, {20, 10}, {0, 10}};
  MasterSplitOptions o = options(4);
  o.bed_height = 4.5;
  o.pin_diameter = 1.0;
  o.pin_clearance = 0.1;
  const MasterSplit split = split_master(loop, o);
  REQUIRE(split.sections.size() == 12);
  CHECK(split.sections[0].name == "section-1-quarter-1");
  CHECK(split.sections[11].name == "section-3-quarter-4");
  const double pin = M_PI * 0.25 * split.pin_height;
  const double hole = M_PI * split.hole_radius * split.hole_radius * split.hole_depth;
  double exact = 0.0;
  for (const MasterSection& s : split.sections) {
    INFO(s.name);
    const ValidationReport full = validate(s.soup);
    CHECK(full.valid());
    CHECK(full.components == 1);
    // Standing on its bottom with the axis pin's quarter on top, it fits the bed.
    CHECK(s.z_high + (s.pin ? split.pin_height : 0.0) - s.z_low <= o.bed_height);
    exact += s.volume;
  }
  // The master, each horizontal joint's pin less its hole, each axial joint's (4 in each of 3 sections).
  CHECK(exact == Approx(M_PI * 400 * 10 + 2 * (pin - hole) + 12 * (pin - hole)).epsilon(1e-13));
  // The quarters of the axis pin glued back are the pin: the lower section's quarters fill the upper's holes.
  for (std::size_t k = 0; k < 4; ++k) {
    for (std::size_t l = 4; l < 8; ++l)
      CHECK_FALSE(interpenetrate(split.sections[k].soup, split.sections[l].soup));
  }
}

TEST_CASE("master sectors: a master too thin for a joint's pin is refused at pin_diameter",
          "[mould][master]") {
  // Radius 6 with 4 mm pins: the hole (radius 2.2, 4.2 deep) cannot keep 2 mm of material all round.
  const std::vector<Vec2> loop = {{0, 0}, {6, 0}, {6, 40}, {0, 40}};
  try {
    split_master(loop, options(4));
    FAIL("accepted");
  } catch (const GeometryError& e) {
    CHECK(e.where() == "print.pin_diameter");
    CHECK_THAT(std::string(e.what()),
               Catch::Contains("no place on its cut faces for the pin of an axial joint"));
  }
}

TEST_CASE("master sectors: a master no taller than the bed is cut only through its axis", "[mould][master]") {
  // 10 tall on a bed 10.5 tall with 1 mm pins: one section (no joint above it needs a pin), in halves.
  const std::vector<Vec2> loop = {{0, 0}, {20, 0}, {20, 10}, {0, 10}};
  MasterSplitOptions o = options(2);
  o.bed_height = 10.5;
  o.pin_diameter = 1.0;
  const MasterSplit split = split_master(loop, o);
  CHECK(split.cuts.empty());
  REQUIRE(split.sections.size() == 2);
  for (const MasterSection& s : split.sections) {
    CHECK_FALSE(s.pin);
    CHECK_FALSE(s.hole);
    CHECK(s.z_high - s.z_low == 10.0);
  }
}
