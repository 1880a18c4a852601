#include "geometry/mesh/vessel.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "geometry/core/errors.h"
#include "geometry/core/soup.h"
#include "geometry/curves/curve_spec.h"
#include "geometry/fairing/gauss_legendre.h"
#include "geometry/mesh/revolve.h"
#include "geometry/validation/validate.h"
#include "tests/geometry/mesh/point_triangle.h"

using namespace fabmesh;
using fabmesh::test::point_triangle_distance;

namespace {

CompositeCurve golden_profile() {
  CurveSpec spec;
  spec.family = CurveFamily::QuasiBSpline;
  spec.bspline_points = {{1.5, 6}, {1, 5}, {2, 4}, {3, 3}, {1.5, 2}};
  return construct_curve(spec);
}

CompositeCurve arc_profile(Vec2 center, double radius, double from, double to) {
  EllipseArcParams e;
  e.center = center;
  e.a = e.b = radius;
  e.from_deg = from;
  e.to_deg = to;
  return CompositeCurve({Segment::ellipse_arc(e)}, false);
}

// Pappus by quadrature of the exact profile: volume pi |int r^2 z' dt| of the
// solid closed to the axis, and the lateral area 2 pi int r |r'| dt.
struct Exact {
  double volume = 0.0, lateral_area = 0.0;
};

Exact pappus(const CompositeCurve& c) {
  const QuadratureRule q = gauss_legendre(40);
  Exact e;
  double signed_volume = 0.0;
  for (const Segment& s : c.segments()) {
    for (std::size_t i = 0; i < q.nodes.size(); ++i) {
      const CurveJet j = s.jet(q.nodes[i]);
      signed_volume += q.weights[i] * M_PI * j[0].x() * j[0].x() * j[1].y();
      e.lateral_area += q.weights[i] * 2 * M_PI * j[0].x() * j[1].norm();
    }
  }
  e.volume = std::abs(signed_volume);
  return e;
}

// Largest distance from random points of the exact surface of revolution to
// the mesh (an upper bound: only triangles near the point's angle are tried).
double surface_to_mesh_distance(const CompositeCurve& profile, const TriangleSoup& soup, int samples) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(0, 1);
  double worst = 0.0;
  for (int k = 0; k < samples; ++k) {
    const Segment& seg = profile.segments()[rng() % profile.size()];
    const Vec2 q = seg.point(u(rng));
    const double theta = 2 * M_PI * u(rng);
    const Vec3 p(q.x() * std::cos(theta), q.x() * std::sin(theta), q.y());
    double best = INFINITY;
    for (const auto& t : soup.triangles) {
      const Vec3& a = soup.vertices[t[0]];
      const Vec3 centroid = (a + soup.vertices[t[1]] + soup.vertices[t[2]]) / 3.0;
      if ((centroid - p).norm() > 0.5) continue;
      best = std::min(best, point_triangle_distance(p, a, soup.vertices[t[1]], soup.vertices[t[2]]));
    }
    worst = std::max(worst, best);
  }
  return worst;
}

std::size_t axis_vertices(const TriangleSoup& soup) {
  std::size_t n = 0;
  for (const Vec3& p : soup.vertices) n += p.x() == 0.0 && p.y() == 0.0;
  return n;
}

}  // namespace

TEST_CASE("vessel: solid golden profile converges to the Pappus volume and area", "[mesh][vessel]") {
  const CompositeCurve profile = golden_profile();
  const Exact exact = pappus(profile);
  const double r_top = 1.5, r_bottom = 1.5;  // both ends off the axis: closed by flat discs
  const double area = exact.lateral_area + M_PI * (r_top * r_top + r_bottom * r_bottom);
  double previous_volume_error = INFINITY, previous_area_error = INFINITY;
  for (double tol : {0.02, 0.005, 0.00125}) {
    VesselOptions o;
    o.tolerance = tol;
    const VesselMesh v = build_vessel(profile, o);
    CHECK(v.max_deviation <= tol);
    const ValidationReport r = validate(v.soup);
    REQUIRE(r.valid());
    CHECK(r.genus == 0);
    CHECK(r.components == 1);
    const double volume_error = std::abs(r.volume - exact.volume);
    const double area_error = std::abs(r.area - area);
    CHECK(volume_error <= tol * area);  // the surface moved by at most tol everywhere
    CHECK(volume_error < 0.5 * previous_volume_error);
    CHECK(area_error < 0.5 * previous_area_error);
    previous_volume_error = volume_error;
    previous_area_error = area_error;
  }
}

