// A patch's B-spline surface (its bases' C1 Hermite interpolants) evaluated
// by de Boor's algorithm stays within the proven bound of the exact patch,
// the bound is not absurdly loose, and it shrinks like n^-4.

#include "geometry/surfaces/bspline_patch.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "io/design/read_design.h"
#include "tests/geometry/surfaces/test_networks.h"

using namespace fabmesh;

namespace {

// The full knot vector of distinct knots with multiplicities.
std::vector<double> full_knots(const HermiteBasis& b) {
  std::vector<double> out;
  for (std::size_t k = 0; k < b.knots.size(); ++k) out.insert(out.end(), b.multiplicities[k], b.knots[k]);
  return out;
}

// De Boor's algorithm, degree 3, at x in [0, 1].
template <class T>
T de_boor(const std::vector<double>& knots, const std::vector<T>& poles, double x) {
  const int p = 3;
  const int last = static_cast<int>(poles.size()) - 1;
  int span = p;
  while (span < last && knots[static_cast<std::size_t>(span) + 1] <= x) ++span;
  std::vector<T> d;
  for (int j = 0; j <= p; ++j) d.push_back(poles[static_cast<std::size_t>(span - p + j)]);
  for (int r = 1; r <= p; ++r) {
    for (int j = p; j >= r; --j) {
      const double lo = knots[static_cast<std::size_t>(span - p + j)];
      const double hi = knots[static_cast<std::size_t>(span + 1 + j - r)];
      const double a = hi > lo ? (x - lo) / (hi - lo) : 0.0;
      d[static_cast<std::size_t>(j)] =
          (1.0 - a) * d[static_cast<std::size_t>(j) - 1] + a * d[static_cast<std::size_t>(j)];
    }
  }
  return d[p];
}

Vec3 surface_point(const BSplinePatch& b, double s, double t) {
  const std::vector<double> ku = full_knots(b.u), kv = full_knots(b.v);
  std::vector<Vec3> column;
  for (std::size_t k = 0; k < b.u_poles; ++k) {
    const std::vector<Vec3> row(b.poles.begin() + static_cast<std::ptrdiff_t>(k * b.v_poles),
                                b.poles.begin() + static_cast<std::ptrdiff_t>((k + 1) * b.v_poles));
    column.push_back(de_boor(kv, row, t));
  }
  return de_boor(ku, column, s);
}

// The largest |S - Ŝ| at `samples` random (s, t) and on the grid's corners.
double measured_error(const HBezierPatch& patch, const BSplinePatch& b, int samples) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worst = 0.0;
  for (int k = 0; k < samples; ++k) {
    const double s = unit(rng), t = unit(rng);
    worst = std::max(worst, (patch.point(s, t) - surface_point(b, s, t)).norm());
  }
  return worst;
}

HBezierPatch skewed_patch() {
  ControlNet net;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = 0; j < 4; ++j)
      net[i][j] = Vec3(static_cast<double>(j) + jitter(rng), static_cast<double>(i) + jitter(rng),
                       jitter(rng) + 0.5 * std::sin(static_cast<double>(i * j)));
  return HBezierPatch(net, {2.5, 0.4, -0.6}, {0.7, -1.0, 0.8});
}

}  // namespace

TEST_CASE("bspline patch: the Hermite basis interpolates h and sums to one", "[surfaces][bspline]") {
  const HBezierParams params{2.5, 0.4, -0.6};
  const HermiteBasis b = hermite_basis(params, 8);
  REQUIRE(b.knots.size() == 9);
  CHECK(b.multiplicities.front() == 4);
  CHECK(b.multiplicities[4] == 2);
  const std::vector<double> knots = full_knots(b);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    const double x = k < 9 ? k / 8.0 : unit(rng);
    const auto exact = unit_hbezier_weights(x, params);
    double sum = 0.0;
    for (std::size_t i = 0; i < 4; ++i) {
      const double approx = de_boor(knots, b.coefficients[i], x);
      sum += approx;
      CHECK(std::abs(approx - exact[0][i]) <= b.error[i] + 1e-15);
      if (k < 9) CHECK(approx == Approx(exact[0][i]).margin(1e-14));  // interpolates at the knots
      CHECK(b.sup[i] >= std::abs(exact[0][i]));
    }
    CHECK(sum == Approx(1.0).margin(1e-14));
  }
  CHECK_THROWS(hermite_basis(params, 0));
}

