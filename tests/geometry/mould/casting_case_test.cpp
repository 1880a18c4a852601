#include "geometry/mould/casting_case.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "geometry/core/errors.h"
#include "geometry/mesh/bounding_box.h"
#include "geometry/mesh/interpenetration.h"
#include "geometry/mesh/volume.h"
#include "geometry/mould/mould.h"
#include "geometry/validation/validate.h"
#include "tests/geometry/mould/mould_fixtures.h"

using namespace fabmesh;
using namespace fabmesh::test;

namespace {

// The outward direction of a mould part: its bisector for a side part, down for the base.
Vec3 outward_of(const MouldPart& p) {
  if (p.kind == MouldPartKind::Base) return {0.0, 0.0, -1.0};
  const double mid = 0.5 * (p.from_angle + p.to_angle);
  return {std::cos(mid), std::sin(mid), 0.0};
}

TriangleSoup moved(TriangleSoup soup, const Vec3& by) {
  for (Vec3& p : soup.vertices) p += by;
  return soup;
}

bool interpenetrate(const TriangleSoup& a, const TriangleSoup& b) {
  return !interpenetrating_pairs({&a, &b}).pairs.empty();
}

// A case in the fixtures' centimetres: walls 0.5, pins' clearance 0.02.
CaseOptions case_options(double wall = 0.5, double clearance = 0.02) {
  CaseOptions o;
  o.wall = wall;
  o.clearance = clearance;
  o.tolerance = cm_options().tolerance;
  return o;
}

// The soup turned half a turn about the vertical axis through `centre`.
TriangleSoup half_turned(TriangleSoup soup, const Vec3& centre) {
  for (Vec3& p : soup.vertices) p = Vec3(2.0 * centre.x() - p.x(), 2.0 * centre.y() - p.y(), p.z());
  return soup;
}

// The area of a regular polygon of `sides` sides inscribed in a circle of `radius`.
double polygon_area(double radius, std::size_t sides) {
  const double n = static_cast<double>(sides);
  return 0.5 * n * radius * radius * std::sin(2.0 * M_PI / n);
}

MouldOptions box_options(int parts, int keys, bool base) {
  MouldOptions o = cm_options();
  o.block = BlockShape::Box;
  o.parts = parts;
  o.keys = keys;
  o.base_part = base;
  if (parts == 3) o.key_clearance = 0.1;
  return o;
}

// A carved case: every piece a valid solid with two pins, together filling
// the case's box less the part, plus the pins standing out of the pieces,
// less their holes.
void check_pieces_fill_box(const CastingCase& c, const TriangleSoup& part, const CaseOptions& options) {
  const ValidationReport main = validate(c.soup);
  CHECK(main.valid());
  CHECK(main.components == 1);  // one body: nothing loose inside the part
  double pieces = main.volume, pins = 0.0;
  for (const CasePlate& p : c.plates) {
    INFO(p.face);
    const ValidationReport v = validate(p.soup);
    CHECK(v.valid());
    CHECK(v.components == 1);
    pieces += v.volume;
    REQUIRE(p.pins.size() == 2);
    for (const CasePin& pin : p.pins) {
      pins += polygon_area(pin.radius, pin.sides) * pin.height -
              polygon_area(pin.hole_radius, pin.sides) * pin.hole_depth;
    }
  }
  // The part as the case casts it: less what its draft leans off.
  const double expected = (c.hi - c.lo).prod() - (signed_volume(part) - c.draft_volume) + pins;
  CHECK(pieces == Approx(expected).margin(1e-3 * polygon_area(options.wall / 4.0, 8)));
}

// Taken off in order, each piece of a carved case clears what is left as
// soon as it moves (a slanted seam's points are rounded to doubles, so
// assembled the pieces may cross by a rounding, which the volumes bound),
// and not the other way; then the part leaves the main piece along the
// pull, and not against it.
void check_pieces_come_off(const CastingCase& c, const TriangleSoup& part) {
  for (std::size_t i = 0; i < c.plates.size(); ++i) {
    INFO(c.plates[i].face);
    std::vector<const TriangleSoup*> left{&part, &c.soup};
    for (std::size_t j = i + 1; j < c.plates.size(); ++j) left.push_back(&c.plates[j].soup);
    for (double by : {1e-6, 0.05}) {
      const TriangleSoup off = moved(c.plates[i].soup, by * c.plates[i].pull);
      for (const TriangleSoup* other : left) CHECK_FALSE(interpenetrate(off, *other));
    }
    CHECK(interpenetrate(moved(c.plates[i].soup, -0.05 * c.plates[i].pull), part));
  }
  CHECK_FALSE(interpenetrate(moved(part, 1e-6 * c.pull), c.soup));
  CHECK_FALSE(interpenetrate(moved(part, 0.3 * c.pull), c.soup));
  CHECK(interpenetrate(moved(part, -0.3 * c.pull), c.soup));
}

}  // namespace

