// The orientation of each component against its nesting: validate's
// component shells and the InvertedComponent and NestedSameOrientation
// defects, and the ray casting of detail/components.h under it.

#include <array>
#include <catch2/catch.hpp>
#include <cstdint>
#include <random>
#include <string>

#include "geometry/validation/detail/components.h"
#include "geometry/validation/validate.h"
#include "tests/geometry/mesh/shapes.h"
#include "tests/geometry/validation/moved_from.h"

using namespace fabmesh;
using fabmesh::test::append;
using fabmesh::test::box;

namespace {

/// `soup` with every face turned over.
TriangleSoup inverted(TriangleSoup soup) {
  for (auto& t : soup.triangles) std::swap(t[1], t[2]);
  return soup;
}

/// The union of two soups, `first`'s vertices first (so it is component 0).
TriangleSoup both(const TriangleSoup& first, const TriangleSoup& second) {
  TriangleSoup soup = first;
  append(soup, second);
  return soup;
}

TriangleSoup cube(double lo, double hi) { return box(Vec3(lo, lo, lo), Vec3(hi, hi, hi)); }

Vec3 direction(std::size_t k) {
  const auto d = ray_direction(k);
  return Vec3(d[0], d[1], d[2]);
}

bool has_only(const ValidationReport& r, Defect kind) { return r.defects.size() == 1 && r.find(kind); }

}  // namespace

TEST_CASE("orientation: a cube and a separate inverted cube is an inverted component",
          "[mesh][validate][orientation]") {
  const ValidationReport r = validate(both(cube(0, 20), inverted(box(Vec3(30, 0, 0), Vec3(35, 5, 5)))));
  CHECK(r.volume == 7875.0);  // the total is positive: not inside-out
  CHECK(r.oriented_outward);
  REQUIRE(has_only(r, Defect::InvertedComponent));
  const DefectReport& d = *r.find(Defect::InvertedComponent);
  CHECK(d.count == 1);
  REQUIRE(d.examples.size() == 1);
  CHECK(d.examples[0] == Vec3(30, 0, 0));
  CHECK_FALSE(r.valid());
  REQUIRE(r.component_shells.size() == 2);
  CHECK(r.component_shells[0].outward);
  CHECK(r.component_shells[0].volume == 8000.0);
  CHECK(r.component_shells[0].depth == std::optional<std::size_t>(0));
  CHECK_FALSE(r.component_shells[1].outward);
  CHECK(r.component_shells[1].volume == -125.0);
  CHECK(r.component_shells[1].faces == 12);
  CHECK(r.component_shells[1].depth == std::optional<std::size_t>(0));
  CHECK_FALSE(r.component_shells[1].inside);
  const std::string line = describe_defects(r).at(0);
  CHECK(
      line.find("1 inverted components: component 2 of 2 (12 faces, volume -125, at (30, 0, 0)) faces inward "
                "inside no other component") != std::string::npos);
}

TEST_CASE("orientation: two nested outward cubes are nested of the same orientation",
          "[mesh][validate][orientation]") {
  const ValidationReport r = validate(both(cube(0, 20), cube(5, 10)));
  CHECK(r.volume == 8125.0);
  REQUIRE(has_only(r, Defect::NestedSameOrientation));
  CHECK(r.find(Defect::NestedSameOrientation)->examples.at(0) == Vec3(5, 5, 5));
  REQUIRE(r.component_shells.size() == 2);
  CHECK(r.component_shells[1].depth == std::optional<std::size_t>(1));
  CHECK(r.component_shells[1].inside == std::optional<std::size_t>(0));
  CHECK(describe_defects(r).at(0).find(
            "component 2 of 2 (12 faces, volume 125, at (5, 5, 5)) faces outward like "
            "component 1, the innermost containing it") != std::string::npos);
  // The inner one listed first (component 0) changes nothing but the numbers.
  const ValidationReport swapped = validate(both(cube(5, 10), cube(0, 20)));
  REQUIRE(has_only(swapped, Defect::NestedSameOrientation));
  CHECK(swapped.component_shells[0].inside == std::optional<std::size_t>(1));
}

