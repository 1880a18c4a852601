#include "geometry/mesh/thicken.h"

#include <catch2/catch.hpp>

#include "geometry/core/errors.h"
#include "geometry/mesh/validate.h"
#include "geometry/surfaces/tessellate.h"
#include "tests/geometry/surfaces/test_networks.h"

using namespace fabmesh;

TEST_CASE("thicken: a disk-like G1 network becomes a valid outward solid of genus 0", "[mesh][thicken]") {
  // A shallow dish: its square rim's corners are gentle enough for the offset not to fold.
  const PatchNetwork net = build_patch_network(test::basin_specs(2.0, 0.6, 2.0 / 3.0));
  TessellateOptions o;
  o.tolerance = 0.02;
  o.shell_to = 0.05;
  const SurfaceTessellation sheet = tessellate(net, o);
  const Mesh solid = thicken(sheet.mesh, sheet.normals, {0.05});
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
  const SurfaceTessellation sheet = tessellate(net, o);
  CHECK(validate(thicken(sheet.mesh, sheet.normals, {0.1})).valid());  // thin: fine
  const ValidationReport r =
      validate(thicken(sheet.mesh, sheet.normals, {2.5}));  // beyond the axis: walls cross
  CHECK_FALSE(r.valid());
  CHECK(r.self_intersecting);
}

TEST_CASE("thicken: bad thickness and normal counts are rejected", "[mesh][thicken]") {
  const PatchNetwork net = build_patch_network(test::half_cylinder_specs());
  const SurfaceTessellation sheet = tessellate(net, {});
  CHECK_THROWS_AS(thicken(sheet.mesh, sheet.normals, {0.0}), RangeError);
  CHECK_THROWS_AS(thicken(sheet.mesh, sheet.normals, {-1.0}), RangeError);
  CHECK_THROWS_AS(thicken(sheet.mesh, {}, {1.0}), RangeError);
  ThickenOptions small;
  small.max_triangles = thickened_triangle_count(sheet.mesh) - 1;
  CHECK_THROWS_AS(thicken(sheet.mesh, sheet.normals, small), BudgetError);
}