TEST_CASE("casting case: each part of a two-part box mould has a valid case whose cavity is the part",
          "[mould][case]") {
  const CompositeCurve profile = example_profile("vessel_golden_solid.yaml");
  const Mould mould = build_mould(profile, box_options(2, 2, false));
  REQUIRE(mould.parts.size() == 2);
  for (const MouldPart& part : mould.parts) {
    INFO(part.name);
    const CastingCase c = build_casting_case(part.soup, part.name, outward_of(part), case_options());
    // Side 1 lies on +y of the split plane y = 0, side 2 on -y: each pours through its back.
    CHECK(c.pull == outward_of(part).array().round().matrix());
    const ValidationReport v = validate(c.soup);
    CHECK(v.valid());
    REQUIRE(v.genus);
    CHECK(*v.genus == 0);
    // Its surface is the box's and the part's: its volume is the box's less the part's.
    const Vec3 size = c.hi - c.lo;
    const double part_volume = signed_volume(part.soup);
    CHECK(v.volume == Approx(size.prod() - part_volume).epsilon(1e-10));
    const BoundingBox pb = bounding_box(part.soup.vertices);
    CHECK(c.pour_area == Approx((pb.hi - pb.lo).prod() / (pb.hi - pb.lo).dot(c.pull.cwiseAbs())));
    // The walls are 0.5 thick on every side but the opening.
    CHECK(bounding_box(c.soup.vertices).lo == c.lo);
    CHECK(bounding_box(c.soup.vertices).hi == c.hi);
    for (int k = 0; k < 3; ++k) {
      CHECK(pb.lo[k] - c.lo[k] == Approx(c.pull[k] < 0.0 ? 0.0 : 0.5).margin(1e-12));
      CHECK(c.hi[k] - pb.hi[k] == Approx(c.pull[k] > 0.0 ? 0.0 : 0.5).margin(1e-12));
    }
    // The part sits in its case without overlap; pulled out along the pull it
    // clears the case, pushed the other way or sideways it runs into it.
    CHECK_FALSE(interpenetrate(part.soup, c.soup));
    CHECK_FALSE(interpenetrate(moved(part.soup, 0.3 * c.pull), c.soup));
    CHECK_FALSE(interpenetrate(moved(part.soup, 3.0 * c.pull), c.soup));
    CHECK(interpenetrate(moved(part.soup, -0.3 * c.pull), c.soup));
    CHECK(interpenetrate(moved(part.soup, Vec3(0.3, 0.0, 0.0)), c.soup));
    CHECK(c.release_proof.find("leaves its case along") != std::string::npos);
  }
}

TEST_CASE("casting case: a box mould's base part pours through its bottom, pulled down off the keys",
          "[mould][case]") {
  const CompositeCurve profile = example_profile("vessel_golden_solid.yaml");
  const Mould mould = build_mould(profile, box_options(2, 2, true));
  REQUIRE(mould.parts.back().kind == MouldPartKind::Base);
  const MouldPart& base = mould.parts.back();
  const CastingCase c = build_casting_case(base.soup, base.name, outward_of(base), case_options());
  CHECK(c.pull == Vec3(0.0, 0.0, -1.0));
  const ValidationReport v = validate(c.soup);
  CHECK(v.valid());
  CHECK(v.volume == Approx((c.hi - c.lo).prod() - signed_volume(base.soup)).epsilon(1e-10));
  CHECK_FALSE(interpenetrate(moved(base.soup, 0.3 * c.pull), c.soup));
  CHECK(interpenetrate(moved(base.soup, -0.3 * c.pull), c.soup));

  CHECK(c.plates.empty());
}