TEST_CASE("vessel: every point of the exact surface is within tolerance of the mesh", "[mesh][vessel]") {
  const CompositeCurve profile = golden_profile();
  for (double tol : {0.05, 0.01}) {
    VesselOptions o;
    o.tolerance = tol;
    const VesselMesh v = build_vessel(profile, o);
    CHECK(surface_to_mesh_distance(profile, v.soup, 300) <= tol);
  }
}

TEST_CASE("revolve: a profile from axis to axis gives single pole vertices and no zero-area triangles",
          "[mesh][revolve]") {
  const CompositeCurve sphere = arc_profile({0, 0}, 2.0, -90, 90);
  VesselOptions o;
  o.tolerance = 0.002;
  const VesselMesh v = build_vessel(sphere, o);
  CHECK(axis_vertices(v.soup) == 2);
  const ValidationReport r = validate(v.soup);
  REQUIRE(r.valid());
  CHECK(r.degenerate_faces == 0);
  CHECK(r.genus == 0);
  const double exact_volume = 4.0 / 3.0 * M_PI * 8.0, exact_area = 16 * M_PI;
  CHECK(std::abs(r.volume - exact_volume) <= o.tolerance * exact_area);
  CHECK(r.area == Approx(exact_area).epsilon(0.01));
  CHECK(surface_to_mesh_distance(sphere, v.soup, 300) <= o.tolerance);
}

TEST_CASE("revolve: a closed profile off the axis gives a torus of genus 1", "[mesh][revolve]") {
  EllipseArcParams e;
  e.center = Vec2(3, 1);
  e.a = e.b = 1;
  const CompositeCurve ring({Segment::ellipse_arc(e)}, true);
  VesselOptions o;
  o.tolerance = 0.005;
  const VesselMesh v = build_vessel(ring, o);
  CHECK(axis_vertices(v.soup) == 0);
  const ValidationReport r = validate(v.soup);
  REQUIRE(r.valid());
  CHECK(r.genus == 1);
  const double exact_volume = 2 * M_PI * M_PI * 3, exact_area = 4 * M_PI * M_PI * 3;
  CHECK(std::abs(r.volume - exact_volume) <= o.tolerance * exact_area);
}

TEST_CASE("revolve: a profile running along the axis between two parts gives two closed bodies",
          "[mesh][revolve]") {
  CurveSpec spec;
  for (auto [a, b] : {std::pair{Vec2(0, 0), Vec2(1, 1)},
                      {Vec2(1, 1), Vec2(0, 2)},
                      {Vec2(0, 2), Vec2(0, 3)},
                      {Vec2(0, 3), Vec2(1, 4)},
                      {Vec2(1, 4), Vec2(0, 5)}}) {
    SegmentSpec s;
    s.kind = SegmentKind::Line;
    s.points = spec.segments.empty() ? std::vector<Vec2>{a, b} : std::vector<Vec2>{b};
    spec.segments.push_back(s);
  }
  VesselOptions o;
  o.tolerance = 0.01;
  const VesselMesh v = build_vessel(construct_curve(spec), o);
  CHECK(v.section.loops.size() == 2);
  const ValidationReport r = validate(v.soup);
  REQUIRE(r.valid());
  CHECK(r.components == 2);
  CHECK(axis_vertices(v.soup) == 4);
  // Two double cones of radius 1 and height 2: volume 2 * (2/3) pi, lateral area 4 * pi * sqrt(2).
  CHECK(std::abs(r.volume - 4.0 / 3.0 * M_PI) <= o.tolerance * 4 * M_PI * std::sqrt(2.0));
}