TEST_CASE("bspline patch: the B-spline surface is within its proven bound, and not absurdly loosely",
          "[surfaces][bspline]") {
  for (const HBezierPatch& patch : {skewed_patch(), build_patch_network(test::basin_specs()).patches[0],
                                    build_patch_network(test::half_cylinder_specs()).patches[0]}) {
    for (const int n : {1, 2, 8}) {
      const BSplinePatch b = bspline_patch(patch, n, 2 * n);
      CHECK(b.u_poles == static_cast<std::size_t>(2 * n + 2));
      CHECK(b.v_poles == static_cast<std::size_t>(4 * n + 2));
      const double measured = measured_error(patch, b, 10000);
      INFO("n = " << n << ", bound " << b.bound << ", measured " << measured);
      CHECK(measured <= b.bound);
      CHECK(b.bound <= 1000.0 * measured + 1e-12);
      // The corners are the net's.
      CHECK((b.poles.front() - patch.points()[0][0]).norm() <= 1e-14);
      CHECK((b.poles.back() - patch.points()[3][3]).norm() <= 1e-14);
    }
  }
}

TEST_CASE("bspline patch: the bound shrinks about 16 times when the grid doubles", "[surfaces][bspline]") {
  const HBezierPatch patch = skewed_patch();
  double previous = bspline_patch(patch, 2, 2).bound;
  for (const int n : {4, 8, 16}) {
    const double bound = bspline_patch(patch, n, n).bound;
    INFO("n = " << n);
    CHECK(previous / bound > 12.0);
    CHECK(previous / bound < 20.0);
    previous = bound;
  }
}

TEST_CASE("bspline patch: a network's tied directions share their grids, within tolerance",
          "[surfaces][bspline]") {
  const PatchNetwork net = build_patch_network(test::basin_specs());
  for (const double tolerance : {1e-2, 1e-4}) {
    const BSplineNetwork b = bspline_network(net, tolerance);
    REQUIRE(b.patches.size() == net.patches.size());
    CHECK(b.max_bound <= tolerance);
    for (const SharedBorder& border : net.borders) {
      const BSplinePatch& pa = b.patches[border.a];
      const BSplinePatch& pb = b.patches[border.b];
      auto along = [](const BSplinePatch& p, PatchSide side) {
        return side == PatchSide::UMin || side == PatchSide::UMax ? p.v.intervals : p.u.intervals;
      };
      CHECK(along(pa, border.side_a) == along(pb, border.side_b));
      // The same border curve: its points agree to rounding.
      for (int k = 0; k <= 20; ++k) {
        const double x = k / 20.0, y = border.reversed ? 1.0 - x : x;
        const auto [sa, ta] = border_uv(border.side_a, x);
        const auto [sb, tb] = border_uv(border.side_b, y);
        CHECK((surface_point(pa, sa, ta) - surface_point(pb, sb, tb)).norm() <= 1e-12 * net.size);
      }
    }
  }
  CHECK_THROWS_WITH(bspline_network(net, 1e-12, 4), Catch::Contains("patch 'a'"));
}

TEST_CASE("bspline patch: the bundled open basin within the share of the tolerance its STEP file gets",
          "[surfaces][bspline]") {
  const Design design =
      read_design(std::string(FABMESH_SOURCE_DIR) + "/configs/examples/surface_basin_open.yaml");
  const PatchNetwork net = build_patch_network(std::get<SurfaceDesign>(design.body).patches);
  const double tolerance = 0.15;  // about what the viewing mesh leaves of 0.5 mm
  const BSplineNetwork b = bspline_network(net, tolerance);
  REQUIRE(b.patches.size() == 4);
  double measured = 0.0;
  for (std::size_t p = 0; p < 4; ++p) {
    const double m = measured_error(net.patches[p], b.patches[p], 10000);
    INFO("patch " << net.names[p] << ": n " << b.patches[p].u.intervals << " x " << b.patches[p].v.intervals
                  << ", bound " << b.patches[p].bound << ", measured " << m);
    CHECK(m <= b.patches[p].bound);
    CHECK(b.patches[p].bound <= tolerance);
    measured = std::max(measured, m);
  }
  INFO("bound " << b.max_bound << ", measured " << measured);
  CHECK(b.max_bound <= 1000.0 * measured);
}