TEST_CASE("casting case: a side part over a keyed base gets a plate under it that comes off first",
          "[mould][case]") {
  const CompositeCurve profile = example_profile("vessel_golden_solid.yaml");
  const Mould mould = build_mould(profile, box_options(2, 2, true));
  for (std::size_t n = 0; n < 2; ++n) {
    const MouldPart& side = mould.parts[n];
    INFO(side.name);
    std::size_t sockets = 0;
    for (const KeyFeature& k : side.keys) sockets += k.on_base && !k.bump ? 1 : 0;
    REQUIRE(sockets > 0);
    const CastingCase c = build_casting_case(side.soup, side.name, outward_of(side), case_options());
    CHECK(c.pull == outward_of(side).array().round().matrix());
    REQUIRE(c.plates.size() == 1);
    const CasePlate& plate = c.plates.front();
    // The plate lies under the part's bottom, the slab 0.5 thick, and fills its sockets.
    CHECK(plate.pull == Vec3(0.0, 0.0, -1.0));
    CHECK(plate.features == sockets);
    const BoundingBox pb = bounding_box(side.soup.vertices);
    CHECK(plate.hi.z() == pb.lo.z());
    CHECK(plate.lo.z() == pb.lo.z() - 0.5);
    CHECK(bounding_box(plate.soup.vertices).lo == plate.lo);
    CHECK(bounding_box(plate.soup.vertices).hi.z() > pb.lo.z());  // its bumps in the sockets
    const ValidationReport main = validate(c.soup), under = validate(plate.soup);
    CHECK(main.valid());
    CHECK(under.valid());
    REQUIRE(main.genus);
    REQUIRE(under.genus);
    CHECK(*main.genus == 0);
    CHECK(*under.genus == 0);
    // Two pins stand on the plate's face, up into the case's walls either
    // side of the part, a third of the way from the floor to the opening.
    REQUIRE(plate.pins.size() == 2);
    double pins = 0.0, holes = 0.0;
    const int across = c.pull.x() != 0.0 ? 1 : 0;
    for (const CasePin& pin : plate.pins) {
      CHECK(pin.axis == -plate.pull);
      CHECK(pin.base.z() == pb.lo.z());
      CHECK(pin.radius == 0.125);
      CHECK(pin.height == 0.25);
      CHECK(pin.hole_radius == Approx(0.145));
      CHECK(pin.hole_depth == Approx(0.27));
      CHECK(pin.sides % 4 == 0);
      // Each polygon within the tolerance of its circle.
      CHECK(pin.hole_radius * (1.0 - std::cos(M_PI / static_cast<double>(pin.sides))) <= 0.005);
      const double off =
          std::min(std::abs(pin.base[across] - pb.lo[across]), std::abs(pin.base[across] - pb.hi[across]));
      CHECK(off == Approx(0.25));
      CHECK((pin.base[across] < pb.lo[across] || pin.base[across] > pb.hi[across]));
      const int k = c.pull.x() != 0.0 ? 0 : 1;
      const double floor_at = c.pull[k] > 0.0 ? c.lo[k] : c.hi[k],
                   opening = c.pull[k] > 0.0 ? c.hi[k] : c.lo[k];
      CHECK(pin.base[k] == Approx(floor_at + (opening - floor_at) / 3.0));
      pins += polygon_area(pin.radius, pin.sides) * pin.height;
      holes += polygon_area(pin.hole_radius, pin.sides) * pin.hole_depth;
    }
    CHECK(plate.pins[0].base[across] < plate.pins[1].base[across]);
    // Together they are the box less the part, with the pins' holes less the pins.
    CHECK(main.volume + under.volume ==
          Approx((c.hi - c.lo).prod() - signed_volume(side.soup) - holes + pins).epsilon(1e-10));
    CHECK_FALSE(interpenetrate(c.soup, plate.soup));
    // The pins hold the plate in place: moved across by more than the
    // clearance, or turned half round, it runs into the main piece.
    const Vec3 centre = 0.5 * (c.lo + c.hi);
    CHECK(interpenetrate(moved(plate.soup, Vec3(0.05, 0.0, 0.0)), c.soup));
    CHECK(interpenetrate(moved(plate.soup, Vec3(0.0, 0.05, 0.0)), c.soup));
    CHECK_FALSE(interpenetrate(moved(plate.soup, Vec3(0.0, 0.0, -0.01)), c.soup));
    CHECK(interpenetrate(half_turned(plate.soup, centre), c.soup));
    CHECK_FALSE(interpenetrate(side.soup, c.soup));
    CHECK_FALSE(interpenetrate(side.soup, plate.soup));
    // The plate comes off down; pushed up it runs into the part. With the
    // plate in place the part cannot leave (its sockets hold it); with the
    // plate off it leaves along the pull, and not the other way or sideways.
    CHECK_FALSE(interpenetrate(moved(plate.soup, 0.3 * plate.pull), side.soup));
    CHECK(interpenetrate(moved(plate.soup, -0.3 * plate.pull), side.soup));
    CHECK(interpenetrate(moved(side.soup, 0.3 * c.pull), plate.soup));
    CHECK_FALSE(interpenetrate(moved(side.soup, 0.3 * c.pull), c.soup));
    CHECK_FALSE(interpenetrate(moved(side.soup, 3.0 * c.pull), c.soup));
    CHECK(interpenetrate(moved(side.soup, -0.3 * c.pull), c.soup));
    CHECK(interpenetrate(moved(side.soup, Vec3(0.3, 0.0, 0.0)), c.soup));
    CHECK_THAT(c.release_proof, Catch::Contains("once the plate across -z is off") &&
                                    Catch::Contains("the plate comes off first along -z") &&
                                    Catch::Contains("its 2 pins run along it out of their holes"));
  }
}

