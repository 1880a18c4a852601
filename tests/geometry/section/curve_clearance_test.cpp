#include "geometry/section/curve_clearance.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "geometry/core/errors.h"
#include "geometry/curves/curve_spec.h"
#include "geometry/section/region.h"

using namespace fabmesh;

namespace {

CompositeCurve circle(Vec2 center, double r) {
  EllipseArcParams e;
  e.center = center;
  e.a = e.b = r;
  return CompositeCurve({Segment::ellipse_arc(e)}, true);
}

CompositeCurve rectangle(double w, double h) {
  CurveSpec spec;
  spec.closed = true;
  for (const Vec2& p : {Vec2(w, 0), Vec2(w, h), Vec2(0, h), Vec2(0, 0)}) {
    SegmentSpec s;
    s.kind = SegmentKind::Line;
    s.points = spec.segments.empty() ? std::vector<Vec2>{Vec2(0, 0), p} : std::vector<Vec2>{p};
    spec.segments.push_back(s);
  }
  return construct_curve(spec);
}

}  // namespace

TEST_CASE("clearance: two circles are exactly their centre distance minus the radii apart",
          "[section][clearance]") {
  const CompositeCurve a = circle({0, 0}, 100), b = circle({250, 30}, 60);
  const SegmentArc arc_a(a.segments()[0]), arc_b(b.segments()[0]);
  std::vector<ArcPiece> pieces;
  for (int k = 0; k < 12; ++k) pieces.push_back({&arc_a, k / 12.0, (k + 1) / 12.0, 0});
  for (int k = 0; k < 7; ++k) pieces.push_back({&arc_b, k / 7.0, (k + 1) / 7.0, 1});
  ClearanceOptions o;
  o.accuracy = 1e-6;
  const Clearance c = exact_clearance(pieces, o);
  const double exact = std::hypot(250.0, 30.0) - 160.0;
  CHECK(c.lower <= exact);
  CHECK(c.upper >= exact - 1e-9);
  CHECK(c.upper - c.lower <= 1e-6);
  CHECK(c.group_a != c.group_b);
  // Crossing curves: the clearance is 0.
  const CompositeCurve d = circle({150, 0}, 60);
  const SegmentArc arc_d(d.segments()[0]);
  pieces.resize(12);
  for (int k = 0; k < 5; ++k) pieces.push_back({&arc_d, k / 5.0, (k + 1) / 5.0, 1});
  CHECK(exact_clearance(pieces, o).upper <= 1e-6);
}

TEST_CASE(
    "region: holes whose exact curves come closer than the tolerance are refused, though their polygons "
    "do not meet",
    "[section][clearance][errors]") {
  // Polygons inscribed in circles lie inside them: the sampled holes are farther
  // apart than the exact ones, by up to twice the sampling deviation.
  const double tolerance = 0.5, gap = 0.3;
  RegionOptions o;
  o.tolerance = tolerance;
  o.outline_key = "outline";
  const std::vector<RegionHole> holes{{circle({300, 300}, 100), "holes[0] (ellipse)", "holes[0]"},
                                      {circle({500 + gap, 300}, 100), "holes[1] (ellipse)", "holes[1]"}};
  try {
    build_region(rectangle(1000, 600), holes, o);
    FAIL("closer than the tolerance, yet accepted");
  } catch (const GeometryError& e) {
    CHECK(e.where() == "holes[1]");
    REQUIRE(e.location().point.size() == 2);  // near the closest place, on holes[1]'s side
    CHECK(e.location().point[0] == Approx(400 + gap).margin(0.01));
    CHECK_THAT(std::string(e.what()), Catch::Contains("holes[1] (ellipse) comes within 0.3") &&
                                          Catch::Contains("holes[0] (ellipse)") &&
                                          Catch::Contains("closer than the 0.5 the mesh is built within"));
  }
  // Farther than the tolerance: accepted, with the exact clearance reported.
  const std::vector<RegionHole> apart{{circle({300, 300}, 100), "holes[0] (ellipse)", ""},
                                      {circle({500.8, 300}, 100), "holes[1] (ellipse)", ""}};
  const Region2 r = build_region(rectangle(1000, 600), apart, o);
  CHECK(r.min_clearance == Approx(0.8).margin(1e-3 * tolerance));
  CHECK(r.min_clearance <= 0.8);
  CHECK_THAT(r.clearance_where,
             Catch::Contains("holes[0] (ellipse) near (400") && Catch::Contains("holes[1]"));
  // A hole nearly touching the outline.
  const std::vector<RegionHole> edge{
      {circle({300, 100.2}, 100), "holes[0] (ellipse)", "design.yaml:9:5: holes[0]"}};
  CHECK_THROWS_AS(build_region(rectangle(1000, 600), edge, o), GeometryError);
}

