// weld_candidate: the tolerance that closes a mesh whose copies of each
// vertex were written with a little noise, and none for a real hole.

#include "geometry/mesh/weld_hint.h"

#include <catch2/catch.hpp>
#include <cstdint>
#include <random>

#include "geometry/mesh/weld.h"
#include "geometry/validation/validate.h"
#include "tests/geometry/mesh/shapes.h"

using namespace fabmesh;

namespace {

/// Every corner of every triangle its own vertex, moved by up to `noise` per coordinate.
TriangleSoup jittered(const TriangleSoup& soup, double noise, std::uint32_t seed) {
  TriangleSoup s = test::unwelded(soup);
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> offset(-noise, noise);
  for (Vec3& p : s.vertices) p += Vec3(offset(random), offset(random), offset(random));
  return s;
}

}  // namespace

TEST_CASE("weld hint: a torus with 1e-5 of jitter per corner closes with the tolerance suggested",
          "[mesh][weld]") {
  const TriangleSoup noisy = jittered(test::torus(30.0, 10.0, 48, 24), 1e-5, 7);
  const WeldResult exact = weld(noisy);
  REQUIRE(validate(exact.soup).boundary_edges > 0);  // open: nothing coincides exactly
  const auto candidate = weld_candidate(exact.soup);
  REQUIRE(candidate);
  CHECK(candidate->closing_distance <= 2 * std::sqrt(3.0) * 1e-5);  // two copies at most this far apart
  CHECK(candidate->tolerance >= candidate->closing_distance);
  CHECK(candidate->tolerance <= 1.1 * candidate->closing_distance);  // two digits, rounded up
  CHECK(candidate->tolerance <= kWeldHintFraction * candidate->mean_edge);
  const ValidationReport welded = validate(weld(noisy, WeldOptions{candidate->tolerance}).soup);
  CHECK(welded.boundary_edges == 0);
  CHECK(welded.valid());
}

TEST_CASE("weld hint: a crack of one corner 1e-9 off closes with a tolerance of 1e-9", "[mesh][weld]") {
  TriangleSoup cracked = test::unwelded(test::box());
  cracked.vertices[0].x() += 1e-9;
  const WeldResult exact = weld(cracked);
  REQUIRE(validate(exact.soup).boundary_edges == 4);  // two edges of the stray corner, two of its twin
  const auto candidate = weld_candidate(exact.soup);
  REQUIRE(candidate);
  CHECK(candidate->closing_distance == Approx(1e-9).epsilon(1e-6));
  CHECK(validate(weld(cracked, WeldOptions{candidate->tolerance}).soup).valid());
}

TEST_CASE("weld hint: none for a closed mesh or a real hole", "[mesh][weld]") {
  CHECK_FALSE(weld_candidate(test::box()));
  TriangleSoup open = test::torus(30.0, 10.0, 48, 24);
  open.triangles.erase(open.triangles.begin(), open.triangles.begin() + 2);  // a hole of two faces
  CHECK_FALSE(weld_candidate(open));  // its border's vertices are an edge apart, not noise apart
}
