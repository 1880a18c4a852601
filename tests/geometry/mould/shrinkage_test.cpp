#include "geometry/mould/shrinkage.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "geometry/core/errors.h"
#include "geometry/curves/curve_spec.h"
#include "geometry/mould/mould.h"
#include "tests/geometry/mould/mould_fixtures.h"

using namespace fabmesh;
using namespace fabmesh::test;

TEST_CASE("shrinkage: the factor is 1 / (1 - s), so master x (1 - s) is the fired size",
          "[mould][shrinkage]") {
  CHECK(shrinkage_factor(0.0) == 1.0);
  CHECK(shrinkage_factor(0.5) == 2.0);
  CHECK(shrinkage_factor(0.75) == 4.0);
  for (const double s : {0.05, 0.1, 0.12, 0.13, 0.2, 0.9}) {
    const double f = shrinkage_factor(s);
    CHECK(f == 1.0 / (1.0 - s));
    // Correctly rounded division: (1 - s) f is 1 within one rounding of the product.
    CHECK(std::abs((1.0 - s) * f - 1.0) <= 2.0 * std::numeric_limits<double>::epsilon());
  }
  for (const double bad : {-0.01, 1.0, 1.5, std::nan("")}) {
    try {
      shrinkage_factor(bad);
      FAIL("accepted shrinkage " << bad);
    } catch (const RangeError& e) {
      CHECK(e.field() == "shrinkage");
    }
  }
}

TEST_CASE("shrinkage: a scaled curve is the curve scaled point for point, in every family",
          "[mould][shrinkage]") {
  CurveSpec golden;
  golden.family = CurveFamily::QuasiBSpline;
  golden.bspline_points = {{1.5, 6}, {1, 5}, {2, 4}, {3, 3}, {1.5, 2}};
  golden.bspline_lambdas = {-3, 1, -6};
  EllipseArcParams e;
  e.center = {2, 3};
  e.a = 1.5;
  e.b = 0.7;
  e.rotation_deg = 20;
  e.from_deg = -80;
  e.to_deg = 100;
  const std::vector<CompositeCurve> curves = {
      construct_curve(golden),
      CompositeCurve({Segment::tbezier({Vec2(1, 0), Vec2(3, 1), Vec2(2, 3), Vec2(1, 4)}, -1.5, 0.5),
                      Segment::hbezier({Vec2(1, 4), Vec2(0.5, 4.5), Vec2(1.5, 5), Vec2(2, 6)}, 1.0, 0.2, 0.3),
                      Segment::ellipse_arc(e), Segment::line(Vec2(3, 1), Vec2(4, 2))},
                     false)};
  const double f = shrinkage_factor(0.12);
  for (const CompositeCurve& c : curves) {
    const CompositeCurve scaled = scale_curve(c, f);
    REQUIRE(scaled.size() == c.size());
    for (int i = 0; i <= 100; ++i) {
      const double g = static_cast<double>(c.size()) * i / 100.0;
      const Vec2 want = f * c.point(g);
      CHECK((scaled.point(g) - want).norm() <= 1e-14 * std::max(1.0, want.norm()));
    }
    for (std::size_t k = 0; k < c.size(); ++k) {
      CHECK(scaled.segments()[k].kind() == c.segments()[k].kind());
      CHECK(scaled.segments()[k].lambda() == c.segments()[k].lambda());
      CHECK(scaled.segments()[k].mu() == c.segments()[k].mu());
    }
  }
}

TEST_CASE("shrinkage: the mould's cavity is the fired vessel scaled by 1 / (1 - s)", "[mould][shrinkage]") {
  const CompositeCurve profile = example_profile("vessel_golden_solid.yaml");
  MouldOptions o = cm_options();
  o.shrinkage = 0.0;
  const Mould fired = build_mould(profile, o);
  o.shrinkage = 0.12;
  const Mould m = build_mould(profile, o);
  const double f = 1.0 / (1.0 - 0.12);
  CHECK(m.sizes.factor == f);
  // The golden profile runs from (1.5, 6) to (1.5, 2): 4 tall as designed.
  CHECK(m.sizes.fired_height == Approx(4.0).epsilon(1e-15));
  CHECK(m.sizes.master_height == Approx(4.0 * f).epsilon(1e-15));
  CHECK(m.section.rim_radius == Approx(1.5 * f).epsilon(1e-15));
  CHECK(m.section.rim_z == Approx(6.0 * f).epsilon(1e-15));
  CHECK(m.sizes.master_diameter == Approx(m.sizes.fired_diameter * f).epsilon(1e-15));
  // Volumes scale with f^3 (the exact vessel) while the reservoir keeps its height.
  CHECK(m.vessel_volume == Approx(fired.vessel_volume * f * f * f).epsilon(1e-12));
  CHECK(m.section.z_top - m.section.rim_z == Approx(o.spare).epsilon(1e-15));
}