TEST_CASE("casting case: the plate's pins without clearance, and a clearance the walls cannot hold",
          "[mould][case]") {
  const CompositeCurve profile = example_profile("vessel_golden_solid.yaml");
  const Mould mould = build_mould(profile, box_options(2, 2, true));
  const MouldPart& side = mould.parts[0];
  // No clearance: each pin fills its hole, both still valid and apart.
  const CastingCase c = build_casting_case(side.soup, side.name, outward_of(side), case_options(0.5, 0.0));
  REQUIRE(c.plates.size() == 1);
  CHECK(validate(c.soup).valid());
  CHECK(validate(c.plates.front().soup).valid());
  CHECK(c.plates.front().pins.front().hole_radius == c.plates.front().pins.front().radius);
  CHECK(validate(c.soup).volume + validate(c.plates.front().soup).volume ==
        Approx((c.hi - c.lo).prod() - signed_volume(side.soup)).epsilon(1e-10));
  // A clearance of a quarter of the wall would leave the holes no wall.
  for (double clearance : {0.125, 0.2, -0.01}) {
    INFO(clearance);
    try {
      build_casting_case(side.soup, side.name, outward_of(side), case_options(0.5, clearance));
      FAIL("accepted");
    } catch (const RangeError& e) {
      CHECK(e.field() == "clearance");
      CHECK(e.value() == clearance);
      CHECK_THAT(e.what(),
                 Catch::Contains("case.clearance") && Catch::Contains("quarter of case.wall (0.125)"));
    }
  }
}

TEST_CASE(
    "casting case: a three-part keyed mould's side parts get cases carved in pieces that come off in turn",
    "[mould][case][carved]") {
  const CompositeCurve profile = example_profile("vessel_golden_solid.yaml");
  const Mould mould = build_mould(profile, box_options(3, 2, true));
  const CaseOptions options = case_options();
  for (std::size_t n = 0; n < 3; ++n) {
    const MouldPart& side = mould.parts[n];
    INFO(side.name);
    const CastingCase c =
        build_casting_case(side.soup, side.name, outward_of(side), options, {}, split_faces(side));
    INFO(c.release_proof);
    CHECK(c.carved);
    // A piece under the part (the base keys' sockets) and one beyond each slanted split face whose keys
    // catch.
    REQUIRE(c.plates.size() >= 2);
    CHECK(c.plates.front().face == "its face across -z");
    CHECK(c.plates.front().pull == Vec3(0.0, 0.0, -1.0));
    check_pieces_fill_box(c, side.soup, options);
    check_pieces_come_off(c, side.soup);
    CHECK(c.release_proof.find("comes off first") != std::string::npos);
  }
}

TEST_CASE(
    "casting case: a cylinder mould's side parts are cast upright under a lid, its base part in one piece",
    "[mould][case][carved][lid]") {
  const CompositeCurve profile = example_profile("vessel_golden_solid.yaml");
  for (const bool base : {false, true}) {
    MouldOptions o = cm_options();
    o.keys = 2;
    o.base_part = base;
    const Mould mould = build_mould(profile, o);
    CaseOptions options = case_options();
    options.cylinder_radius = mould.section.block_radius;
    for (const MouldPart& part : mould.parts) {
      INFO(part.name << (base ? " over a base part" : ""));
      const CastingCase c =
          build_casting_case(part.soup, part.name, outward_of(part), options, {}, split_faces(part));
      INFO(c.release_proof);
      // Carved by exact booleans but for the base part's, built face by face.
      CHECK(c.carved == (part.kind == MouldPartKind::Side));
      check_pieces_fill_box(c, part.soup, options);
      if (part.kind == MouldPartKind::Base) {
        // Poured through its flat bottom, and pulled out that way off its keys.
        CHECK(c.plates.empty());
        CHECK(c.pull == Vec3(0.0, 0.0, -1.0));
        CHECK(c.opening == c.pull);
        const double r = options.cylinder_radius.value();
        CHECK(c.pour_area == Approx(M_PI * r * r).epsilon(1e-3));
        // Its wall on the cylinder leans by the draft: as designed the
        // part does not fit the cavity, as cast it does.
        REQUIRE(c.drafts.size() == 1);
        CHECK(c.drafts.front().face == "its cylinder");
        CHECK(c.draft_volume > 0.0);
        CHECK(interpenetrate(part.soup, c.soup));
        TriangleSoup cast = part.soup;
        const double low = bounding_box(part.soup.vertices).lo.z();
        const double t = std::tan(options.draft_deg * M_PI / 180.0);
        for (Vec3& p : cast.vertices) {
          const double at = std::hypot(p.x(), p.y());
          if (at < r * (1.0 - 1e-9) || p.z() == low) continue;
          const double keep = 1.0 - t * (p.z() - low) / at;
          p.x() *= keep;
          p.y() *= keep;
        }
        CHECK(signed_volume(cast) == Approx(signed_volume(part.soup) - c.draft_volume).epsilon(1e-12));
        CHECK_FALSE(interpenetrate(moved(cast, 1e-6 * c.pull), c.soup));
        CHECK_FALSE(interpenetrate(moved(cast, 0.3 * c.pull), c.soup));
        CHECK(interpenetrate(moved(cast, -0.3 * c.pull), c.soup));
        continue;
      }
      // Poured through its flat top; the lid over its back (after the plate
      // under it, over a base part) comes off along the split face's normal,
      // and the part then leaves the main piece that way.
      CHECK(c.opening == Vec3(0.0, 0.0, 1.0));
      const Vec3 out = outward_of(part);
      CHECK(c.pull == Vec3(0.0, out.y() > 0.0 ? 1.0 : -1.0, 0.0));
      REQUIRE(c.plates.size() == (base ? 2U : 1U));
      const CasePlate& lid = c.plates.back();
      CHECK(lid.face == "its curved back");
      CHECK(lid.pull == c.pull);
      CHECK(lid.hollow.size() > 8);
      if (base) CHECK(c.plates.front().face == "its face across -z");
      CHECK(c.pour_area < 0.5 * M_PI * options.cylinder_radius.value() * options.cylinder_radius.value());
      check_pieces_come_off(c, part.soup);
      CHECK(c.release_proof.find("the lid over") != std::string::npos);
      // Built again, the same triangles in the same order: the carved
      // pieces do not depend on what CGAL did before.
      if (part.name == "side 1 of 2") {
        const CastingCase again =
            build_casting_case(part.soup, part.name, outward_of(part), options, {}, split_faces(part));
        CHECK(again.soup.vertices == c.soup.vertices);
        CHECK(again.soup.triangles == c.soup.triangles);
        REQUIRE(again.plates.size() == c.plates.size());
        for (std::size_t i = 0; i < c.plates.size(); ++i) {
          CHECK(again.plates[i].soup.vertices == c.plates[i].soup.vertices);
          CHECK(again.plates[i].soup.triangles == c.plates[i].soup.triangles);
        }
      }
    }
  }
}

