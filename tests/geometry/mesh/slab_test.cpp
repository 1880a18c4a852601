#include "geometry/mesh/slab.h"

#include <catch2/catch.hpp>

#include "geometry/core/errors.h"
#include "geometry/mesh/halfedge_mesh.h"
#include "geometry/validation/validate.h"
#include "tests/geometry/section/region_shapes.h"

using namespace fabmesh;
using namespace fabmesh::test;

namespace {

struct Kitchen {
  CompositeCurve outline;
  std::vector<RegionHole> holes;
  double exact_area = 0.0;  // of the exact curves
  double perimeter = 0.0;
};

// A countertop outline in mm with an elliptic sink and a rounded cooktop, rotated by `degrees` about the
// origin.
Kitchen kitchen(double degrees) {
  const double c = std::cos(degrees * M_PI / 180.0), s = std::sin(degrees * M_PI / 180.0);
  auto rot = [&](Vec2 p) { return Vec2(c * p.x() - s * p.y(), s * p.x() + c * p.y()); };
  Kitchen k;
  // Lines and exact quarter circles, rotated segment by segment.
  std::vector<Segment> segs;
  const CompositeCurve base = rounded_rect(0, 0, 1200, 600, 60);
  for (const Segment& seg : base.segments()) {
    if (seg.kind() == SegmentKind::Line) {
      segs.push_back(Segment::line(rot(seg.point(0.0)), rot(seg.point(1.0))));
    } else {
      EllipseArcParams e = *seg.ellipse();
      e.center = rot(e.center);
      e.rotation_deg += degrees;
      segs.push_back(Segment::ellipse_arc(e));
    }
  }
  k.outline = CompositeCurve(segs, true);
  k.holes.push_back({ellipse(rot({350, 300}), 200, 150, degrees + 10), "holes[0] (ellipse)"});
  k.holes.push_back({ellipse(rot({900, 300}), 150, 150, 0), "holes[1] (ellipse)"});
  k.exact_area = std::abs(exact_area(k.outline));
  k.perimeter = exact_length(k.outline);
  for (const auto& h : k.holes)
    k.exact_area -= std::abs(exact_area(h.curve)), k.perimeter += exact_length(h.curve);
  return k;
}

// The kitchen's slab: its region within `tolerance`, extruded `thickness` high.
SlabMesh kitchen_slab(double degrees, double tolerance, double thickness, double max_edge = 0.0) {
  const Kitchen k = kitchen(degrees);
  RegionOptions ro;
  ro.tolerance = tolerance;
  SlabOptions so;
  so.thickness = thickness;
  so.max_edge = max_edge;
  return build_slab(build_region(k.outline, k.holes, ro), so);
}

}  // namespace

TEST_CASE("slab: valid with the 3D self-intersection test, genus = holes, volume = exact area x thickness",
          "[mesh][slab][countertop]") {
  for (const double degrees : {0.0, 33.0}) {
    const Kitchen k = kitchen(degrees);
    RegionOptions ro;
    ro.tolerance = 0.2;
    const Region2 region = build_region(k.outline, k.holes, ro);
    SlabOptions so;
    so.thickness = 30.0;
    const SlabMesh slab = build_slab(region, so);
    const ValidationReport full = validate(to_soup(slab.mesh));
    INFO(describe_defects(full).size());
    CHECK(full.valid());
    CHECK(full.self_intersection == IntersectionCheck::Tested);
    CHECK_FALSE(full.self_intersecting);
    REQUIRE(full.genus);
    CHECK(*full.genus == 2);
    CHECK(full.components == 1);
    CHECK(full.triangles == slab_triangle_count(slab.triangulation));
    // The polygon is within max_deviation of the exact boundary everywhere.
    CHECK(std::abs(full.volume - k.exact_area * so.thickness) <=
          region.max_deviation * k.perimeter * so.thickness);
    CHECK(full.volume == Approx(region.area * so.thickness).epsilon(1e-12));
    // The construction proof agrees with the full test.
    REQUIRE(slab.proof);
    ValidationOptions proven;
    proven.embedding = *slab.proof;
    const ValidationReport constructed = validate(to_soup(slab.mesh), proven);
    CHECK(constructed.self_intersection == IntersectionCheck::ProvenByConstruction);
    CHECK(constructed.valid());
    CHECK(constructed.volume == full.volume);
    CHECK(constructed.genus == full.genus);
  }
}

