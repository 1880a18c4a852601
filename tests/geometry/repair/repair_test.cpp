// The repair engine on meshes broken in code, one defect kind at a time:
// each output valid by fabmesh's validate AND by CGAL PMP's predicates,
// components accounted for, the distance bounded, and a second repair a no-op.

#include "geometry/repair/repair.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "geometry/core/errors.h"
#include "geometry/mesh/volume.h"
#include "tests/geometry/repair/broken_meshes.h"
#include "tests/geometry/repair/cgal_solid.h"

using namespace fabmesh;
using namespace fabmesh::testing;

namespace {

/// The count of `step` in the result's log, 0 when it never acted.
std::size_t done(const RepairResult& r, RepairStep step) {
  for (const RepairAction& a : r.actions) {
    if (a.step == step) return a.count;
  }
  return 0;
}

/// Repairs `broken` and checks what every repair must give: valid by both
/// judges, within the distance it reports, unchanged by a second repair.
RepairResult repaired(const TriangleSoup& broken, const RepairOptions& options = {}) {
  const RepairResult r = repair(broken, options);
  INFO("unresolved: " << (r.unresolved.empty() ? std::string("none") : r.unresolved.front()));
  REQUIRE(r.ok());
  CHECK(r.after.valid());
  const CgalSolid cgal = cgal_solid(r.soup);
  CHECK(cgal.polygon_mesh);
  CHECK(cgal.closed);
  CHECK_FALSE(cgal.self_intersecting);
  CHECK(cgal.bounds_a_volume);
  CHECK(r.measure.distance >= r.measure.input_to_output.lower);
  CHECK(r.measure.distance >= r.measure.output_to_input.lower);
  const RepairResult again = repair(r.soup, options);
  CHECK_FALSE(again.changed);
  CHECK(again.soup.triangles == r.soup.triangles);
  CHECK(again.soup.vertices == r.soup.vertices);
  return r;
}

}  // namespace

TEST_CASE("repair: a valid mesh is returned as it is, nothing logged", "[repair]") {
  const TriangleSoup s = sphere(Vec3::Zero(), 2.0, 2);
  const RepairResult r = repair(s);
  CHECK_FALSE(r.changed);
  CHECK(r.ok());
  CHECK(r.actions.empty());
  CHECK(r.soup.triangles == s.triangles);
  CHECK(r.measure.distance == 0.0);
}

TEST_CASE("repair: an STL with 1e-5 jitter is welded at a distance chosen from the data", "[repair]") {
  const TriangleSoup s = jittered(unshared(sphere(Vec3::Zero(), 10.0, 3)), 1e-5);
  const RepairResult r = repaired(s);
  CHECK(r.weld.distance > 1e-5);
  CHECK(r.weld.distance < 1e-3);
  CHECK(done(r, RepairStep::Weld) > 0);
  CHECK(done(r, RepairStep::HoleFill) == 0);
  CHECK(r.after.components == 1);
  CHECK(r.measure.distance < 1e-4);
  CHECK(r.after.volume == Approx(signed_volume(sphere(Vec3::Zero(), 10.0, 3))).epsilon(1e-5));
}

TEST_CASE("repair: degenerate faces are removed, a collinear needle stitched", "[repair]") {
  TriangleSoup s = cube(Vec3::Zero(), 1.0);
  // The front's face (0, 1, 5) split at m, the midpoint of edge 0-1, and the
  // needle (1, m, 0) between it and the bottom: closed, one face of no area.
  s.vertices.push_back(Vec3(0.5, 0.0, 0.0));  // m = 8
  s.triangles[4] = {0, 8, 5};
  s.triangles.push_back({8, 1, 5});
  s.triangles.push_back({1, 8, 0});
  s.triangles.push_back({2, 2, 3});  // a repeated corner
  const RepairResult r = repaired(s);
  CHECK(done(r, RepairStep::DegenerateFace) == 2);
  CHECK(done(r, RepairStep::Stitch) == 1);
  CHECK(r.after.volume == Approx(1.0));
  CHECK(r.measure.distance < 1e-5);  // 0 but for the bound's resolution (1e-6 of the size)
}