TEST_CASE(
    "casting case: a cylinder mould in three parts: a lid over each back, a piece beyond each slanted split "
    "face",
    "[mould][case][carved][lid]") {
  const CompositeCurve profile = example_profile("vessel_golden_solid.yaml");
  for (const bool base : {false, true}) {
    MouldOptions o = cm_options();
    o.parts = 3;
    o.keys = 2;
    o.key_clearance = 0.1;
    o.base_part = base;
    const Mould mould = build_mould(profile, o);
    CaseOptions options = case_options();
    options.cylinder_radius = mould.section.block_radius;
    // Each side spans 120 degrees from 0, 120 or 240: its lid comes off
    // across the plane through the axis that has its back on one side (side
    // 1: +y, its split face at 0 on that plane; side 2: -x; side 3: -y).
    const std::map<std::string, Vec3> lids{{"side 1 of 3", Vec3(0.0, 1.0, 0.0)},
                                           {"side 2 of 3", Vec3(-1.0, 0.0, 0.0)},
                                           {"side 3 of 3", Vec3(0.0, -1.0, 0.0)}};
    for (const MouldPart& part : mould.parts) {
      if (part.kind != MouldPartKind::Side) continue;
      INFO(part.name << (base ? " over a base part" : ""));
      const bool middle = part.name == "side 2 of 3";
      const CastingCase c =
          build_casting_case(part.soup, part.name, outward_of(part), options, {}, split_faces(part));
      INFO(c.release_proof);
      CHECK(c.carved);
      CHECK(c.opening == Vec3(0.0, 0.0, 1.0));
      // The lid first, then a piece beyond each split face off the lid's
      // plane, then over a base part the plate under the part; the part then
      // leaves the main piece the lid's way. The middle side's last piece
      // takes the vessel's slice too, and the part lifts off the floor.
      const std::size_t slanted = middle ? 2 : 1;
      CHECK(c.pull == (middle ? c.opening : lids.at(part.name)));
      REQUIRE(c.plates.size() == 1U + slanted + (base && !middle ? 1U : 0U));
      if (middle) {
        // The slice in one prism from inside the part's bottom; over a base
        // part from the floor up, narrower up past the base key's bump.
        const std::vector<CasePrism>& cores = c.plates[slanted].cores;
        REQUIRE(cores.size() == (base ? 2U : 1U));
        if (base) {
          const auto reach = [](const CasePrism& p) {
            double r = 0.0;
            for (const Vec3& q : p.ring) r = std::max(r, std::hypot(q.x(), q.y()));
            return r;
          };
          CHECK(reach(cores[0]) < reach(cores[1]));
          CHECK(cores[0].ring.front().z() + cores[0].along.z() == cores[1].ring.front().z());
          // The bump filling the base key's socket stays on the floor: the
          // main piece reaches up into the socket, the slice's piece does not.
          const auto on_base = std::find_if(part.keys.begin(), part.keys.end(),
                                            [](const KeyFeature& key) { return key.on_base; });
          REQUIRE(on_base != part.keys.end());
          const auto in_socket = [&](const TriangleSoup& piece) {
            return std::any_of(piece.vertices.begin(), piece.vertices.end(), [&](const Vec3& q) {
              return q.z() > on_base->centre.z() + 0.5 * on_base->radius &&
                     std::hypot(q.x() - on_base->centre.x(), q.y() - on_base->centre.y()) < on_base->radius;
            });
          };
          CHECK(in_socket(c.soup));
          CHECK_FALSE(in_socket(c.plates[slanted].soup));
        }
      }
      CHECK(c.plates.front().face == "its curved back");
      CHECK(c.plates.front().pull == lids.at(part.name));
      for (std::size_t i = 1; i <= slanted; ++i) {
        CHECK(c.plates[i].face.find("its split face at") == 0);
        CHECK(c.plates[i].pull.z() == 0.0);
        CHECK(std::abs(c.plates[i].pull.dot(lids.at(part.name))) < 0.9);
      }
      if (c.plates.size() > 1U + slanted) CHECK(c.plates.back().face == "its face across -z");
      check_pieces_fill_box(c, part.soup, options);
      check_pieces_come_off(c, part.soup);
    }
  }
}

