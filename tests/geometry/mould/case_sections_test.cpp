#include "geometry/mould/case_sections.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "geometry/core/errors.h"
#include "geometry/mesh/bounding_box.h"
#include "geometry/mesh/interpenetration.h"
#include "geometry/mesh/volume.h"
#include "geometry/mould/mould.h"
#include "geometry/validation/validate.h"
#include "tests/geometry/mesh/point_triangle.h"
#include "tests/geometry/mould/mould_fixtures.h"

using namespace fabmesh;
using namespace fabmesh::test;

namespace {

CaseOptions options_of(double wall, double clearance, double tolerance) {
  CaseOptions o;
  o.wall = wall;
  o.clearance = clearance;
  o.tolerance = tolerance;
  return o;
}

// The area of the polygon of `sides` sides inscribed in a circle of `radius`.
double polygon_area(double radius, std::size_t sides) {
  return 0.5 * static_cast<double>(sides) * radius * radius *
         std::sin(2.0 * M_PI / static_cast<double>(sides));
}

// Checks what cut_case_piece promises of `cut`, a cut of `piece` for `bed`:
// every section a valid solid of one piece that fits the bed; the volumes
// add up to the piece's with the pins standing out and the holes taken (the
// pins' polygon areas, computed here); every pin and hole in the material
// with room all round (for a plain tray, half a wall inside its box); no two
// sections overlapping as they are assembled, and each pin clear of the
// section above it.
void check_cut(const TriangleSoup& piece, const SectionedPiece& cut, const Vec3& bed, const CaseOptions& o,
               bool all_in_walls = true) {
  const BoundingBox box = bounding_box(piece.vertices);
  double sum = 0.0;
  std::vector<const TriangleSoup*> solids;
  std::size_t pins = 0, holes = 0;
  for (const CaseSection& s : cut.sections) {
    INFO("section " << s.cell[0] << " " << s.cell[1] << " " << s.cell[2]);
    const ValidationReport v = validate(s.soup);
    INFO("boundary " << v.boundary_edges << " non-manifold " << v.non_manifold_edges << "/"
                     << v.non_manifold_vertices << " degenerate " << v.degenerate_faces << " duplicate "
                     << v.duplicate_faces << " self-intersecting " << v.intersecting_pairs << " inconsistent "
                     << v.inconsistent_edges);
    CHECK(v.valid());
    CHECK(v.components == 1);
    CHECK(fits_bed(bounding_box(s.soup.vertices).size(), bed));
    sum += v.volume;
    solids.push_back(&s.soup);
    pins += s.pins;
    holes += s.holes;
  }
  REQUIRE_FALSE(cut.pins.empty());
  const CasePin& pin = cut.pins.front();
  CHECK(pin.radius == o.wall / 4.0);
  CHECK(pin.hole_radius == o.wall / 4.0 + o.clearance);
  CHECK(pins == cut.pins.size());
  CHECK(holes == cut.pins.size());
  const double stud = polygon_area(pin.radius, pin.sides) * pin.height;
  const double hole = polygon_area(pin.hole_radius, pin.sides) * pin.hole_depth;
  const double expected = signed_volume(piece) + static_cast<double>(cut.pins.size()) * (stud - hole);
  // Within a thousandth of a pin: the polygons' points lie on a grid.
  CHECK(sum == Approx(expected).margin(1e-3 * stud));
  CHECK(cut.volume_error <= 1e-9 * cut.volume);
  for (const CasePin& p : cut.pins) {
    // In the piece's material with room all round: the hole's axis, from the
    // pin's foot to the hole's end, is farther than the hole's radius from
    // every face of the piece (an independent distance to its triangles).
    CHECK(p.axis.norm() == 1.0);
    double nearest = std::numeric_limits<double>::infinity();
    for (double along = -p.buried; along <= p.hole_depth + 1e-12; along += p.hole_depth / 8.0) {
      const Vec3 q = p.base + along * p.axis;
      for (const auto& t : piece.triangles) {
        nearest = std::min(nearest, point_triangle_distance(q, piece.vertices[t[0]], piece.vertices[t[1]],
                                                            piece.vertices[t[2]]));
      }
    }
    CHECK(nearest > p.hole_radius);
  }
  // Where the walls run along the piece's box, in their middle: half a wall inside it.
  std::size_t in_wall = 0;
  for (const CasePin& p : cut.pins) {
    for (int q = 0; q < 3; ++q) {
      if (p.axis[q] != 0.0) continue;
      if (std::abs(p.base[q] - (box.lo[q] + o.wall / 2.0)) < 1e-9 ||
          std::abs(p.base[q] - (box.hi[q] - o.wall / 2.0)) < 1e-9) {
        ++in_wall;
        break;
      }
    }
  }
  if (all_in_walls) CHECK(in_wall == cut.pins.size());
  // Assembled, the sections touch and do not overlap: each pin stands in
  // its hole with the clearance all round.
  const Interpenetration found = interpenetrating_pairs(solids);
  CHECK(found.complete);
  CHECK(found.pairs.empty());
}

}  // namespace

