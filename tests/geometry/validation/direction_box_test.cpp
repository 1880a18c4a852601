// Direction boxes (direction_box.h): every box holds every direction of its
// arc or cone, sampled densely (in long double), over random faces seen
// from random points at every scale, faces whose plane passes through or
// near the point, thin and tiny faces; the boxes are tight (a cone beside a
// fan stays clear of the fan's arcs); and the box hierarchy answers like a
// scan.

#include "geometry/validation/detail/direction_box.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

using namespace fabmesh;
using namespace fabmesh::detail;

namespace {

/// The direction from v to a + s (b - a) + t (c - a), in long double.
std::array<long double, 3> direction(const Vec3& v, const std::array<Vec3, 3>& p, long double s,
                                     long double t) {
  std::array<long double, 3> d;
  long double n2 = 0;
  for (int k = 0; k < 3; ++k) {
    const long double a = p[0][k];
    d[k] = a + s * (static_cast<long double>(p[1][k]) - a) + t * (static_cast<long double>(p[2][k]) - a) -
           static_cast<long double>(v[k]);
    n2 += d[k] * d[k];
  }
  for (long double& x : d) x /= std::sqrt(n2);
  return d;
}

/// Requires the directions from v to a grid of points of face p (corners,
/// edges, inside) in `box`.
void require_holds(const DirectionBox& box, const Vec3& v, const std::array<Vec3, 3>& p) {
  constexpr int kSteps = 40;
  int outside = 0;
  for (int i = 0; i <= kSteps; ++i) {
    for (int j = 0; i + j <= kSteps; ++j) {
      if (i == 0 && j == 0 && p[0] == v) continue;  // the arc's apex: no direction
      const auto d =
          direction(v, p, static_cast<long double>(i) / kSteps, static_cast<long double>(j) / kSteps);
      for (int k = 0; k < 3; ++k) {
        outside +=
            !(static_cast<long double>(box.lo[k]) <= d[k] && d[k] <= static_cast<long double>(box.hi[k]));
      }
    }
  }
  INFO("corners " << p[0].transpose() << " / " << p[1].transpose() << " / " << p[2].transpose() << " from "
                  << v.transpose());
  REQUIRE(outside == 0);
}

double width(const DirectionBox& b, int k) { return b.hi[k] - b.lo[k]; }

}  // namespace

TEST_CASE("Direction boxes hold every direction of random arcs and cones", "[direction_box]") {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const auto random_point = [&](double scale) -> Vec3 {
    return Vec3(unit(rng), unit(rng), unit(rng)) * scale;
  };
  for (int round = 0; round < 3000; ++round) {
    const double scale = std::pow(10.0, unit(rng) * 6);
    const Vec3 v = random_point(scale);
    std::array<Vec3, 3> p{random_point(scale), random_point(scale), random_point(scale)};
    switch (round % 5) {
      case 1: {  // the plane of the face passes through v, or within 1e-9 of it
        const Vec3 n = (p[1] - p[0]).cross(p[2] - p[0]).normalized();
        const double off = round % 2 == 0 ? 0.0 : 1e-9 * scale;
        for (Vec3& x : p) x -= n * (n.dot(x - v) - off);
        break;
      }
      case 2: {  // a thin face, long and narrow
        p[2] = p[1] + (p[0] - p[1]) * 1e-4 + random_point(scale * 1e-6);
        break;
      }
      case 3: {  // a tiny face far away
        p[1] = p[0] + random_point(scale * 1e-6);
        p[2] = p[0] + random_point(scale * 1e-6);
        break;
      }
      case 4: {  // a face near v
        for (Vec3& x : p) x = v + (x - v) * 1e-3;
        break;
      }
      default:
        break;
    }
    require_holds(cone_box(v, p), v, p);
    std::array<Vec3, 3> arc{v, p[1], p[2]};
    require_holds(arc_box(arc, 0), v, arc);
  }
}