TEST_CASE("slab: max_edge bounds top and bottom edges, walls follow the refined boundary",
          "[mesh][slab][countertop]") {
  const Kitchen k = kitchen(0.0);
  RegionOptions ro;
  ro.tolerance = 0.5;
  const Region2 region = build_region(k.outline, k.holes, ro);
  SlabOptions so;
  so.thickness = 20.0;
  so.max_edge = 50.0;
  const SlabMesh slab = build_slab(region, so);
  CHECK(slab.triangulation.steiner_points > 0);
  const ValidationReport full = validate(to_soup(slab.mesh));
  CHECK(full.valid());
  REQUIRE(full.genus);
  CHECK(*full.genus == 2);
  CHECK(full.volume == Approx(region.area * so.thickness).epsilon(1e-9));
  double longest_flat = 0.0;
  for (const auto& e : slab.mesh.edges()) {
    const auto h = slab.mesh.halfedge_handle(e, 0);
    const auto a = slab.mesh.point(slab.mesh.from_vertex_handle(h)),
               b = slab.mesh.point(slab.mesh.to_vertex_handle(h));
    if (a[2] == b[2]) longest_flat = std::max(longest_flat, (a - b).norm());
  }
  CHECK(longest_flat <= so.max_edge * (1 + 1e-9));
}

TEST_CASE("slab: thickness <= 0 and a triangle budget too small are rejected",
          "[mesh][slab][countertop][errors]") {
  const Kitchen k = kitchen(0.0);
  const Region2 region = build_region(k.outline, k.holes, {});
  SlabOptions so;
  so.thickness = 0.0;
  CHECK_THROWS_AS(build_slab(region, so), RangeError);
  so.thickness = -3.0;
  CHECK_THROWS_AS(build_slab(region, so), RangeError);
  so.thickness = 30.0;
  so.max_triangles = 1000;
  CHECK_THROWS_AS(build_slab(region, so), BudgetError);
}