TEST_CASE("orientation: a cube with an inward cavity is valid with the volume between",
          "[mesh][validate][orientation]") {
  const ValidationReport r = validate(both(cube(0, 20), inverted(cube(5, 10))));
  CHECK(r.defects.empty());
  CHECK(r.valid());
  CHECK(r.volume == 8000.0 - 125.0);
  REQUIRE(r.component_shells.size() == 2);
  CHECK(r.component_shells[0].depth == std::optional<std::size_t>(0));
  CHECK(r.component_shells[1].depth == std::optional<std::size_t>(1));
  CHECK_FALSE(r.component_shells[1].outward);
}

TEST_CASE("orientation: separate outward cubes and an island in a cavity are valid",
          "[mesh][validate][orientation]") {
  const ValidationReport apart = validate(both(cube(0, 20), box(Vec3(30, 0, 0), Vec3(35, 5, 5))));
  CHECK(apart.valid());
  REQUIRE(apart.component_shells.size() == 2);
  CHECK(apart.component_shells[1].depth == std::optional<std::size_t>(0));

  // A solid island in a cavity of a solid: outward, inward, outward at depths 0, 1, 2.
  TriangleSoup island = both(cube(0, 30), inverted(cube(5, 25)));
  append(island, cube(10, 20));
  const ValidationReport r = validate(island);
  CHECK(r.valid());
  CHECK(r.volume == 27000.0 - 8000.0 + 1000.0);
  REQUIRE(r.component_shells.size() == 3);
  CHECK(r.component_shells[2].depth == std::optional<std::size_t>(2));
  CHECK(r.component_shells[2].inside == std::optional<std::size_t>(1));

  // The island facing inward like its cavity.
  TriangleSoup wrong = both(cube(0, 30), inverted(cube(5, 25)));
  append(wrong, inverted(cube(10, 20)));
  const ValidationReport w = validate(wrong);
  REQUIRE(has_only(w, Defect::NestedSameOrientation));
  CHECK(w.find(Defect::NestedSameOrientation)->examples.at(0) == Vec3(10, 10, 10));
}

TEST_CASE("orientation: one inside-out cube stays InsideOut alone, a single shell",
          "[mesh][validate][orientation]") {
  const ValidationReport r = validate(inverted(cube(0, 1)));
  REQUIRE(has_only(r, Defect::InsideOut));
  REQUIRE(r.component_shells.size() == 1);
  CHECK(r.component_shells[0].faces == 12);
  CHECK(r.component_shells[0].volume == r.volume);
  CHECK_FALSE(r.component_shells[0].outward);
  CHECK(r.component_shells[0].depth == std::optional<std::size_t>(0));
  CHECK(r.timings_ms.back().first != "components");  // nothing cast for one component

  // Two separate inside-out cubes: the total is negative, and each is inverted.
  const ValidationReport two = validate(both(inverted(cube(0, 1)), inverted(cube(2, 3))));
  REQUIRE(two.defects.size() == 2);
  CHECK(two.defects[0].kind == Defect::InsideOut);
  CHECK(two.defects[1].kind == Defect::InvertedComponent);
  CHECK(two.defects[1].count == 2);
}

TEST_CASE("orientation: a torus is one outward shell", "[mesh][validate][orientation]") {
  const ValidationReport r = validate(test::torus(3.0, 1.0, 32, 16));
  CHECK(r.valid());
  REQUIRE(r.component_shells.size() == 1);
  CHECK(r.component_shells[0].outward);
  CHECK(r.component_shells[0].faces == 1024);
}

TEST_CASE("orientation: nesting is not judged on a mesh with other defects",
          "[mesh][validate][orientation]") {
  // The inverted cube has a hole: its inside is undefined.
  TriangleSoup open = both(cube(0, 20), inverted(box(Vec3(30, 0, 0), Vec3(35, 5, 5))));
  open.triangles.pop_back();
  const ValidationReport r = validate(open);
  CHECK(r.find(Defect::BoundaryEdge));
  CHECK_FALSE(r.find(Defect::InvertedComponent));
  REQUIRE(r.component_shells.size() == 2);
  CHECK_FALSE(r.component_shells[1].depth);

  // Overlapping cubes: self-intersecting, so neither is inside the other.
  const ValidationReport crossing = validate(both(cube(0, 2), cube(1, 3)));
  CHECK(crossing.find(Defect::SelfIntersection));
  CHECK_FALSE(crossing.find(Defect::NestedSameOrientation));
  CHECK_FALSE(crossing.component_shells.at(0).depth);

  // Without the 3D test nothing says the components are disjoint.
  ValidationOptions untested;
  untested.check_self_intersections = false;
  const ValidationReport skipped = validate(both(cube(0, 20), cube(5, 10)), untested);
  CHECK_FALSE(skipped.find(Defect::NestedSameOrientation));
  CHECK_FALSE(skipped.component_shells.at(1).depth);
}

