// validate's defect locations (ValidationOptions::max_locations): each
// occurrence's faces and vertices, the first N of each kind, the count the
// total; and measures of meshes whose coordinates overflow doubles.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <vector>

#include "geometry/validation/validate.h"
#include "tests/geometry/mesh/shapes.h"

using namespace fabmesh;
using fabmesh::test::append;
using fabmesh::test::box;

namespace {

ValidationReport located(const TriangleSoup& soup, std::size_t max_locations) {
  ValidationOptions options;
  options.max_locations = max_locations;
  return validate(soup, options);
}

bool has_face(const DefectLocation& at, std::uint32_t f) {
  return std::find(at.faces.begin(), at.faces.end(), f) != at.faces.end();
}

}  // namespace

TEST_CASE("defect locations: a cube less one face lists each boundary edge's vertices and face",
          "[mesh][validate][locations]") {
  TriangleSoup open = box();
  open.triangles.pop_back();
  const ValidationReport r = located(open, 100);
  const DefectReport* d = r.find(Defect::BoundaryEdge);
  REQUIRE(d != nullptr);
  REQUIRE(d->count == 3);
  REQUIRE(d->locations.size() == 3);
  const auto removed = box().triangles.back();  // a copy: box() is a temporary
  for (const DefectLocation& at : d->locations) {
    REQUIRE(at.faces.size() == 1);
    REQUIRE(at.vertices.size() == 2);
    CHECK(at.vertices[0] < at.vertices[1]);
    // The edge is an edge of the removed face and of the face listed.
    for (const std::uint32_t v : at.vertices) {
      CHECK(std::count(removed.begin(), removed.end(), v) == 1);
      const auto& t = open.triangles[at.faces[0]];
      CHECK(std::count(t.begin(), t.end(), v) == 1);
    }
  }
  // At most N listed, the count still the total; none unless asked.
  CHECK(located(open, 2).find(Defect::BoundaryEdge)->locations.size() == 2);
  CHECK(located(open, 2).find(Defect::BoundaryEdge)->count == 3);
  CHECK(validate(open).find(Defect::BoundaryEdge)->locations.empty());
}

TEST_CASE("defect locations: intersecting, duplicate and degenerate faces, inverted components",
          "[mesh][validate][locations]") {
  TriangleSoup two = box();
  append(two, box(Vec3(0.5, 0.5, 0.5), Vec3(1.5, 1.5, 1.5)));
  const ValidationReport crossing = located(two, 1000);
  const DefectReport* si = crossing.find(Defect::SelfIntersection);
  REQUIRE(si != nullptr);
  REQUIRE(si->locations.size() == si->count);
  for (const DefectLocation& at : si->locations) {
    REQUIRE(at.faces.size() == 2);
    CHECK(at.faces[0] < 12);  // one face of each cube
    CHECK(at.faces[1] >= 12);
    REQUIRE(at.vertices.size() == 6);
    CHECK(std::equal(at.vertices.begin(), at.vertices.begin() + 3, two.triangles[at.faces[0]].begin()));
  }

  TriangleSoup doubled = box();
  doubled.triangles.push_back(doubled.triangles[4]);
  const ValidationReport doubled_report = located(doubled, 10);
  const DefectReport* dup = doubled_report.find(Defect::DuplicateFace);
  REQUIRE(dup != nullptr);
  REQUIRE(dup->locations.size() == 1);
  CHECK(dup->locations[0].faces == std::vector<std::uint32_t>{4, 12});

  TriangleSoup flat = box();
  flat.vertices.push_back(Vec3(0, 0, 0));
  flat.vertices.push_back(Vec3(1, 0, 0));
  flat.vertices.push_back(Vec3(2, 0, 0));
  const auto n = static_cast<std::uint32_t>(flat.vertices.size());
  flat.triangles.push_back({n - 3, n - 2, n - 1});
  const ValidationReport flat_report = located(flat, 10);
  const DefectReport* degenerate = flat_report.find(Defect::DegenerateFace);
  REQUIRE(degenerate != nullptr);
  REQUIRE(degenerate->locations.size() == 1);
  CHECK(degenerate->locations[0].faces == std::vector<std::uint32_t>{12});
  CHECK(degenerate->locations[0].vertices == std::vector<std::uint32_t>{n - 3, n - 2, n - 1});

  TriangleSoup apart = box();
  TriangleSoup inverted = box(Vec3(3, 0, 0), Vec3(4, 1, 1));
  for (auto& t : inverted.triangles) std::swap(t[1], t[2]);
  append(apart, inverted);
  const ValidationReport apart_report = located(apart, 10);
  const DefectReport* inv = apart_report.find(Defect::InvertedComponent);
  REQUIRE(inv != nullptr);
  REQUIRE(inv->locations.size() == 1);
  REQUIRE(inv->locations[0].faces.size() == 12);
  for (std::uint32_t f = 12; f < 24; ++f) CHECK(has_face(inv->locations[0], f));
  CHECK(inv->locations[0].vertices == std::vector<std::uint32_t>{8});  // its lowest vertex
}

TEST_CASE("validate: a cube of coordinates near 1e300 has no NaN volume or area", "[mesh][validate]") {
  const ValidationReport huge = validate(box(Vec3(0, 0, 0), Vec3(1e300, 1e300, 1e300)));
  CHECK(huge.valid());
  CHECK_FALSE(std::isnan(huge.volume));
  CHECK_FALSE(std::isnan(huge.area));
  CHECK(huge.volume == std::numeric_limits<double>::infinity());  // 1e900: beyond doubles, but positive
  CHECK(huge.area == std::numeric_limits<double>::infinity());
  const ValidationReport large = validate(box(Vec3(0, 0, 0), Vec3(1e100, 2e100, 1e100)));
  CHECK(large.volume == Approx(2e300));  // the products overflow no more
  CHECK(large.area == Approx(2 * (2e200 + 1e200 + 2e200)));
  CHECK(large.component_shells.at(0).volume == Approx(2e300));
}
