// validate with moved_from (test::validate_moved) against validate: the same verdict on meshes whose vertices
// moved.

#include <catch2/catch.hpp>
#include <random>

#include "geometry/core/errors.h"
#include "geometry/validation/validate.h"
#include "tests/geometry/mesh/shapes.h"
#include "tests/geometry/validation/moved_from.h"

namespace fabmesh {
namespace {

using test::validate_moved;

// The defect kinds and counts of a report, for comparison.
std::vector<std::pair<Defect, std::size_t>> defects_of(const ValidationReport& r) {
  std::vector<std::pair<Defect, std::size_t>> out;
  for (const DefectReport& d : r.defects) out.emplace_back(d.kind, d.count);
  return out;
}

void require_same_verdict(const TriangleSoup& original, const ValidationReport& report,
                          const TriangleSoup& moved) {
  const ValidationReport full = validate(moved);
  const ValidationReport cheap = validate_moved(original, report, moved);
  REQUIRE(cheap.valid() == full.valid());
  REQUIRE(defects_of(cheap) == defects_of(full));
  CHECK(cheap.intersecting_pairs == full.intersecting_pairs);
  CHECK(cheap.volume == full.volume);
  CHECK(cheap.genus == full.genus);
  CHECK(cheap.euler_characteristics == full.euler_characteristics);
}

}  // namespace

TEST_CASE("validate_moved: the same verdict as validate on many random perturbations",
          "[mesh][validate][draco]") {
  std::mt19937 rng(12345);
  const std::vector<TriangleSoup> shapes = {test::torus(2.0, 0.5, 24, 12), test::sphere(1.0, 16, 8),
                                            test::box()};
  int invalid = 0, valid = 0;
  for (const TriangleSoup& original : shapes) {
    const ValidationReport report = validate(original);
    REQUIRE(report.valid());
    // From invisible to folding: up to a few edge lengths.
    for (const double scale : {1e-9, 1e-4, 1e-2, 0.05, 0.1, 0.2, 0.5}) {
      for (int trial = 0; trial < 6; ++trial) {
        std::uniform_real_distribution<double> jitter(-scale, scale);
        TriangleSoup moved = original;
        for (Vec3& p : moved.vertices) p += Vec3(jitter(rng), jitter(rng), jitter(rng));
        require_same_verdict(original, report, moved);
        (validate(moved).valid() ? valid : invalid) += 1;
      }
    }
  }
  // Both verdicts occur, so the comparison says something about each.
  CHECK(valid > 20);
  CHECK(invalid > 20);
}

TEST_CASE("validate_moved: a collapsed vertex, a flattened box and a non-finite vertex are caught",
          "[mesh][validate][draco]") {
  const TriangleSoup original = test::box();
  const ValidationReport report = validate(original);
  TriangleSoup collapsed = original;
  collapsed.vertices[collapsed.triangles[0][0]] = collapsed.vertices[collapsed.triangles[0][1]];
  require_same_verdict(original, report, collapsed);
  CHECK_FALSE(validate_moved(original, report, collapsed).valid());
  TriangleSoup flat = original;
  for (Vec3& p : flat.vertices) p.z() = 0.0;
  require_same_verdict(original, report, flat);
  CHECK_FALSE(validate_moved(original, report, flat).valid());
  TriangleSoup nan = original;
  nan.vertices[3].x() = std::nan("");
  CHECK_FALSE(validate_moved(original, report, nan).valid());
  CHECK(validate_moved(original, report, nan).find(Defect::NonFiniteVertex) != nullptr);
}

TEST_CASE("validate_moved: an open surface keeps its boundary edges and only those",
          "[mesh][validate][draco]") {
  TriangleSoup open = test::box();
  open.triangles.pop_back();
  const ValidationReport report = validate(open);
  REQUIRE(report.find(Defect::BoundaryEdge) != nullptr);
  TriangleSoup moved = open;
  for (Vec3& p : moved.vertices) p *= 1.001;
  require_same_verdict(open, report, moved);
}

TEST_CASE("validate_moved: refuses a mesh whose triangles are not the original's",
          "[mesh][validate][errors]") {
  const TriangleSoup original = test::box();
  TriangleSoup other = original;
  std::swap(other.triangles[0], other.triangles[1]);
  CHECK_THROWS_AS(validate_moved(original, validate(original), other), InputError);
}

}  // namespace fabmesh