TEST_CASE("orientation: proofs of topology and embedding still get the nesting",
          "[mesh][validate][orientation]") {
  const TriangleSoup soup = both(cube(0, 20), cube(5, 10));
  ValidationOptions options;
  options.topology = TopologyProof{"two boxes", 2, {2, 2}};
  options.embedding = EmbeddingProof{"apart", 0.0};
  const ValidationReport r = validate(soup, options);
  CHECK(r.self_intersection == IntersectionCheck::ProvenByConstruction);
  REQUIRE(has_only(r, Defect::NestedSameOrientation));
  CHECK(r.component_shells.at(1).depth == std::optional<std::size_t>(1));
}

TEST_CASE("orientation: a moved copy gets its nesting from the moved vertices",
          "[mesh][validate][orientation]") {
  const TriangleSoup cavity = both(cube(0, 20), inverted(cube(5, 10)));
  const ValidationReport original = validate(cavity);
  REQUIRE(original.valid());
  // The same triangles, the cavity's vertices moved out of the solid: now an inverted component.
  TriangleSoup moved = cavity;
  for (std::size_t v = 8; v < 16; ++v) moved.vertices[v].x() += 30.0;
  const ValidationReport r = test::validate_moved(cavity, original, moved);
  REQUIRE(has_only(r, Defect::InvertedComponent));
  CHECK(r.component_shells.at(1).depth == std::optional<std::size_t>(0));
  // Unmoved, the same report as the original's.
  const ValidationReport same = test::validate_moved(cavity, original, cavity);
  CHECK(same.valid());
  CHECK(same.component_shells.at(1).depth == std::optional<std::size_t>(1));
}

TEST_CASE("components: labels follow each component's lowest vertex", "[mesh][validate][orientation]") {
  TriangleSoup soup = both(cube(5, 10), cube(0, 20));
  soup.triangles.push_back({3, 3, 4});  // index-degenerate: in no component
  const ComponentLabels labels = label_components(soup);
  CHECK(labels.count == 2);
  CHECK(labels.lowest_vertex == std::vector<std::uint32_t>{0, 8});
  CHECK(labels.faces == std::vector<std::size_t>{12, 12});
  CHECK(labels.face_component.back() == ComponentLabels::kNone);
  CHECK(component_volumes(soup, labels) == std::vector<double>{125.0, 8000.0});
}

TEST_CASE("components: a ray through a vertex of another shell is cast again",
          "[mesh][validate][orientation]") {
  // The first ray from the inner cube's first vertex (the origin) runs along
  // direction(0): pull the outer box's corner in that octant onto it.
  const Vec3 d = direction(0);
  TriangleSoup outer = box(Vec3(-16, -16, -16), Vec3(16, 16, 16));
  for (Vec3& v : outer.vertices) {
    if (v.x() * d.x() > 0 && v.y() * d.y() > 0 && v.z() * d.z() > 0) v = 32.0 * d;
  }
  const TriangleSoup soup = both(outer, inverted(cube(0, 1)));  // a cavity
  const ValidationReport r = validate(soup);
  CHECK(r.valid());
  const Nesting nesting = nest_components(soup, label_components(soup));
  CHECK(nesting.retries >= 1);
  CHECK(nesting.depth == std::vector<std::size_t>{0, 1});
  CHECK(r.component_shells.at(1).depth == std::optional<std::size_t>(1));
}