TEST_CASE("Direction boxes are tight: a tall face beside a fan stays clear of its arcs", "[direction_box]") {
  // A cap of a cylinder (radius 10) as a fan from rim point v = (10, 0, 0),
  // and a side face (rim points 3 and 4 of 2000, up to z = 5) seen from v:
  // its cone is a sliver of directions rising from the chord's direction.
  constexpr double kPi = 3.14159265358979323846;
  const auto rim = [&](int i, double z) {
    const double a = 2 * kPi * i / 2000;
    return Vec3(10 * std::cos(a), 10 * std::sin(a), z);
  };
  const Vec3 v = rim(0, 0);
  const DirectionBox cone = cone_box(v, {rim(3, 0), rim(4, 0), rim(4, 5)});
  int overlapping = 0;
  for (int i = 1; i + 1 < 2000; ++i) overlapping += overlap(arc_box({v, rim(i, 0), rim(i + 1, 0)}, 0), cone);
  REQUIRE(overlapping <= 3);
  // Its extremes along x: the chord to rim point 4 (x = -sin(pi 4 / 2000)) and the vertical.
  REQUIRE(cone.lo[0] > -std::sin(kPi * 4 / 2000) - 2 * kDirectionMargin);
  REQUIRE(cone.hi[0] < 2 * kDirectionMargin);
  // Exact boxes of simple arcs, within the margin.
  const DirectionBox quarter = arc_box({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, 0);
  REQUIRE(quarter.hi[0] == Approx(1 + kDirectionMargin));
  REQUIRE(quarter.lo[0] == Approx(-kDirectionMargin).margin(1e-8));
  REQUIRE(width(quarter, 2) < 3 * kDirectionMargin);
  const DirectionBox over = arc_box({Vec3(0, 0, 0), Vec3(1, 0, 1), Vec3(-1, 0, 1)}, 0);
  REQUIRE(over.hi[2] > 1.0);  // the arc passes through (0, 0, 1)
  REQUIRE(over.lo[2] == Approx(std::sqrt(0.5) - kDirectionMargin).margin(1e-8));
}

TEST_CASE("Direction boxes of faces through the centre, or nearly opposite, are the sphere's box",
          "[direction_box]") {
  const Vec3 v(1, 2, 3);
  const DirectionBox touching = cone_box(v, {v, Vec3(2, 2, 3), Vec3(1, 3, 3)});
  const DirectionBox around = cone_box(v, {Vec3(2, 2, 3), Vec3(0, 2.5, 3), Vec3(0, 1.5, 3)});  // v inside it
  for (const DirectionBox& b : {touching, around}) {
    for (int k = 0; k < 3; ++k) REQUIRE(width(b, k) == Approx(2 + 2 * kDirectionMargin));
  }
}

TEST_CASE("The direction box hierarchy finds what a scan finds", "[direction_box]") {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_real_distribution<double> size(0.0, 0.3);
  const auto random_box = [&]() {
    DirectionBox b;
    for (int k = 0; k < 3; ++k) {
      b.lo[k] = unit(rng);
      b.hi[k] = b.lo[k] + size(rng);
    }
    return b;
  };
  for (const std::size_t n : {1, 3, 4, 5, 17, 400}) {
    std::vector<DirectionBox> boxes(n);
    for (DirectionBox& b : boxes) b = random_box();
    const DirectionTree tree(boxes);
    for (int q = 0; q < 50; ++q) {
      const DirectionBox query = random_box();
      std::vector<std::uint32_t> found;
      tree.for_each_overlapping(query, [&](std::uint32_t i) {
        found.push_back(i);
        return true;
      });
      std::sort(found.begin(), found.end());
      std::vector<std::uint32_t> expected;
      for (std::uint32_t i = 0; i < n; ++i) {
        if (overlap(boxes[i], query)) expected.push_back(i);
      }
      REQUIRE(found == expected);
    }
  }
}
