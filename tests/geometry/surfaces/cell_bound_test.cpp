// The tessellation's reported deviation is a proof: dense evaluation of the
// exact surface (and of its offset sheets) against the mesh never exceeds it,
// over random patches and the bundled basin.

#include "geometry/surfaces/cell_bound.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "geometry/surfaces/tessellate.h"
#include "io/design/read_design.h"
#include "tests/geometry/mesh/point_triangle.h"
#include "tests/geometry/surfaces/test_networks.h"

using namespace fabmesh;
using fabmesh::test::point_triangle_distance;

namespace {

// The largest deviation found between the exact sheet S + offset n and the
// tessellation's triangles (as tessellate splits each cell), densely: the
// exact point against the interpolated point of the same parameters (which
// bounds both one-sided distances), and against the cell's two triangles.
struct Measured {
  double parametric = 0.0, distance = 0.0;
};

Measured measure(const PatchNetwork& net, const SurfaceTessellation& t, double offset, int per_cell) {
  Measured m;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto sheet = [&](const HBezierPatch& p, double s, double u) {
    return Vec3(p.point(s, u) + offset * p.normal(s, u));
  };
  for (std::size_t k = 0; k < net.patches.size(); ++k) {
    const HBezierPatch& p = net.patches[k];
    const auto& sb = t.s_breaks[k];
    const auto& tb = t.t_breaks[k];
    for (std::size_t a = 0; a + 1 < sb.size(); ++a) {
      for (std::size_t b = 0; b + 1 < tb.size(); ++b) {
        const Vec3 v00 = sheet(p, sb[a], tb[b]), v10 = sheet(p, sb[a + 1], tb[b]),
                   v01 = sheet(p, sb[a], tb[b + 1]), v11 = sheet(p, sb[a + 1], tb[b + 1]);
        const Vec3 s00 = p.point(sb[a], tb[b]), s10 = p.point(sb[a + 1], tb[b]),
                   s01 = p.point(sb[a], tb[b + 1]), s11 = p.point(sb[a + 1], tb[b + 1]);
        const bool main = (s00 - s11).norm() <= (s10 - s01).norm();  // the diagonal tessellate takes
        for (int i = 0; i < per_cell; ++i) {
          // Random points, then the edge and diagonal midpoints.
          double x = unit(rng), y = unit(rng);
          if (i == 0) x = 0.5, y = 0.0;
          if (i == 1) x = 0.0, y = 0.5;
          if (i == 2) x = 0.5, y = 0.5;
          if (i == 3) x = 1.0, y = 0.5;
          Vec3 lin;
          if (main) {
            lin = x >= y ? Vec3(v00 + x * (v10 - v00) + y * (v11 - v10))
                         : Vec3(v00 + y * (v01 - v00) + x * (v11 - v01));
          } else {
            lin = x + y <= 1.0 ? Vec3(v00 + x * (v10 - v00) + y * (v01 - v00))
                               : Vec3(v11 + (1.0 - x) * (v01 - v11) + (1.0 - y) * (v10 - v11));
          }
          const Vec3 exact = sheet(p, sb[a] + x * (sb[a + 1] - sb[a]), tb[b] + y * (tb[b + 1] - tb[b]));
          m.parametric = std::max(m.parametric, (exact - lin).norm());
          const double d = main ? std::min(point_triangle_distance(exact, v00, v10, v11),
                                           point_triangle_distance(exact, v00, v11, v01))
                                : std::min(point_triangle_distance(exact, v00, v10, v01),
                                           point_triangle_distance(exact, v10, v11, v01));
          m.distance = std::max(m.distance, d);
        }
      }
    }
  }
  return m;
}

PatchNetwork random_patch(std::mt19937& rng) {
  std::uniform_real_distribution<double> bump(-1.0, 1.0), alpha(0.2, 4.0), unit(0.0, 1.0);
  PatchSpec spec;
  spec.name = "random";
  for (int i = 0; i < 4; ++i) {
    std::array<Vec3, 4> row;
    for (int j = 0; j < 4; ++j) row[j] = Vec3(i + 0.3 * bump(rng), j + 0.3 * bump(rng), 1.5 * bump(rng));
    spec.points.push_back(row);
  }
  for (HBezierParams* p : {&spec.u, &spec.v}) {
    p->alpha = alpha(rng);
    const double lo = hbezier_lambda_min(p->alpha) + 0.05;
    p->lambda = lo + (1.0 - lo) * unit(rng);
    p->mu = lo + (1.0 - lo) * unit(rng);
  }
  return build_patch_network({spec});
}

}  // namespace