TEST_CASE("casting case: parts no single pull clears, or without a flat face, are refused saying why",
          "[mould][case]") {
  const CompositeCurve profile = example_profile("vessel_golden_solid.yaml");
  SECTION("a cylinder block's curved back") {
    MouldOptions o = cm_options();
    const Mould mould = build_mould(profile, o);
    const MouldPart& side = mould.parts.front();
    CHECK_THROWS_WITH(build_casting_case(side.soup, side.name, outward_of(side), case_options()),
                      Catch::Contains("no flat face across +y") || Catch::Contains("does not cover"));
  }
  SECTION("three parts with keys on planes 120 degrees apart") {
    const Mould mould = build_mould(profile, box_options(3, 2, false));
    const MouldPart& side = mould.parts.front();
    CHECK_THROWS_WITH(
        build_casting_case(side.soup, side.name, outward_of(side), case_options()),
        Catch::Contains("no casting case of one piece, or of one piece and a plate, releases side 1 of 3"));
  }
  SECTION("three parts without keys pour through a box side") {
    const Mould mould = build_mould(profile, box_options(3, 0, false));
    for (const MouldPart& side : mould.parts) {
      const CastingCase c = build_casting_case(side.soup, side.name, outward_of(side), case_options());
      CHECK(validate(c.soup).valid());
      CHECK_FALSE(interpenetrate(moved(side.soup, 0.3 * c.pull), c.soup));
    }
  }
  SECTION("a wall of no thickness") {
    const Mould mould = build_mould(profile, box_options(2, 0, false));
    CHECK_THROWS_AS(build_casting_case(mould.parts[0].soup, "side", {0.0, 1.0, 0.0}, case_options(0.0)),
                    RangeError);
  }
}

namespace {

// The convex polygon `outline` in the (x, y) plane swept from z = 0 to
// `height`: closed, outward.
TriangleSoup swept_xy(const std::vector<Vec2>& outline, double height) {
  TriangleSoup s;
  const auto n = static_cast<std::uint32_t>(outline.size());
  for (double z : {0.0, height}) {
    for (const Vec2& p : outline) s.vertices.emplace_back(p.x(), p.y(), z);
  }
  for (std::uint32_t m = 1; m + 1 < n; ++m) {
    s.triangles.push_back({0, m, m + 1});
    s.triangles.push_back({n, n + m + 1, n + m});
  }
  for (std::uint32_t m = 0; m < n; ++m) {
    const std::uint32_t l = (m + 1) % n;
    s.triangles.push_back({m, n + m, l});
    s.triangles.push_back({l, n + m, n + l});
  }
  if (signed_volume(s) < 0.0) {
    for (auto& t : s.triangles) std::swap(t[1], t[2]);
  }
  return s;
}

}  // namespace

