// fit_draco: one encoding, the decoded mesh matched to the input exactly,
// quantizations that fold or collapse faces refused.

#include "io/mesh/draco.h"

#include <catch2/catch.hpp>

#include "geometry/core/errors.h"
#include "geometry/validation/validate.h"
#include "tests/geometry/mesh/shapes.h"
#include "tests/geometry/validation/moved_from.h"

namespace fabmesh {
namespace {

using test::validate_moved;

bool valid(const TriangleSoup& decoded) { return validate(decoded).valid(); }

// A tetrahedron over the unit right triangle with its apex at height h.
TriangleSoup tent(double h) {
  TriangleSoup s;
  s.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0.3, 0.3, h)};
  s.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  return s;
}

}  // namespace

TEST_CASE("draco: fit_draco's bytes are the plain encoding and decode to its decoded mesh",
          "[io][mesh][draco]") {
  for (const TriangleSoup& soup : {test::torus(20.0, 5.0, 90, 40), test::sphere(10.0, 40, 20)}) {
    const DracoFit fit = fit_draco(soup, 0.01, valid, "drc");
    CHECK(fit.bytes == encode_draco_bits(soup, fit.bits));  // the same file as before, deterministic
    CHECK_NOTHROW(require_draco_matches(fit.bytes, fit));
    CHECK(fit.decoded.triangles == soup.triangles);
    const TriangleSoup read = parse_draco(fit.bytes, "drc");
    CHECK(read.triangles.size() == soup.triangles.size());
    double moved = 0.0;
    for (std::size_t i = 0; i < soup.vertices.size(); ++i)
      moved = std::max(moved, (fit.decoded.vertices[i] - soup.vertices[i]).norm());
    CHECK(moved == fit.max_displacement);
    CHECK(moved <= 0.01);
    CHECK(validate(read).valid());
  }
}

TEST_CASE("draco: a quantization that flattens a face is refused and a finer one chosen",
          "[io][mesh][draco]") {
  // At 7 bits (step 1/127) the apex at 0.003 rounds to 0: the tent is flat,
  // its faces fold onto each other. At 8 bits (step 1/255) it stays up.
  const TriangleSoup soup = tent(0.003);
  const ValidationReport report = validate(soup);
  REQUIRE(report.valid());
  REQUIRE_FALSE(validate(parse_draco(encode_draco_bits(soup, 7), "7 bits")).valid());
  int tries = 0;
  const DracoFit fit = fit_draco(
      soup, 0.01,
      [&](const TriangleSoup& decoded) {
        ++tries;
        return validate_moved(soup, report, decoded).valid();
      },
      "drc");
  CHECK(fit.bits == 8);
  CHECK(tries == 2);
  CHECK_NOTHROW(require_draco_matches(fit.bytes, fit));
  CHECK(validate(parse_draco(fit.bytes, "drc")).valid());
}

TEST_CASE("draco: when every quantization collapses the mesh, the OutputError says faces collapse or fold",
          "[io][mesh][draco][errors]") {
  // The apex 1e-12 above the base: every quantization puts it on the base,
  // onto vertex 0 (two vertices at one position: the match falls back to the
  // id-tagged encoding, which must reach the same verdict).
  TriangleSoup soup = tent(1e-12);
  soup.vertices[3] = Vec3(0, 0, 1e-12);
  const ValidationReport report = validate(soup);
  REQUIRE(report.valid());
  const auto accept = [&](const TriangleSoup& decoded) {
    return validate_moved(soup, report, decoded).valid();
  };
  CHECK_THROWS_AS(fit_draco(soup, 0.01, accept, "drc"), OutputError);
  CHECK_THROWS_WITH(fit_draco(soup, 0.01, accept, "drc"),
                    Catch::Contains("drc: at every Draco quantization") &&
                        Catch::Contains("the decoded mesh is no longer valid (faces collapse or fold)"));
}

TEST_CASE("draco: quantizations that put two vertices at one position are passed over without a try",
          "[io][mesh][draco]") {
  // A second tent standing on the apex of the first, its corner 2e-6 beside
  // it: the two vertices meet at one position at the fewest bits (7) and for
  // many more. With distinct_positions the search finds the first bit count
  // that keeps them apart by the quantizer's prediction and asks `accept`
  // about that one first (without it: every bit count up to it in turn, each
  // encoded, decoded and validated).
  TriangleSoup soup = tent(0.5);
  const TriangleSoup other = tent(0.5);
  for (const Vec3& p : other.vertices) soup.vertices.push_back(p + Vec3(0.3 + 2e-6, 0.3, 0.5));
  for (const auto& t : other.triangles) soup.triangles.push_back({t[0] + 4, t[1] + 4, t[2] + 4});
  const ValidationReport report = validate(soup);
  REQUIRE(report.valid());
  int tries = 0;
  DracoAccept accept;
  accept.accept = [&](const TriangleSoup& decoded) {
    ++tries;
    return validate_moved(soup, report, decoded).valid();
  };
  accept.distinct_positions = true;
  const DracoFit fit = fit_draco(soup, 0.01, accept, "drc");
  CHECK(tries == 1);
  CHECK(fit.bits >= 12);
  CHECK(validate(parse_draco(fit.bytes, "drc")).valid());
  // One bit fewer puts the two corners at one position: the decoded mesh is not valid.
  CHECK_FALSE(validate(parse_draco(encode_draco_bits(soup, fit.bits - 1), "fewer")).valid());
}

TEST_CASE("draco: a proven margin bounds the bits the search tries", "[io][mesh][draco]") {
  // An apex 0.0008 high folds onto the base up to 9 bits and stands from 10.
  // The fewest bits for the tolerance (7) and the next fail; then the search
  // tries the fewest bits a margin of 1e-4 covers (14), not the most worth
  // trying (about 23), and bisects below: the same answer in fewer tries.
  const TriangleSoup soup = tent(0.0008);
  const ValidationReport report = validate(soup);
  REQUIRE(report.valid());
  const auto search = [&](double margin) {
    DracoAccept accept;
    int tries = 0;
    accept.accept = [&](const TriangleSoup& decoded) {
      ++tries;
      return validate_moved(soup, report, decoded).valid();
    };
    accept.margin = margin;
    const int bits = fit_draco(soup, 0.01, accept, "drc").bits;
    return std::make_pair(bits, tries);
  };
  const auto [bits_without, tries_without] = search(0.0);
  const auto [bits_with, tries_with] = search(1e-4);
  CHECK(bits_without == 10);
  CHECK(bits_with == 10);
  CHECK(tries_with == 6);  // 7, 8, 14, 11, 9, 10
  CHECK(tries_with < tries_without);
}

TEST_CASE("draco: a tolerance below what 30 bits can keep is refused with the measured error",
          "[io][mesh][draco][errors]") {
  const TriangleSoup soup =
      test::box(Vec3(1e6 + 0.1, 1e6 + 0.1, 1e6 + 0.1), Vec3(1e6 + 1.1, 1e6 + 1.1, 1e6 + 1.1));
  // float32 holds 1e6 + 0.1 only to 1/32: no quantization keeps it within 1e-6.
  CHECK_THROWS_WITH(fit_draco(soup, 1e-6, valid, "drc"),
                    Catch::Contains("drc: Draco cannot keep every vertex within"));
}

}  // namespace fabmesh
