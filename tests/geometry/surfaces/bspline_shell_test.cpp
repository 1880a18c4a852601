// A shell's B-spline faces: each within the proven bound of its exact
// surface (the sheet on the surface, the offset sheets, the ruled walls), the
// walls' borders the sheets' border curves, for shells on either side and
// centred.

#include "geometry/surfaces/bspline_shell.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "geometry/core/errors.h"
#include "geometry/surfaces/tessellate.h"
#include "tests/geometry/surfaces/test_networks.h"

using namespace fabmesh;

namespace {

std::array<double, 2> on_side(PatchSide side, double x) { return border_uv(side, x); }

// The largest distance of each kind of face from its exact surface at random
// parameters, and of the walls' borders from the sheets' borders.
struct Measured {
  double sheets = 0.0, walls = 0.0, seams = 0.0;
};

Measured measure(const PatchNetwork& net, const ShellGrid& grid, const BSplineShell& shell) {
  const std::size_t np = net.patches.size();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Measured m;
  for (std::size_t sheet = 0; sheet < 2; ++sheet) {
    const double offset = sheet == 0 ? grid.from : grid.to;
    for (std::size_t p = 0; p < np; ++p) {
      const HBezierPatch& patch = net.patches[p];
      for (int k = 0; k < 400; ++k) {
        const double s = unit(rng), t = unit(rng);
        const Vec3 exact = patch.point(s, t) + offset * patch.normal(s, t);
        m.sheets = std::max(m.sheets, (face_point(shell.faces[sheet * np + p], s, t) - exact).norm());
      }
    }
  }
  const std::vector<std::array<bool, 4>> outer = outer_sides(net);
  std::size_t wall = 2 * np;
  for (std::size_t p = 0; p < np; ++p) {
    for (PatchSide side : {PatchSide::UMin, PatchSide::UMax, PatchSide::VMin, PatchSide::VMax}) {
      if (!outer[p][static_cast<std::size_t>(side)]) continue;
      const BSplineFace& f = shell.faces[wall++];
      for (int k = 0; k <= 200; ++k) {
        const double x = k / 200.0, lambda = unit(rng);
        const auto [s, t] = on_side(side, x);
        const Vec3 point = net.patches[p].point(s, t), n = net.patches[p].normal(s, t);
        const Vec3 exact = point + ((1.0 - lambda) * grid.from + lambda * grid.to) * n;
        m.walls = std::max(m.walls, (face_point(f, x, lambda) - exact).norm());
        m.seams = std::max(m.seams, (face_point(f, x, 0.0) - face_point(shell.faces[p], s, t)).norm());
        m.seams = std::max(m.seams, (face_point(f, x, 1.0) - face_point(shell.faces[np + p], s, t)).norm());
      }
    }
  }
  REQUIRE(wall == shell.faces.size());
  return m;
}

}  // namespace

TEST_CASE("bspline shell: every face within the proven bound, the walls' borders the sheets' borders",
          "[surfaces][bspline][shell]") {
  const PatchNetwork net = build_patch_network(test::basin_specs());
  const double tolerance = 0.01, thickness = 0.2;
  for (const std::array<double, 2> span :
       {std::array<double, 2>{0.0, thickness}, std::array<double, 2>{-thickness, 0.0},
        std::array<double, 2>{-thickness / 2, thickness / 2}}) {
    INFO("span " << span[0] << " .. " << span[1]);
    TessellateOptions o;
    o.tolerance = tolerance;
    o.shell_from = span[0];
    o.shell_to = span[1];
    const SurfaceTessellation sheet = tessellate(net, o);
    const ShellGrid grid = shell_grid(sheet, span[0], span[1]);
    const BSplineShell shell = bspline_shell(net, grid, 0.1 * tolerance);
    CHECK(shell.faces.size() == 2 * 4 + 8);  // both sheets, a wall along each of the rim's 8 sides
    CHECK(shell.bound >= sheet.max_deviation);
    CHECK(shell.bound <= tolerance);
    const Measured m = measure(net, grid, shell);
    INFO("bound " << shell.bound << "; measured: sheets " << m.sheets << ", walls " << m.walls << ", seams "
                  << m.seams);
    CHECK(m.sheets <= shell.bound);
    CHECK(m.walls <= shell.bound);
    CHECK(m.seams <= 1e-12 * net.size);
    // The bound is a proof, not a guess: not absurdly loose either.
    CHECK(shell.bound <= 100.0 * std::max(m.sheets, m.walls));
    // Each offset sheet's poles are the tessellation's vertices moved along their normals.
    for (std::size_t sheet_index = 0; sheet_index < 2; ++sheet_index) {
      const double offset = span[sheet_index];
      if (offset == 0.0) continue;
      const BSplineFace& f = shell.faces[sheet_index * 4];
      CHECK(f.u_degree == 1);
      CHECK(f.v_degree == 1);
      const int corner = grid.vertices[0][0];
      const auto& q = sheet.mesh.point(Mesh::VertexHandle(corner));
      CHECK((f.poles[0] - (Vec3(q[0], q[1], q[2]) + offset * sheet.normals[static_cast<std::size_t>(corner)]))
                .norm() == 0.0);
    }
  }
}

TEST_CASE("bspline shell: a grid that does not match its network is refused", "[surfaces][bspline][shell]") {
  const PatchNetwork net = build_patch_network(test::basin_specs());
  TessellateOptions o;
  o.tolerance = 0.05;
  o.shell_to = 0.1;
  ShellGrid grid = shell_grid(tessellate(net, o), 0.0, 0.1);
  ShellGrid reversed = grid;
  std::swap(reversed.from, reversed.to);
  CHECK_THROWS_AS(bspline_shell(net, reversed, 0.01), RangeError);
  grid.vertices.pop_back();
  CHECK_THROWS_WITH(bspline_shell(net, grid, 0.01),
                    Catch::Contains("does not match the network of 4 patches"));
}