TEST_CASE("components: a segment meets a triangle exactly", "[mesh][validate][orientation]") {
  const Vec3 a(0, 0, 0), b(4, 0, 0), c(0, 4, 0);
  const auto meets = [&](const Vec3& p, const Vec3& q) { return segment_meets_triangle(p, q, a, b, c); };
  CHECK(meets(Vec3(1, 1, -1), Vec3(1, 1, 1)) == SegmentMeeting::Cross);
  CHECK(meets(Vec3(1, 1, 1), Vec3(1, 2, 5)) == SegmentMeeting::Miss);      // one side
  CHECK(meets(Vec3(5, 5, -1), Vec3(5, 5, 1)) == SegmentMeeting::Miss);     // beyond the hypotenuse
  CHECK(meets(Vec3(2, 0, -1), Vec3(2, 0, 1)) == SegmentMeeting::Touch);    // through an edge
  CHECK(meets(Vec3(2, 2, -1), Vec3(2, 2, 1)) == SegmentMeeting::Touch);    // through the hypotenuse
  CHECK(meets(Vec3(0, 0, -1), Vec3(0, 0, 1)) == SegmentMeeting::Touch);    // through a vertex
  CHECK(meets(Vec3(-1, 1, 0), Vec3(5, 1, 0)) == SegmentMeeting::Touch);    // within the plane, across
  CHECK(meets(Vec3(-1, -1, 0), Vec3(-5, 1, 0)) == SegmentMeeting::Miss);   // within the plane, apart
  CHECK(meets(Vec3(1, 1, 0), Vec3(1, 1, 3)) == SegmentMeeting::Touch);     // from a point of it
  CHECK(meets(Vec3(9, 9, 0), Vec3(9, 9, 3)) == SegmentMeeting::Miss);      // from its plane, outside it
  CHECK(meets(Vec3(1, -1, -1), Vec3(-1, 1, 1)) == SegmentMeeting::Touch);  // slanted, through a vertex
}

TEST_CASE("components: nested shells on shared planes nest by exact parity",
          "[mesh][validate][orientation]") {
  // An octahedron whose equator z = 10 holds four of its vertices and the
  // inner cube's top face: rays from the cube run near that plane and
  // through edges of the octahedron's diagonal planes x = y and x = -y.
  TriangleSoup octahedron;
  octahedron.vertices = {{10, 10, -5}, {25, 10, 10}, {10, 25, 10}, {-5, 10, 10}, {10, -5, 10}, {10, 10, 25}};
  octahedron.triangles = {{0, 2, 1}, {0, 3, 2}, {0, 4, 3}, {0, 1, 4},
                          {5, 1, 2}, {5, 2, 3}, {5, 3, 4}, {5, 4, 1}};
  const TriangleSoup cavity = both(octahedron, inverted(box(Vec3(8, 8, 8), Vec3(12, 12, 10))));
  const ValidationReport r = validate(cavity);
  CHECK(r.defects.empty());
  CHECK(r.valid());
  CHECK(r.component_shells.at(1).depth == std::optional<std::size_t>(1));
  CHECK(has_only(validate(both(octahedron, box(Vec3(8, 8, 8), Vec3(12, 12, 10)))),
                 Defect::NestedSameOrientation));
}

/// x, y with a x + b y = gcd(a, b) (>= 0).
std::array<std::int64_t, 3> extended_gcd(std::int64_t a, std::int64_t b) {
  if (b == 0) return {a < 0 ? -a : a, a < 0 ? -1 : 1, 0};
  const auto [g, x, y] = extended_gcd(b, a % b);
  return {g, y, x - (a / b) * y};
}