TEST_CASE("repair: duplicate faces go and opposite copies of a shared wall cancel", "[repair]") {
  SECTION("a repeated face") {
    TriangleSoup s = cube(Vec3::Zero(), 1.0);
    s.triangles.push_back(s.triangles[3]);
    const RepairResult r = repaired(s);
    CHECK(done(r, RepairStep::DuplicateFace) == 1);
    CHECK(r.after.volume == Approx(1.0));
  }
  SECTION("two boxes exported with their common wall: one solid") {
    // Box b's wall at x = 1 is box a's reversed, with the same diagonal.
    const TriangleSoup a = cube(Vec3::Zero(), 1.0);
    TriangleSoup b = cube(Vec3(1, 0, 0), 1.0);
    const TriangleSoup s = unshared(join(a, b));
    const RepairResult r = repaired(s);
    CHECK(done(r, RepairStep::DuplicateFace) == 4);
    CHECK(r.after.components == 1);
    CHECK(r.after.volume == Approx(2.0));
    CHECK(r.measure.unmeasured_faces == 4);
  }
}

TEST_CASE("repair: faces that disagree are flipped and an inside-out solid turned", "[repair]") {
  SECTION("a few faces flipped") {
    TriangleSoup s = sphere(Vec3::Zero(), 1.0, 2);
    for (std::size_t f : {3, 17, 40}) std::swap(s.triangles[f][1], s.triangles[f][2]);
    const RepairResult r = repaired(s);
    CHECK(done(r, RepairStep::Orientation) == 3);
    CHECK(r.measure.distance == 0.0);
  }
  SECTION("inside out") {
    const RepairResult r = repaired(reversed(sphere(Vec3::Zero(), 1.0, 2)));
    CHECK(done(r, RepairStep::Outward) == 1);
    CHECK(r.after.volume > 0.0);
  }
  SECTION("a cavity written outward stays a cavity") {
    const TriangleSoup s = join(cube(Vec3::Zero(), 4.0), cube(Vec3(1, 1, 1), 1.0));
    const RepairResult r = repaired(s);
    CHECK(done(r, RepairStep::Outward) == 1);
    CHECK(r.after.components == 2);
    CHECK(r.after.volume == Approx(63.0));
  }
}

TEST_CASE("repair: holes are filled, the patch verified and measured", "[repair]") {
  const TriangleSoup whole = sphere(Vec3::Zero(), 5.0, 3);
  const TriangleSoup s = without(whole, {10, 11, 12, 100});
  const RepairResult r = repaired(s);
  CHECK(done(r, RepairStep::HoleFill) >= 1);
  CHECK(r.after.volume == Approx(signed_volume(whole)).epsilon(0.01));
  CHECK(r.measure.distance < 1.0);
  CHECK(r.measure.distance > 0.0);
}

TEST_CASE("repair: --no-fill leaves a hole and refuses", "[repair]") {
  RepairOptions options;
  options.fill_holes = false;
  const RepairResult r = repair(without(sphere(Vec3::Zero(), 5.0, 2), {7}), options);
  CHECK_FALSE(r.ok());
  CHECK_FALSE(r.unresolved.empty());
}

TEST_CASE("repair: two cubes sharing an edge or a vertex are split into two solids", "[repair]") {
  SECTION("an edge") {
    const TriangleSoup s = unshared(join(cube(Vec3::Zero(), 1.0), cube(Vec3(1, 1, 0), 1.0)));
    const RepairResult r = repaired(s);
    CHECK(done(r, RepairStep::NonManifoldEdge) == 1);
    CHECK(r.after.components == 2);
    CHECK(r.after.volume == Approx(2.0).epsilon(1e-3));
  }
  SECTION("a vertex") {
    const TriangleSoup s = unshared(join(cube(Vec3::Zero(), 1.0), cube(Vec3(1, 1, 1), 1.0)));
    const RepairResult r = repaired(s);
    CHECK(done(r, RepairStep::NonManifoldVertex) == 1);
    CHECK(r.after.components == 2);
  }
}

