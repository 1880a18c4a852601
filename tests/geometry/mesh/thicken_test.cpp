#include "geometry/mesh/thicken.h"

#include <catch2/catch.hpp>

#include "geometry/core/errors.h"
#include "geometry/mesh/tessellate.h"
#include "geometry/mesh/validate.h"
#include "tests/geometry/surfaces/test_networks.h"

using namespace fabmesh;

TEST_CASE("thicken: a disk-like G1 network becomes a valid outward solid of genus 0", "[mesh][thicken]") {
  // A shallow dish: its square rim's corners are gentle enough for the offset not to fold.
  const PatchNetwork net = build_patch_network(test::basin_specs(2.0, 0.6, 2.0 / 3.0));
  TessellateOptions o;
  o.tolerance = 0.02;
  o.offset = 0.05;
  SurfaceTessellation sheet;
  tessellate(net, o, sheet);
  Mesh solid;
  thicken(sheet.mesh, sheet.normals, {0.05}, solid);
  const ValidationReport r = validate(solid);
  std::string defects;
  for (const std::string& d : describe_defects(r)) defects += d + "; ";
  INFO(defects);
  CHECK(r.valid());
  CHECK(r.boundary_edges == 0);
  CHECK(r.oriented_outward);
  CHECK(r.components == 1);
  REQUIRE(r.genus);
  CHECK(*r.genus == 0);
  // A thin shell: volume ~ sheet area x thickness.
  const ValidationReport s = validate(sheet.mesh);
  CHECK(r.volume == Approx(s.area * 0.05).epsilon(0.05));
}

TEST_CASE("thicken: a shell thicker than the radius of curvature intersects itself and is caught by validate",
          "[mesh][thicken]") {
  const PatchNetwork net = build_patch_network(test::half_cylinder_specs(1.0, 2.0));
  TessellateOptions o;
  o.tolerance = 0.01;
  SurfaceTessellation sheet;
  tessellate(net, o, sheet);
  Mesh solid;
  thicken(sheet.mesh, sheet.normals, {0.1}, solid);  // thin: fine
  CHECK(validate(solid).valid());
  thicken(sheet.mesh, sheet.normals, {2.5}, solid);  // beyond the axis: the walls cross
  const ValidationReport r = validate(solid);
  CHECK_FALSE(r.valid());
  CHECK(r.self_intersecting);
}

TEST_CASE("thicken: bad thickness and normal counts are rejected", "[mesh][thicken]") {
  const PatchNetwork net = build_patch_network(test::half_cylinder_specs());
  SurfaceTessellation sheet;
  tessellate(net, {}, sheet);
  Mesh solid;
  CHECK_THROWS_AS(thicken(sheet.mesh, sheet.normals, {0.0}, solid), RangeError);
  CHECK_THROWS_AS(thicken(sheet.mesh, sheet.normals, {-1.0}, solid), RangeError);
  CHECK_THROWS_AS(thicken(sheet.mesh, {}, {1.0}, solid), RangeError);
}