TEST_CASE("vessel: a straight shell matches the exact cup volume and is a valid solid", "[mesh][vessel]") {
  // A cylinder wall R = 2, height 5: exact V = pi R^2 H - pi (R - w)^2 (H - b).
  const double radius = 2, height = 5, wall = 0.25, base = 0.5;
  CurveSpec spec;
  SegmentSpec s;
  s.kind = SegmentKind::Line;
  s.points = {Vec2(radius, 0), Vec2(radius, height)};
  spec.segments = {s};
  VesselOptions o;
  o.mode = BodyMode::Shell;
  o.wall = wall;
  o.base = base;
  o.tolerance = 0.001;
  const VesselMesh v = build_vessel(construct_curve(spec), o);
  const ValidationReport r = validate(v.soup);
  REQUIRE(r.valid());
  CHECK(r.genus == 0);
  const double ri = radius - wall;
  const double exact_volume = M_PI * radius * radius * height - M_PI * ri * ri * (height - base);
  const double exact_area = 2 * M_PI * radius * height + 2 * M_PI * ri * (height - base) +
                            M_PI * (radius * radius - ri * ri) + M_PI * radius * radius + M_PI * ri * ri;
  CHECK(std::abs(r.volume - exact_volume) <= o.tolerance * exact_area);
  CHECK(r.area == Approx(exact_area).epsilon(1e-3));
}

TEST_CASE("vessel: the golden shell is valid, thinner than the solid, with its rim open", "[mesh][vessel]") {
  VesselOptions solid, shell;
  solid.tolerance = shell.tolerance = 0.01;
  shell.mode = BodyMode::Shell;
  shell.wall = 0.3;
  shell.base = 0.4;
  const CompositeCurve profile = golden_profile();
  const ValidationReport rs = validate(build_vessel(profile, solid).soup);
  const ValidationReport rh = validate(build_vessel(profile, shell).soup);
  REQUIRE(rh.valid());
  CHECK(rh.genus == 0);
  CHECK(rh.volume > 0.2 * rs.volume);
  CHECK(rh.volume < 0.6 * rs.volume);
}

TEST_CASE("vessel bad input: axis crossing, self-crossing, thick wall, bad tolerance, budget",
          "[mesh][vessel][errors]") {
  auto lines = [](std::vector<Vec2> pts) {
    CurveSpec spec;
    for (std::size_t i = 1; i < pts.size(); ++i) {
      SegmentSpec s;
      s.kind = SegmentKind::Line;
      s.points = i == 1 ? std::vector<Vec2>{pts[0], pts[1]} : std::vector<Vec2>{pts[i]};
      spec.segments.push_back(s);
    }
    return construct_curve(spec);
  };
  VesselOptions o;
  o.tolerance = 0.01;
  REQUIRE_THROWS_WITH(build_vessel(lines({{1, 0}, {-0.5, 1}, {1, 2}}), o),
                      Catch::Contains("crosses the axis"));
  REQUIRE_THROWS_WITH(build_vessel(lines({{1, 0}, {2, 2}, {2, 0.5}, {0.5, 1.5}, {1, 3}}), o),
                      Catch::Contains("crosses itself"));
  VesselOptions thick = o;
  thick.mode = BodyMode::Shell;
  thick.wall = 0.5;
  REQUIRE_THROWS_WITH(build_vessel(arc_profile({0, 2}, 0.4, -60, 60), thick), Catch::Contains("too thick"));
  thick.wall = 1.5;  // wider than the vessel itself
  REQUIRE_THROWS_WITH(build_vessel(lines({{1, 0}, {1, 3}}), thick), Catch::Contains("too thick"));
  VesselOptions bad = o;
  bad.tolerance = 0;
  REQUIRE_THROWS_AS(build_vessel(golden_profile(), bad), RangeError);
  VesselOptions budget = o;
  budget.tolerance = 1e-5;
  budget.max_triangles = 100000;
  REQUIRE_THROWS_AS(build_vessel(golden_profile(), budget), BudgetError);
  VesselOptions memory = o;
  const VesselMesh fits = build_vessel(golden_profile(), o);
  memory.max_bytes = fits.soup.triangles.size() * 12 + fits.soup.vertices.size() * 24;  // exactly its arrays
  CHECK(build_vessel(golden_profile(), memory).soup.triangles.size() == fits.soup.triangles.size());
  memory.max_bytes -= 1;
  REQUIRE_THROWS_WITH(build_vessel(golden_profile(), memory), Catch::Contains("GB of memory"));
}