TEST_CASE(
    "slab: extrude links the halfedges as OpenMesh's add_face does, and refuses a triangulation "
    "that is not a disc with holes",
    "[mesh][slab]") {
  // A unit square with a square hole: 8 vertices, 8 triangles, an outer and an inner boundary cycle.
  PlanarTriangulation t;
  t.vertices = {{0, 0}, {3, 0}, {3, 3}, {0, 3}, {1, 1}, {2, 1}, {2, 2}, {1, 2}};
  t.triangles = {{0, 1, 5}, {0, 5, 4}, {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  t.boundary = {{0, 1, 2, 3}, {4, 7, 6, 5}};
  const Mesh mesh = extrude(t, 0.5);
  const TriangleSoup soup = to_soup(mesh);
  // The same faces, corner for corner, as adding them one by one through OpenMesh.
  const SoupToMesh reference = to_mesh(soup);
  REQUIRE(reference.refused_faces == 0);
  CHECK(to_soup(reference.mesh).triangles == soup.triangles);
  CHECK(mesh.n_edges() == reference.mesh.n_edges());
  for (const auto h : mesh.halfedges()) {
    CHECK(mesh.next_halfedge_handle(mesh.prev_halfedge_handle(h)) == h);
    CHECK(mesh.face_handle(h).is_valid());
    CHECK(mesh.from_vertex_handle(h) == mesh.to_vertex_handle(mesh.opposite_halfedge_handle(h)));
  }
  const ValidationReport report = validate(to_soup(mesh));
  CHECK(report.valid());
  CHECK(report.genus == 1);
  CHECK(report.volume == Approx(8.0 * 0.5).epsilon(1e-12));
  // A flipped triangle makes two sides run the same way; a missing boundary cycle leaves sides unpaired.
  PlanarTriangulation flipped = t;
  std::swap(flipped.triangles[3][1], flipped.triangles[3][2]);
  CHECK_THROWS_AS(extrude(flipped, 0.5), std::logic_error);
  PlanarTriangulation open = t;
  open.boundary.pop_back();
  CHECK_THROWS_AS(extrude(open, 0.5), std::logic_error);
}

TEST_CASE("slab: a rounded copy is re-proven embedded exactly, a broken one is not",
          "[mesh][slab][countertop]") {
  const SlabMesh slab = kitchen_slab(33.0, 0.2, 30.0);
  REQUIRE(slab.proof.has_value());
  const EmbeddingProof& proof = *slab.proof;
  REQUIRE(proof.recheck);
  const TriangleSoup soup = to_soup(slab.mesh);
  const std::size_t n = slab.triangulation.vertices.size();

  // Rounded to float32, as STL stores it: still an extrusion, still embedded.
  TriangleSoup rounded = soup;
  for (Vec3& p : rounded.vertices) p = p.cast<float>().cast<double>();
  CHECK(proof.recheck(rounded));
  ValidationOptions vo;
  vo.embedding = proof;
  const ValidationReport built = validate(soup, vo);
  ValidationOptions moved;
  moved.moved_from = MovedFrom{&soup, &built};
  const ValidationReport stored = validate(rounded, moved);
  CHECK(stored.valid());
  CHECK(stored.self_intersection == IntersectionCheck::ProvenByConstruction);
  CHECK_THAT(stored.embedding_proof, Catch::Contains("still the extrusion of a planar triangulation"));

  // A top vertex lifted: no longer level, so no re-proof (the 3D test decides).
  TriangleSoup lifted = soup;
  lifted.vertices[n].z() += 1e-3;
  CHECK_FALSE(proof.recheck(lifted));
  // A vertex pulled across the triangulation, top and bottom alike: a triangle turns
  // over, the re-proof fails, and the full test finds the faces that cross.
  TriangleSoup folded = soup;
  const auto& t = slab.triangulation.triangles[slab.triangulation.triangles.size() / 2];
  const Vec2 across = slab.triangulation.vertices[t[1]] +
                      2.0 * (slab.triangulation.vertices[t[2]] - slab.triangulation.vertices[t[1]]);
  for (const std::size_t v : {std::size_t{t[2]}, n + t[2]}) {
    folded.vertices[v].x() = across.x();
    folded.vertices[v].y() = across.y();
  }
  CHECK_FALSE(proof.recheck(folded));
  const ValidationReport broken = validate(folded, moved);
  CHECK_FALSE(broken.valid());
}

TEST_CASE("slab: the connectivity extrude proves is what the analysis finds", "[mesh][slab][countertop]") {
  for (const double degrees : {0.0, 33.0}) {
    const SlabMesh slab = kitchen_slab(degrees, 0.2, 25.0, degrees > 0.0 ? 80.0 : 0.0);
    REQUIRE(slab.topology.has_value());
    const TriangleSoup soup = to_soup(slab.mesh);
    const ValidationReport analysed = validate(soup);
    CHECK(analysed.valid());
    CHECK(analysed.components == slab.topology->components);
    CHECK(analysed.euler_characteristics == slab.topology->euler_characteristics);
    ValidationOptions vo;
    vo.topology = slab.topology;
    vo.embedding = slab.proof;
    const ValidationReport proven = validate(soup, vo);
    CHECK(proven.valid());
    CHECK(proven.genus == analysed.genus);
    CHECK(proven.genus == std::optional<long>(2));  // the sink and the cooktop
    CHECK(proven.topology_proof == slab.topology->statement);
  }
}