TEST_CASE("casting case: the part's free faces along the pull lean by the draft, exactly",
          "[mould][case][draft]") {
  // A 4 x 2 x 3 block poured through its back (+y), on the mould's outside
  // across +x and +z only: those two faces lean, each by a wedge of
  // tan(draft) D^2 / 2 times its width, less the corner both take.
  const TriangleSoup part = swept_xy({{0.0, 0.0}, {4.0, 0.0}, {4.0, 2.0}, {0.0, 2.0}}, 3.0);
  CaseOptions o = case_options();
  o.outside = BoundingBox{Vec3(-1.0, -1.0, -1.0), Vec3(4.0, 3.0, 3.0)};
  for (double deg : {1.0, 5.0}) {
    INFO(deg);
    o.draft_deg = deg;
    const CastingCase c = build_casting_case(part, "a block", Vec3(0.0, 1.0, 0.0), o);
    CHECK(c.pull == Vec3(0.0, 1.0, 0.0));
    REQUIRE(c.drafts.size() == 2);
    CHECK(c.drafts[0].face == "its face across +z");
    CHECK(c.drafts[1].face == "its face across +x");
    CHECK(c.undrafted.empty());
    const double t = std::tan(deg * M_PI / 180.0), d = 2.0;
    const double wedges = 0.5 * t * d * d * (3.0 + 4.0) - t * t * d * d * d / 3.0;
    CHECK(c.draft_volume == Approx(wedges).epsilon(1e-12));
    const ValidationReport v = validate(c.soup);
    CHECK(v.valid());
    CHECK(v.volume == Approx((c.hi - c.lo).prod() - (24.0 - wedges)).epsilon(1e-12));
    // The cavity is the block leaned: no point of the case within the
    // block's box lies beyond either leaned plane (x <= 4 - t (2 - y),
    // z <= 3 - t (2 - y)), and the leaned faces reach them at the far side.
    bool far_x = false, far_z = false;
    for (const Vec3& p : c.soup.vertices) {
      if (p.x() < 0.0 || p.x() > 4.0 || p.y() < 0.0 || p.y() > 2.0 || p.z() < 0.0 || p.z() > 3.0) continue;
      const double inset = t * (2.0 - p.y());
      CHECK(p.x() <= 4.0 - inset + 1e-12);
      CHECK(p.z() <= 3.0 - inset + 1e-12);
      far_x = far_x || (p.y() == 0.0 && p.x() == Approx(4.0 - 2.0 * t).margin(1e-12));
      far_z = far_z || (p.y() == 0.0 && p.z() == Approx(3.0 - 2.0 * t).margin(1e-12));
    }
    CHECK(far_x);
    CHECK(far_z);
    // Pulled the least bit, the leaned faces come away from the case: the
    // block as cast (the case's cavity) is the block less the wedges, so
    // the block itself overlaps the case, and moved back by its wedges'
    // reach it does not.
    CHECK(interpenetrate(part, c.soup));
    TriangleSoup cast = part;
    for (Vec3& p : cast.vertices) {
      const double inset = t * (2.0 - p.y());
      if (p.x() == 4.0) p.x() -= inset;
      if (p.z() == 3.0) p.z() -= inset;
    }
    CHECK(signed_volume(cast) == Approx(24.0 - wedges).epsilon(1e-12));
    CHECK_FALSE(interpenetrate(moved(cast, 1e-3 * c.pull), c.soup));
  }
  // No draft, or no outside given: nothing leans.
  o.draft_deg = 0.0;
  CHECK(build_casting_case(part, "a block", Vec3(0.0, 1.0, 0.0), o).drafts.empty());
  o.draft_deg = 1.0;
  o.outside.reset();
  CHECK(build_casting_case(part, "a block", Vec3(0.0, 1.0, 0.0), o).drafts.empty());
  // Out of range.
  for (double deg : {-1.0, 10.5, std::nan("")}) {
    o.draft_deg = deg;
    CHECK_THROWS_AS(build_casting_case(part, "a block", Vec3(0.0, 1.0, 0.0), o), RangeError);
  }
}

TEST_CASE("casting case: a face with a slanted feature within the draft's reach does not lean, saying where",
          "[mould][case][draft]") {
  // The block with the edge of its floor and its +x end chamfered 0.05:
  // the chamfer meets the end and is not flat across x, so the end does
  // not lean; it runs up along z, so the top still does.
  const TriangleSoup part = swept_xy({{0.0, 0.0}, {3.95, 0.0}, {4.0, 0.05}, {4.0, 2.0}, {0.0, 2.0}}, 3.0);
  CaseOptions o = case_options();
  o.outside = BoundingBox{Vec3(-1.0, -1.0, -1.0), Vec3(4.0, 3.0, 3.0)};
  const CastingCase c = build_casting_case(part, "a block", Vec3(0.0, 1.0, 0.0), o);
  CHECK(c.pull == Vec3(0.0, 1.0, 0.0));
  REQUIRE(c.drafts.size() == 1);
  CHECK(c.drafts.front().face == "its face across +z");
  REQUIRE(c.undrafted.size() == 1);
  CHECK_THAT(c.undrafted.front(), Catch::StartsWith("its face across +x does not lean: its face at (3.9") &&
                                      Catch::EndsWith("meets it and is not flat across x"));
  // The top's wedge alone: tan(1 degree) 2^2 / 2 over the top's width
  // along x, 4, less what the chamfer leaves out: the integral over
  // y in [0, 0.05] of the wedge's depth t (2 - y) times 0.05 - y.
  const double t = std::tan(M_PI / 180.0), e = 0.05;
  const double chamfer = t * (e * e - e * e * e / 6.0);
  CHECK(c.draft_volume == Approx(0.5 * t * 2.0 * 2.0 * 4.0 - chamfer).epsilon(1e-12));
  CHECK(validate(c.soup).volume ==
        Approx((c.hi - c.lo).prod() - signed_volume(part) + c.draft_volume).epsilon(1e-12));
}

