#include "geometry/fairing/build_curve.h"

#include <catch2/catch.hpp>

#include "geometry/core/errors.h"

using namespace fabmesh;

namespace {

// The closed G2 outline of docs/math/curves.md 1.1: every segment G2-joined to its predecessor, the
// first to the last.
CurveSpec g2_loop() {
  CurveSpec spec;
  spec.closed = true;
  spec.key = "curve";
  for (const Vec2& p : {Vec2(100, 0), Vec2(100, 60), Vec2(0, 60), Vec2(0, 0)}) {
    SegmentSpec s;
    s.points = {p};
    s.lambda = s.mu = 0.5;
    s.join = JoinSpec{Continuity::G2, 1.0, 0.0, 1.0, 0.0};
    spec.segments.push_back(s);
  }
  return spec;
}

}  // namespace

TEST_CASE("build_curve: fairing that loses a declared G2 is an error naming the joint and what fairing did",
          "[curves][fairing][errors]") {
  CurveSpec spec = g2_loop();
  CHECK_NOTHROW(build_curve(spec));  // unfaired: G2 everywhere
  spec.fair = FairMode::CurvatureVariation;
  try {
    build_curve(spec);
    FAIL("a lost G2 passed");
  } catch (const GeometryError& e) {
    CHECK(e.where() == "curve");  // the message's place: io gives the key's file, line and column
    CHECK_THAT(std::string(e.what()), Catch::StartsWith("joint 1 (segments 1 -> 2): ") &&
                                          Catch::Contains("declared G2") && Catch::Contains("is G1") &&
                                          Catch::Contains("segment 1 (lambda 0.5 ->") &&
                                          Catch::Contains("fair_keeps: G1"));
  }
  // The design accepts G1 after fairing: built, and the report still says what was lost.
  spec.fair_keeps = Continuity::G1;
  const BuiltCurve built = build_curve(spec);
  REQUIRE(built.joints.size() == 4);
  for (std::size_t i = 0; i < built.joints.size(); ++i) {
    CHECK(built.declared[i] == Continuity::G2);
    CHECK(built.joints[i].achieved >= Continuity::G1);
  }
  // Accepting G2 is accepting nothing less than declared.
  spec.fair_keeps = Continuity::G2;
  CHECK_THROWS_AS(build_curve(spec), GeometryError);
}