TEST_CASE("tessellate bound: dense evaluation of random patches never exceeds the reported deviation",
          "[surfaces][tessellate][bound]") {
  std::mt19937 rng(17);
  for (int trial = 0; trial < 12; ++trial) {
    const PatchNetwork net = random_patch(rng);
    for (double tolerance : {0.05, 0.005}) {
      TessellateOptions o;
      o.tolerance = tolerance;
      const SurfaceTessellation t = tessellate(net, o);
      CHECK(t.max_deviation <= tolerance);
      const Measured m = measure(net, t, 0.0, 8);
      INFO("trial " << trial << ", tolerance " << tolerance);
      CHECK(m.parametric <= t.max_deviation);
      CHECK(m.distance <= t.max_deviation);
      CHECK(min_triangle_count(net, tolerance) <= static_cast<double>(t.mesh.n_faces()));
    }
  }
}

TEST_CASE("tessellate bound: a shell's offset sheets stay within the reported deviation too",
          "[surfaces][tessellate][bound]") {
  const PatchNetwork net = build_patch_network(test::basin_specs(2.0, 0.6, 2.0 / 3.0));
  for (auto [from, to] : {std::pair{0.0, 0.1}, std::pair{-0.1, 0.0}, std::pair{-0.05, 0.05}}) {
    TessellateOptions o;
    o.tolerance = 0.005;
    o.shell_from = from;
    o.shell_to = to;
    const SurfaceTessellation t = tessellate(net, o);
    CHECK(t.max_deviation <= o.tolerance);
    for (double offset : {from, to}) {
      const Measured m = measure(net, t, offset, 6);
      INFO("offset " << offset);
      CHECK(m.parametric <= t.max_deviation + 1e-12);
      CHECK(m.distance <= t.max_deviation + 1e-12);
    }
  }
}

TEST_CASE("tessellate bound: the bundled basin, open and as a 6 mm shell, within the reported deviation",
          "[surfaces][tessellate][bound]") {
  const Design design =
      read_design(std::string(FABMESH_SOURCE_DIR) + "/configs/examples/surface_basin_shell.yaml");
  const PatchNetwork net = build_patch_network(std::get<SurfaceDesign>(design.body).patches);
  for (double thickness : {0.0, 6.0}) {
    TessellateOptions o;
    o.tolerance = 0.45;
    o.shell_to = thickness;
    const SurfaceTessellation t = tessellate(net, o);
    CHECK(t.max_deviation <= o.tolerance);
    for (double offset : {0.0, thickness}) {
      // The shared borders' vertices come from the first patch: equal up to rounding.
      const Measured m = measure(net, t, offset, 4);
      INFO("thickness " << thickness << ", sheet at " << offset);
      CHECK(m.parametric <= t.max_deviation + 1e-9);
      CHECK(m.distance <= t.max_deviation + 1e-9);
    }
    CHECK(min_triangle_count(net, o.tolerance) <= static_cast<double>(t.mesh.n_faces()));
  }
}

TEST_CASE("cell bounds: the enclosures hold the basis and the partials over the cell", "[surfaces][bound]") {
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const PatchNetwork net = random_patch(rng);
    const HBezierPatch& p = net.patches[0];
    const double s0 = 0.8 * unit(rng), t0 = 0.8 * unit(rng), ds = 0.2 * unit(rng) + 1e-3,
                 dt = 0.2 * unit(rng) + 1e-3;
    const HBezierConstants ku = hbezier_constants(p.u().alpha), kv = hbezier_constants(p.v().alpha);
    const BasisEnclosure eu =
        enclose(unit_jet(s0, p.u(), ku), unit_jet(s0 + ds, p.u(), ku), ds, unit_fourth_bound(p.u()));
    const BasisEnclosure ev =
        enclose(unit_jet(t0, p.v(), kv), unit_jet(t0 + dt, p.v(), kv), dt, unit_fourth_bound(p.v()));
    const CellDerivatives d =
        cell_derivatives(p.points(), net_differences(p.points()), eu, ev, unit_jet(s0 + ds / 2, p.u(), ku),
                         unit_jet(t0 + dt / 2, p.v(), kv), ds, dt);
    for (int i = 0; i <= 10; ++i) {
      for (int j = 0; j <= 10; ++j) {
        const double s = s0 + ds * i / 10.0, t = t0 + dt * j / 10.0;
        const UnitJet ju = unit_jet(s, p.u(), ku);
        for (std::size_t k = 0; k < 4; ++k) {
          for (std::size_t b = 0; b < 4; ++b) {
            CHECK(ju[k][b] >= eu[k][b].lo - 1e-12);
            CHECK(ju[k][b] <= eu[k][b].hi + 1e-12);
          }
        }
        const PatchJet jet = p.jet(s, t);
        CHECK(jet.dss.norm() <= d.ss * (1 + 1e-12));
        CHECK(jet.dst.norm() <= d.st * (1 + 1e-12));
        CHECK(jet.dtt.norm() <= d.tt * (1 + 1e-12));
        CHECK(jet.ds.cross(jet.dt).norm() >= d.normal_low * (1 - 1e-12));
      }
    }
  }
}