TEST_CASE("clearance: many circles, each group split into several runs, match the exact distance",
          "[section][clearance]") {
  // Circles on a grid with exact clearances; each circle's pieces come in two
  // runs separated by another circle's, so groups are not contiguous.
  std::vector<CompositeCurve> circles;
  std::vector<Vec2> centres;
  std::vector<double> radii;
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 4; ++j) {
      centres.emplace_back(100.0 * i + 7.0 * j, 90.0 * j + 3.0 * i);
      radii.push_back(30.0 + 2.0 * ((i * 4 + j) % 5));
    }
  }
  for (std::size_t k = 0; k < centres.size(); ++k) circles.push_back(circle(centres[k], radii[k]));
  std::vector<std::unique_ptr<SegmentArc>> arcs;
  for (const CompositeCurve& c : circles) arcs.push_back(std::make_unique<SegmentArc>(c.segments()[0]));
  constexpr int kPieces = 300;
  std::vector<ArcPiece> pieces;
  for (int half : {0, 1}) {
    for (std::size_t k = 0; k < arcs.size(); ++k) {
      for (int p = half * kPieces / 2; p < (half + 1) * kPieces / 2; ++p)
        pieces.push_back({arcs[k].get(), double(p) / kPieces, double(p + 1) / kPieces, int(k)});
    }
  }
  double exact = std::numeric_limits<double>::infinity();
  for (std::size_t a = 0; a < centres.size(); ++a) {
    for (std::size_t b = a + 1; b < centres.size(); ++b)
      exact = std::min(exact, (centres[a] - centres[b]).norm() - radii[a] - radii[b]);
  }
  REQUIRE(exact > 0.0);
  ClearanceOptions o;
  o.accuracy = 1e-7;
  const Clearance c = exact_clearance(pieces, o);
  CHECK(c.lower <= exact);
  CHECK(c.upper >= exact - 1e-9);
  CHECK(c.upper - c.lower <= 1e-7);
  REQUIRE(c.group_a != c.group_b);
  const std::size_t ga = static_cast<std::size_t>(c.group_a), gb = static_cast<std::size_t>(c.group_b);
  CHECK((centres[ga] - centres[gb]).norm() - radii[ga] - radii[gb] == Approx(exact).margin(1e-6));
  // Pieces of one group are never compared: one circle alone has no clearance.
  std::vector<ArcPiece> alone;
  for (const ArcPiece& p : pieces) {
    if (p.group == 0) alone.push_back(p);
  }
  CHECK(exact_clearance(alone, o).group_a == -1);
}

TEST_CASE("clearance: 400000 pieces of two curves are searched without listing every pair of chunks",
          "[section][clearance]") {
  // 25000 chunks: every pair of them would be 156 million (3.7 GB). The
  // nearest-first search opens only what can hold the closest place.
  const CompositeCurve a = circle({0, 0}, 1000), b = circle({2100, 0}, 1000);
  const SegmentArc arc_a(a.segments()[0]), arc_b(b.segments()[0]);
  constexpr int kPieces = 200000;
  std::vector<ArcPiece> pieces;
  for (const auto& [arc, group] : {std::pair<const SegmentArc*, int>{&arc_a, 0}, {&arc_b, 1}}) {
    for (int k = 0; k < kPieces; ++k)
      pieces.push_back({arc, double(k) / kPieces, double(k + 1) / kPieces, group});
  }
  ClearanceOptions o;
  o.accuracy = 1e-6;
  const Clearance c = exact_clearance(pieces, o);
  CHECK(c.lower <= 100.0);
  CHECK(c.upper >= 100.0 - 1e-9);
  CHECK(c.upper - c.lower <= 1e-6);
  CHECK(c.a.x() == Approx(1000.0).margin(1e-3));
  CHECK(c.b.x() == Approx(1100.0).margin(1e-3));
}