TEST_CASE("repair: overlapping closed shells become one solid, exactly", "[repair]") {
  const TriangleSoup s = join(cube(Vec3::Zero(), 2.0), cube(Vec3(1, 1, 1), 2.0));
  const RepairResult r = repaired(s);
  CHECK(done(r, RepairStep::Union) == 1);
  CHECK(r.after.components == 1);
  CHECK(r.after.volume == Approx(15.0));
  CHECK(r.measure.output_to_input.upper < 1e-9);
}

TEST_CASE("repair: a sheet without volume is dropped and reported with its size", "[repair]") {
  TriangleSoup s = cube(Vec3::Zero(), 1.0);
  const auto base = static_cast<std::uint32_t>(s.vertices.size());
  for (const Vec3& p : {Vec3(5, 0, 0), Vec3(6, 0, 0), Vec3(5, 1, 0)}) s.vertices.push_back(p);
  s.triangles.push_back({base, base + 1, base + 2});
  const RepairResult r = repaired(s);
  REQUIRE(r.dropped.size() == 1);
  CHECK(r.dropped.front().faces == 1);
  CHECK(r.dropped.front().first_face == 12);
  CHECK(r.dropped.front().area == Approx(0.5));
  CHECK_FALSE(r.dropped.front().why.empty());
  CHECK(r.after.components == 1);
}

TEST_CASE("repair: a T-junction is stitched", "[repair]") {
  // The cube's top split at the midpoint of edge 4-5 on one side only.
  TriangleSoup s = cube(Vec3::Zero(), 1.0);
  s.vertices.push_back(Vec3(0.5, 0.0, 1.0));  // 8, on edge 4-5 (top, y = 0)
  // The top is quads {4, 5, 7, 6}: triangles (4, 5, 7) and (4, 7, 6); split (4, 5, 7) at 8.
  s.triangles[2] = {4, 8, 7};
  s.triangles.push_back({8, 5, 7});
  const RepairResult r = repaired(s);
  CHECK(done(r, RepairStep::Stitch) == 1);
  CHECK(r.after.volume == Approx(1.0));
}

TEST_CASE("repair: --wrap gives a closed surface within the deviation asked", "[repair][wrap]") {
  RepairOptions options;
  options.wrap = true;
  options.max_deviation = 0.5;
  // Open (holes) with a flipped face: the wrap closes it all, within what its
  // offset and alpha allow (no surface inside the solid to be far from it).
  TriangleSoup s = without(sphere(Vec3::Zero(), 5.0, 3), {0, 1, 2, 300});
  std::swap(s.triangles[40][1], s.triangles[40][2]);
  const RepairResult r = repair(s, options);
  INFO((r.unresolved.empty() ? std::string() : r.unresolved.front()));
  REQUIRE(r.ok());
  CHECK(done(r, RepairStep::Wrap) == 1);
  CHECK(cgal_solid(r.soup).solid());
  CHECK(r.measure.distance <= 0.5);
}

TEST_CASE("repair: --max-deviation refuses a larger change", "[repair]") {
  RepairOptions options;
  options.max_deviation = 1e-3;
  const RepairResult r = repair(without(sphere(Vec3::Zero(), 5.0, 2), {7}), options);
  CHECK_FALSE(r.ok());
  CHECK(r.after.valid());
}

TEST_CASE("repair: bad input is an InputError", "[repair]") {
  CHECK_THROWS_AS(repair(TriangleSoup{}), InputError);
  TriangleSoup nan = cube(Vec3::Zero(), 1.0);
  nan.vertices[3].x() = std::nan("");
  CHECK_THROWS_AS(repair(nan), InputError);
  TriangleSoup out_of_range = cube(Vec3::Zero(), 1.0);
  out_of_range.triangles[0][0] = 99;
  CHECK_THROWS_AS(repair(out_of_range), InputError);
}
