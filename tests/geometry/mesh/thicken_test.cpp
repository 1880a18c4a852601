#include "geometry/mesh/thicken.h"

#include <catch2/catch.hpp>

#include "geometry/core/errors.h"
#include "geometry/mesh/halfedge_mesh.h"
#include "geometry/surfaces/tessellate.h"
#include "geometry/validation/validate.h"
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
  const ValidationReport r = validate(to_soup(solid));
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
  const ValidationReport s = validate(to_soup(sheet.mesh));
  CHECK(r.volume == Approx(s.area * 0.05).epsilon(0.05));
}

TEST_CASE("thicken: a shell thicker than the radius of curvature intersects itself and is caught by validate",
          "[mesh][thicken]") {
  const PatchNetwork net = build_patch_network(test::half_cylinder_specs(1.0, 2.0));
  TessellateOptions o;
  o.tolerance = 0.01;
  const SurfaceTessellation sheet = tessellate(net, o);
  CHECK(validate(to_soup(thicken(sheet.mesh, sheet.normals, {0.1}))).valid());  // thin: fine
  const ValidationReport r =
      validate(to_soup(thicken(sheet.mesh, sheet.normals, {2.5})));  // beyond the axis: walls cross
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

TEST_CASE("thicken: outward, inward and centered shells of a dish are valid outward solids on their side",
          "[mesh][thicken]") {
  const double depth = 0.6, thickness = 0.05;
  const PatchNetwork net = build_patch_network(test::basin_specs(2.0, depth, 2.0 / 3.0));
  TessellateOptions coarse;
  coarse.tolerance = 0.05;
  const double volume = enclosed_volume(tessellate(net, coarse).mesh);
  CHECK(volume > 0.0);  // the normals point out of the dish
  struct Case {
    ThickenSide side;
    double lowest;  // the solid's lowest point: under the dish's bottom, or at it
  };
  for (const Case& c :
       {Case{ThickenSide::Outward, -depth - thickness}, Case{ThickenSide::Inward, -depth},
        Case{ThickenSide::Centered, -depth - thickness / 2}, Case{ThickenSide::Normal, -depth - thickness}}) {
    INFO(to_string(c.side));
    const auto span = shell_span(c.side, thickness, volume, net.size);
    CHECK(span[1] - span[0] == Approx(thickness));
    TessellateOptions o;
    o.tolerance = 0.01;
    o.shell_from = span[0];
    o.shell_to = span[1];
    const SurfaceTessellation sheet = tessellate(net, o);
    ThickenOptions th;
    th.thickness = thickness;
    th.offset = span[0];
    const Mesh solid = thicken(sheet.mesh, sheet.normals, th);
    const ValidationReport r = validate(to_soup(solid));
    CHECK(r.valid());
    CHECK(r.oriented_outward);
    CHECK(r.volume == Approx(validate(to_soup(sheet.mesh)).area * thickness).epsilon(0.05));
    double lowest = INFINITY;
    for (const auto v : solid.vertices()) lowest = std::min(lowest, solid.point(v)[2]);
    CHECK(lowest == Approx(c.lowest).margin(o.tolerance));
  }
  // A flat sheet encloses nothing: outward and inward mean nothing there.
  CHECK_THROWS_AS(shell_span(ThickenSide::Outward, thickness, 0.0, net.size), GeometryError);
  CHECK_NOTHROW(shell_span(ThickenSide::Centered, thickness, 0.0, net.size));
}