TEST_CASE("case sections: a tray too long for the bed is cut in two, pinned in its walls",
          "[mould][case][sections]") {
  // A box part 100 x 40 x 30 poured through its top: its case is a tray 110 x 50 x 35.
  const TriangleSoup part = block_of(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ(), {0.0, 100.0},
                                     {0.0, 40.0}, {0.0, 30.0});
  const CaseOptions o = options_of(5.0, 0.2, 0.01);
  const CastingCase c = build_casting_case(part, "box", Vec3(0.0, 0.0, 1.0), o);
  const TriangleSoup printed = standing(c, Vec3::Zero());
  REQUIRE(bounding_box(printed.vertices).size().isApprox(Vec3(110.0, 50.0, 35.0)));

  SECTION("two sections along x") {
    const Vec3 bed(60.0, 60.0, 60.0);
    const SectionedPiece cut = cut_case_piece(printed, "case-box", bed, o);
    CHECK(cut.counts == std::array<int, 3>{2, 1, 1});
    REQUIRE(cut.sections.size() == 2);
    // The lower carries the two pins, the upper has their holes.
    CHECK(cut.sections[0].pins == 2);
    CHECK(cut.sections[0].holes == 0);
    CHECK(cut.sections[1].pins == 0);
    CHECK(cut.sections[1].holes == 2);
    CHECK(cut.sections[0].hi.x() == 55.0);
    // Each 55 long, the lower one with its pins standing 2.5 out.
    CHECK(bounding_box(cut.sections[0].soup.vertices).size().x() == Approx(57.5));
    CHECK(bounding_box(cut.sections[1].soup.vertices).size().x() == Approx(55.0));
    check_cut(printed, cut, bed, o);
    // As far apart as the joint allows: across the tray's floor, from wall to wall.
    CHECK((cut.pins[0].base - cut.pins[1].base).norm() > 40.0);
  }
  SECTION("a grid of four, the bed as it is rather than turned") {
    const Vec3 bed(60.0, 30.0, 60.0);
    const SectionedPiece cut = cut_case_piece(printed, "case-box", bed, o);
    CHECK(cut.counts == std::array<int, 3>{2, 2, 1});
    CHECK_FALSE(cut.turned);
    REQUIRE(cut.sections.size() == 4);
    CHECK(cut.pins.size() == 8);
    check_cut(printed, cut, bed, o);
  }
  SECTION("turned when that takes fewer sections") {
    const Vec3 bed(30.0, 120.0, 60.0);
    const SectionedPiece cut = cut_case_piece(printed, "case-box", bed, o);
    CHECK(cut.turned);
    CHECK(cut.counts == std::array<int, 3>{1, 2, 1});
    check_cut(printed, cut, bed, o);
  }
  SECTION("too tall for the bed: cut across z, the pins upright in the walls") {
    const Vec3 bed(120.0, 120.0, 21.0);
    const SectionedPiece cut = cut_case_piece(printed, "case-box", bed, o);
    CHECK(cut.counts == std::array<int, 3>{1, 1, 2});
    for (const CasePin& p : cut.pins) CHECK(p.axis == Vec3(0.0, 0.0, 1.0));
    check_cut(printed, cut, bed, o);
  }
  SECTION("a bed no longer than a pin (bad input), or one that would take too many sections") {
    CHECK_THROWS_WITH(cut_case_piece(printed, "case-box", Vec3(2.0, 2.0, 60.0), o),
                      Catch::Contains("case-box (110 x 50 x 35 standing) cannot be cut") &&
                          Catch::Contains("no longer than a section's pin (2.5 tall: half of case.wall)"));
    try {
      cut_case_piece(printed, "case-box", Vec3(2.0, 2.0, 60.0), o);
      FAIL("a bed no longer than a pin was taken");
    } catch (const RangeError& e) {
      CHECK(e.field() == "print.bed");
      CHECK(e.value() == 2.0);  // the bed's length along x, which the piece exceeds
    }
    CHECK_THROWS_WITH(cut_case_piece(printed, "case-box", Vec3(10.0, 10.0, 10.0), o),
                      Catch::Contains("would take 525 sections"));
    try {
      cut_case_piece(printed, "case-box", Vec3(10.0, 10.0, 10.0), o);
      FAIL("a bed taking 525 sections was taken");
    } catch (const GeometryError& e) {
      CHECK(e.where() == "print.bed");
    }
  }
}

TEST_CASE("case sections: every piece of a carved case cut for a small bed",
          "[mould][case][sections][carved]") {
  const CompositeCurve profile = example_profile("vessel_golden_solid.yaml");
  MouldOptions mo = cm_options();
  mo.block = BlockShape::Box;
  mo.parts = 3;
  mo.keys = 2;
  mo.base_part = true;
  mo.key_clearance = 0.1;
  const Mould mould = build_mould(profile, mo);
  const MouldPart& side = mould.parts[1];  // pulled along -x, in four pieces
  const CaseOptions o = options_of(0.5, 0.02, mo.tolerance);
  const double mid = 0.5 * (side.from_angle + side.to_angle);
  const CastingCase c = build_casting_case(side.soup, side.name, Vec3(std::cos(mid), std::sin(mid), 0.0), o,
                                           {}, split_faces(side));
  REQUIRE(c.carved);
  std::vector<TriangleSoup> printed{standing(c, Vec3::Zero())};
  for (const CasePlate& p : c.plates) printed.push_back(standing(p, Vec3::Zero()));
  std::size_t cut_pieces = 0;
  for (const TriangleSoup& piece : printed) {
    const Vec3 size = bounding_box(piece.vertices).size();
    INFO("piece of " << size.x() << " x " << size.y() << " x " << size.z());
    // A bed about two thirds of the piece's longest side.
    const double side_length = 0.7 * size.maxCoeff();
    const Vec3 bed(side_length, side_length, side_length);
    if (fits_bed(size, bed)) continue;
    const SectionedPiece cut = cut_case_piece(piece, "piece", bed, o);
    CHECK(cut.sections.size() >= 2);
    check_cut(piece, cut, bed, o, false);
    ++cut_pieces;
  }
  CHECK(cut_pieces >= 3);
}
