#include "geometry/sampling/offset_curve.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "geometry/core/errors.h"
#include "geometry/curves/curve_spec.h"

using namespace fabmesh;

namespace {

double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

// Smallest radius of curvature toward `side` over the segment, densely.
double min_radius(const Segment& seg, double side) {
  double k = 0.0;
  for (int i = 0; i <= 20000; ++i) k = std::max(k, side * seg.curvature(i / 20000.0));
  return k > 0.0 ? 1.0 / k : INFINITY;
}

std::vector<Segment> random_segments(std::mt19937& rng, int count) {
  std::uniform_real_distribution<double> coord(-5.0, 5.0), shape(-1.5, 1.0), alpha(0.2, 3.0);
  std::vector<Segment> out;
  for (int k = 0; k < count; ++k) {
    std::array<Vec2, 4> p;
    for (auto& q : p) q = Vec2(coord(rng), coord(rng));
    switch (k % 3) {
      case 0:
        out.push_back(Segment::tbezier(p, shape(rng), shape(rng)));
        break;
      case 1:
        out.push_back(Segment::hbezier(p, alpha(rng), shape(rng), shape(rng)));
        break;
      default:
        out.push_back(Segment::quasi_bspline_span(p, std::uniform_real_distribution<double>(-8, 1)(rng),
                                                  std::uniform_real_distribution<double>(-8, 1)(rng)));
    }
  }
  return out;
}

}  // namespace

TEST_CASE("offset sampling: the offset polyline stays within its reported bound, measured densely",
          "[sampling][offset]") {
  std::mt19937 rng(11);
  int sampled = 0;
  for (const Segment& seg : random_segments(rng, 30)) {
    for (double side : {1.0, -1.0}) {
      const double radius = min_radius(seg, side);
      const double wall = std::min(0.5, 0.7 * radius);
      if (!(wall > 1e-3)) continue;
      for (double tol : {0.01, 1e-3}) {
        const OffsetSpec spec{wall, side, "wall", "test"};
        SampleOptions opt;
        opt.tolerance = tol;
        double achieved = 0.0;
        const std::vector<double> params = sample_parameters(OffsetChordBound(seg, spec), opt, &achieved);
        CHECK(achieved <= tol);
        double worst = 0.0;
        for (std::size_t k = 0; k + 1 < params.size(); ++k) {
          const Vec2 a = offset_jet(seg, spec, params[k]).point,
                     b = offset_jet(seg, spec, params[k + 1]).point;
          for (int i = 1; i < 40; ++i) {
            const double s = params[k] + (params[k + 1] - params[k]) * i / 40.0;
            worst = std::max(worst, distance_to_segment(offset_jet(seg, spec, s).point, a, b));
          }
        }
        CHECK(worst <= achieved);
        ++sampled;
      }
    }
  }
  CHECK(sampled > 20);
}

TEST_CASE(
    "offset sampling: a wall thicker than the smallest radius of curvature is refused, a thinner one passes",
    "[sampling][offset]") {
  // A sharp T-Bézier bend: its tightest point lies between the initial samples.
  const Segment seg = Segment::tbezier({Vec2(0, 0), Vec2(10, 0.3), Vec2(10.3, 0), Vec2(0.2, 0.4)}, 0.0, 0.0);
  for (double side : {1.0, -1.0}) {
    const double radius = min_radius(seg, side);
    if (!std::isfinite(radius)) continue;
    SampleOptions opt;
    opt.tolerance = 1e-3;
    INFO("side " << side << ", radius " << radius);
    CHECK_NOTHROW(sample_parameters(OffsetChordBound(seg, {0.95 * radius, side, "wall", "test"}), opt));
    CHECK_THROWS_AS(sample_parameters(OffsetChordBound(seg, {1.01 * radius, side, "wall", "test"}), opt),
                    GeometryError);
  }
}

TEST_CASE("sampling estimate: min_chord_count never exceeds the chords the sampler makes",
          "[sampling][budget]") {
  std::mt19937 rng(5);
  for (const Segment& seg : random_segments(rng, 24)) {
    for (double tol : {0.1, 1e-3, 1e-6}) {
      SampleOptions opt;
      opt.tolerance = tol;
      const double estimate = min_chord_count(seg, tol, opt.min_pieces_per_segment);
      const std::size_t chords = sample_segment_parameters(seg, opt).size() - 1;
      CHECK(estimate <= static_cast<double>(chords));
      CHECK(estimate >= 0.2 * static_cast<double>(chords));  // a useful estimate, not a token one
    }
  }
}