namespace {

// The second partials of the offset sheet S + a u (u = N / |N|, N = S_s x S_t)
// at one point, from the exact partials there: ss, st, tt.
std::array<Vec3, 3> offset_partials(const PointPartials& q, double a) {
  const Vec3 n = q[1][0].cross(q[0][1]);
  const Vec3 ns = q[2][0].cross(q[0][1]) + q[1][0].cross(q[1][1]);
  const Vec3 nt = q[1][1].cross(q[0][1]) + q[1][0].cross(q[0][2]);
  const Vec3 nss = q[3][0].cross(q[0][1]) + 2.0 * q[2][0].cross(q[1][1]) + q[1][0].cross(q[2][1]);
  const Vec3 nst = q[2][1].cross(q[0][1]) + q[2][0].cross(q[0][2]) + q[1][0].cross(q[1][2]);
  const Vec3 ntt = q[1][2].cross(q[0][1]) + 2.0 * q[1][1].cross(q[0][2]) + q[1][0].cross(q[0][3]);
  const double r = n.norm();
  const Vec3 u = n / r;
  const auto perp = [&](const Vec3& v) { return Vec3(v - u.dot(v) * u); };
  // u_xy = P N_xy / r - (P N_y (u . N_x) + u (P N_y . N_x) + P N_x (u . N_y)) / r^2
  const auto second = [&](const Vec3& nx, const Vec3& ny, const Vec3& nxy) {
    return Vec3(perp(nxy) / r -
                (perp(ny) * u.dot(nx) + u * perp(ny).dot(nx) + perp(nx) * u.dot(ny)) / (r * r));
  };
  return {q[2][0] + a * second(ns, ns, nss), q[1][1] + a * second(ns, nt, nst),
          q[0][2] + a * second(nt, nt, ntt)};
}

}  // namespace

TEST_CASE(
    "cell bounds: an offset sheet's second partials stay within offset_second, near a singular corner too",
    "[surfaces][bound]") {
  // The bundled basin's patch front_left: its rim corner at (s, t) = (0, 0)
  // is singular (S_s and S_t antiparallel there, N = 0).
  const Design design =
      read_design(std::string(FABMESH_SOURCE_DIR) + "/configs/examples/surface_basin_shell.yaml");
  const PatchNetwork net = build_patch_network(std::get<SurfaceDesign>(design.body).patches);
  const HBezierPatch& p = net.patches[0];
  const NetDifferences diff = net_differences(p.points());
  const HBezierConstants ku = hbezier_constants(p.u().alpha), kv = hbezier_constants(p.v().alpha);
  int bounded = 0;
  for (int k = 1; k <= 11; ++k) {
    const double dist = std::ldexp(1.0, -k);
    for (double width : {0.25, 0.5, 1.0}) {
      for (double along : {0.0, 0.5, 1.0}) {
        const double s0 = dist, t0 = along * dist, ds = width * dist, dt = width * dist;
        const BasisEnclosure eu =
            enclose(unit_jet(s0, p.u(), ku), unit_jet(s0 + ds, p.u(), ku), ds, unit_fourth_bound(p.u()));
        const BasisEnclosure ev =
            enclose(unit_jet(t0, p.v(), kv), unit_jet(t0 + dt, p.v(), kv), dt, unit_fourth_bound(p.v()));
        const CellDerivatives d = cell_derivatives(p.points(), diff, eu, ev, unit_jet(s0 + ds / 2, p.u(), ku),
                                                   unit_jet(t0 + dt / 2, p.v(), kv), ds, dt);
        for (double a : {6.0, -6.0}) {
          const OffsetSecond bound = offset_second(d, a);
          if (!std::isfinite(bound.ss)) continue;
          ++bounded;
          for (int i = 0; i <= 8; ++i) {
            for (int j = 0; j <= 8; ++j) {
              const double s = s0 + ds * i / 8.0, t = t0 + dt * j / 8.0;
              const auto o = offset_partials(
                  point_partials(p.points(), unit_jet(s, p.u(), ku), unit_jet(t, p.v(), kv)), a);
              INFO("cell at distance " << dist << ", width " << width << ", offset " << a << ", point " << s
                                       << ", " << t);
              CHECK(o[0].norm() <= bound.ss * (1 + 1e-9));
              CHECK(o[1].norm() <= bound.st * (1 + 1e-9));
              CHECK(o[2].norm() <= bound.tt * (1 + 1e-9));
            }
          }
        }
      }
    }
  }
  CHECK(bounded >= 40);  // most cells off the corner are bounded, so the checks above ran
}