TEST_CASE("casting case: a cylinder mould's base part leans its wall into a cone by the draft, exactly",
          "[mould][case][draft]") {
  // A 64-sided prism inscribed in the block's cylinder of radius 3, from
  // z = 0 to 1, poured through its bottom: its wall leans into the cone
  // r = 3 - tan(draft) z, its top ring moved toward the axis, so the part as
  // cast is a frustum of the prism.
  const double r = 3.0, height = 1.0;
  const std::size_t sides = 64;
  std::vector<Vec2> outline;
  for (std::size_t i = 0; i < sides; ++i) {
    const double a = 2.0 * M_PI * static_cast<double>(i) / static_cast<double>(sides);
    outline.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  const TriangleSoup part = swept_xy(outline, height);
  CaseOptions o = case_options();
  o.cylinder_radius = r;
  const Vec3 down(0.0, 0.0, -1.0);
  for (double deg : {1.0, 5.0}) {
    INFO(deg);
    o.draft_deg = deg;
    const CastingCase c = build_casting_case(part, "a base", down, o);
    CHECK(c.pull == down);
    REQUIRE(c.drafts.size() == 1);
    CHECK(c.drafts.front().face == "its cylinder");
    CHECK(c.drafts.front().about_axis);
    CHECK(c.undrafted.empty());
    const double t = std::tan(deg * M_PI / 180.0);
    const double bottom = polygon_area(r, sides), top = bottom * std::pow(1.0 - t * height / r, 2);
    const double frustum = height / 3.0 * (bottom + top + std::sqrt(bottom * top));
    CHECK(c.draft_volume == Approx(bottom * height - frustum).epsilon(1e-12));
    // The exact wedge, between the cylinder and the cone, lies within the
    // bound the report gives: the tolerance over the leaned wall's area.
    const double exact = M_PI * (r * t * height * height - t * t * height * height * height / 3.0);
    CHECK(std::abs(c.draft_volume - exact) <= c.draft_volume_error);
    CHECK(c.draft_volume_error < 2.0 * M_PI * r * height * o.tolerance);
    const ValidationReport v = validate(c.soup);
    CHECK(v.valid());
    CHECK(v.volume == Approx((c.hi - c.lo).prod() - frustum).epsilon(1e-12));
    // No point of the case beside the part lies inside the cone, and the
    // cavity reaches it at the part's top.
    bool reached = false;
    for (const Vec3& p : c.soup.vertices) {
      if (p.z() < 0.0 || p.z() > height) continue;
      const double at = std::hypot(p.x(), p.y());
      CHECK(at >= r - t * p.z() - 1e-12);
      reached = reached || (p.z() == height && at == Approx(r - t * height).margin(1e-12));
    }
    CHECK(reached);
    // The part as designed does not fit the cavity; as cast it does, and
    // pulled the least bit it comes away.
    CHECK(interpenetrate(part, c.soup));
    TriangleSoup cast = part;
    for (Vec3& p : cast.vertices) {
      if (p.z() != height) continue;
      const double keep = 1.0 - t * height / std::hypot(p.x(), p.y());
      p.x() *= keep;
      p.y() *= keep;
    }
    CHECK(signed_volume(cast) == Approx(frustum).epsilon(1e-12));
    CHECK_FALSE(interpenetrate(moved(cast, 1e-3 * c.pull), c.soup));
  }
  // A corner pulled in off the cylinder: the faces beside it meet the wall
  // and are not level, so the wall stays as it is, saying where.
  std::vector<Vec2> dented = outline;
  dented.front() *= 0.999;
  const CastingCase d = build_casting_case(swept_xy(dented, height), "a base", down, o);
  CHECK(d.drafts.empty());
  CHECK(d.draft_volume == 0.0);
  REQUIRE(d.undrafted.size() == 1);
  CHECK_THAT(d.undrafted.front(), Catch::StartsWith("its cylinder does not lean: its face at") &&
                                      Catch::EndsWith("meets it and is not level"));
  // No draft: nothing leans, and there is nothing to say.
  o.draft_deg = 0.0;
  const CastingCase none = build_casting_case(part, "a base", down, o);
  CHECK(none.drafts.empty());
  CHECK(none.undrafted.empty());
  CHECK(validate(none.soup).volume ==
        Approx((none.hi - none.lo).prod() - signed_volume(part)).epsilon(1e-12));
}