TEST_CASE("Orientation is the exact sign of the volume, even where rounding decides it wrongly",
          "[orientation][validate]") {
  // Nearly flat tetrahedra on an integer lattice: b and c span the lattice
  // plane n . x = 0 of a normal n of about 2^23, d lies one lattice step off
  // it (n . d = 1), so det(b, c, d) is about 2^37 where the products of
  // coordinates reach 2^106: a sum in double gets its sign wrong for many
  // of them. The exact determinant (128-bit integers) says which way each
  // faces; validate must agree with it.
  std::mt19937_64 rng(3);
  const auto small = [&](int bits) { return static_cast<std::int64_t>(rng() >> (64 - bits)) + 1; };
  __extension__ using I = __int128;  // GCC and Clang have it; -Wpedantic wants it marked
  int naive_wrong = 0;
  int judged = 0;
  for (int round = 0; round < 300; ++round) {
    const std::int64_t n[3] = {small(23), small(23), small(23)};
    const auto [g12, x, y] = extended_gcd(n[0], n[1]);
    const auto [g, s, t] = extended_gcd(g12, n[2]);
    if (g != 1) continue;
    const std::int64_t u[3] = {n[1], -n[0], 0};
    const std::int64_t v[3] = {n[2], 0, -n[0]};
    const std::int64_t a1 = small(7), b1 = -small(7), a2 = small(7), b2 = small(7);
    std::int64_t b[3], c[3], d[3];
    const std::int64_t d0[3] = {x * s, y * s, t};  // n . d0 = 1
    for (int k = 0; k < 3; ++k) {
      b[k] = a1 * u[k] + b1 * v[k];
      c[k] = a2 * u[k] + b2 * v[k];
      d[k] = d0[k];
    }
    const I det = I(b[0]) * (I(c[1]) * d[2] - I(c[2]) * d[1]) - I(b[1]) * (I(c[0]) * d[2] - I(c[2]) * d[0]) +
                  I(b[2]) * (I(c[0]) * d[1] - I(c[1]) * d[0]);
    if (det == 0) continue;
    TriangleSoup tet;
    const auto vec = [](const std::int64_t* p) {
      return Vec3(static_cast<double>(p[0]), static_cast<double>(p[1]), static_cast<double>(p[2]));
    };
    tet.vertices = {Vec3(0, 0, 0), vec(b), vec(c), vec(d)};
    // Outward for a positive det(b, c, d): faces (1, 2, 3), (0, 2, 1), (0, 3, 2), (0, 1, 3).
    tet.triangles = {{1, 2, 3}, {0, 2, 1}, {0, 3, 2}, {0, 1, 3}};
    if (det < 0) tet = inverted(tet);
    const Vec3 &p = tet.vertices[1], &q = tet.vertices[2], &r = tet.vertices[3];
    naive_wrong += (det > 0) != (p.dot(q.cross(r)) > 0.0);
    ++judged;
    INFO("round " << round);
    ComponentLabels about = label_components(tet);
    for (std::uint32_t centre = 0; centre < 4; ++centre) {
      about.lowest_vertex[0] = centre;
      CHECK(component_volume_signs(tet, about)[0] == 1);
    }
    const ValidationReport report = validate(tet);
    CHECK(report.oriented_outward);
    CHECK_FALSE(report.find(Defect::InsideOut));
    const ValidationReport turned = validate(inverted(tet));
    CHECK_FALSE(turned.oriented_outward);
    CHECK(turned.find(Defect::InsideOut));
    // As one of two components (the other a unit cube far away), its shell's orientation.
    const ValidationReport two = validate(both(cube(1e12, 1e12 + 1), inverted(tet)));
    REQUIRE(two.component_shells.size() == 2);
    CHECK_FALSE(two.component_shells[1].outward);
  }
  REQUIRE(judged > 100);
  REQUIRE(naive_wrong > 10);  // the cases the exact sign exists for
}

TEST_CASE("A component every ray from which touches another is undetermined, and the mesh is not valid",
          "[orientation]") {
  // A tetrahedron whose four corners lie on the faces of a cube: every ray
  // from them starts on the cube (validate never gets here: the test of
  // self-intersections finds the contact first). Its nesting is unknown,
  // not an internal error; the cube's is settled (no other box holds it).
  TriangleSoup tetra;
  tetra.vertices = {Vec3(5, 5, 0), Vec3(5, 5, 10), Vec3(0, 5, 5), Vec3(10, 2, 5)};
  tetra.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  const TriangleSoup soup = both(cube(0, 10), tetra);
  const ComponentLabels labels = label_components(soup);
  REQUIRE(labels.count == 2);
  const Nesting nesting = nest_components(soup, labels);
  CHECK(nesting.determined == std::vector<char>{1, 0});
  CHECK(nesting.retries == 4 * 32);  // four start vertices, 32 directions each
  CHECK_FALSE(nesting.inside[1]);
  ValidationReport report = validate(cube(0, 10));
  REQUIRE(report.valid());
  report.undetermined_components = 1;
  CHECK_FALSE(report.valid());
  const std::vector<std::string> lines = describe_defects(report);
  REQUIRE(lines.size() == 1);
  CHECK(lines[0].find("orientation of 1 of 1 components undetermined") != std::string::npos);
}
