#include "geometry/kitchen/pieces.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "geometry/core/errors.h"
#include "geometry/section/simple_polygon.h"
#include "tests/geometry/section/region_shapes.h"

using namespace fabmesh;

namespace {

// An L-shaped top: a 3600 x 650 run along x and a 650 x 2400 leg up the
// left wall, a sink in the run and a cooktop in the leg.
Region2 l_top(double sink_x = 1900.0) {
  const CompositeCurve outline =
      test::polygon({{0, 0}, {3600, 0}, {3600, 650}, {650, 650}, {650, 2400}, {0, 2400}});
  std::vector<RegionHole> holes{
      {test::rounded_rect(sink_x - 380, 120, sink_x + 380, 540, 40), "holes[0]", "holes[0]"},
      {test::rounded_rect(85, 1420, 575, 1980, 10), "holes[1]", "holes[1]"}};
  RegionOptions o;
  o.tolerance = 0.05;
  return build_region(outline, holes, o);
}

// A region sampled within 0.05 of `outline` and `holes`, and split options
// that carry its deviation (and, when `exact`, its outline).
struct Top {
  Region2 region;
  SplitOptions options;
};

Top top_of(const CompositeCurve& outline, const std::vector<RegionHole>& holes = {}, bool exact = false) {
  RegionOptions ro;
  ro.tolerance = 0.05;
  Top t{build_region(outline, holes, ro), {}};
  t.options.deviation = t.region.max_deviation;
  if (exact) t.options.outline = &outline;
  return t;
}

double pieces_area(const KitchenSplit& s) {
  double a = 0.0;
  for (const KitchenPiece& p : s.pieces) a += p.area;
  return a;
}

std::size_t count(const KitchenPiece& p, EdgeKind kind) {
  std::size_t n = 0;
  for (const EdgeKind k : p.edges) n += k == kind ? 1 : 0;
  return n;
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const GeometryError& e) {
    return std::string(e.where()) + " | " + e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("pieces: a seam at the L's inside corner makes a butt joint", "[kitchen][pieces]") {
  const Region2 top = l_top();
  SplitOptions o;
  o.deviation = top.max_deviation;
  const KitchenSplit s = split_top(top, {{{650, 650}, {0, -1}, "seams[0]"}}, o);
  REQUIRE(s.pieces.size() == 2);
  REQUIRE(s.seams.size() == 1);
  // The chord from the inside corner straight down to the front edge.
  CHECK(s.seams[0].from.isApprox(Vec2(650, 650)) != s.seams[0].to.isApprox(Vec2(650, 650)));
  CHECK(std::abs(std::abs(s.seams[0].to.y() - s.seams[0].from.y()) - 650.0) < 1e-9);
  // The pieces partition the top: same area, each simple, each one seam edge.
  CHECK(std::abs(pieces_area(s) - top.area) <= 1e-9 * top.area);
  for (const KitchenPiece& p : s.pieces) {
    INFO(p.name);
    CHECK(count(p, EdgeKind::Seam) == 1);
    CHECK(p.edges.size() == p.outer.size());
    CHECK(signed_area2(p.outer) > 0.0);
    CHECK(p.holes.size() == 1);
  }
  // Named by their lowest-leftmost point: the leg (with the cooktop) first.
  CHECK(s.pieces[0].name == "piece-1");
  CHECK(s.pieces[0].hole_index == std::vector<std::size_t>{1});
  CHECK(s.pieces[1].hole_index == std::vector<std::size_t>{0});
  CHECK(s.seams[0].clearance >= 100.0);
}

TEST_CASE("pieces: a seam through a cut-out, too near one, or off the top is refused", "[kitchen][pieces]") {
  const Region2 top = l_top();
  SplitOptions o;
  o.deviation = top.max_deviation;
  const std::string through = message_of([&] { split_top(top, {{{1900, 0}, {0, 1}, "seams[0]"}}, o); });
  CHECK(through.find("seams[0] |") == 0);
  CHECK(through.find("runs through holes[0]") != std::string::npos);
  // 1900 + 380 (the sink's edge) + 40: 40 from it, under the 100 kept.
  const std::string near = message_of([&] { split_top(top, {{{2320, 0}, {0, 1}, "seams[1]"}}, o); });
  INFO(near);
  CHECK(near.find("seams[1] |") == 0);
  CHECK(near.find("passes 39.98") != std::string::npos);  // 40, less the loops' deviation
  o.seam_clearance = 30.0;
  CHECK(split_top(top, {{{2320, 0}, {0, 1}, "seams[1]"}}, o).pieces.size() == 2);
  const std::string off = message_of([&] { split_top(top, {{{2000, 1000}, {0, 1}, "seams[2]"}}, o); });
  CHECK(off.find("seams[2].at |") == 0);
  // The same seam twice: the second runs along the first's edge.
  const std::string twice = message_of([&] {
    split_top(top, {{{650, 650}, {0, -1}, "seams[0]"}, {{650, 300}, {0, 1}, "seams[1]"}}, o);
  });
  CHECK(twice.find("seams[1]") == 0);
}

TEST_CASE("pieces: seams: auto takes the fewest seams, butt joints first", "[kitchen][pieces]") {
  const Region2 top = l_top();
  SplitOptions o;
  o.deviation = top.max_deviation;
  const SlabFit quartz{2980, 1380, true};
  const KitchenSplit s = auto_split(top, quartz, o);
  REQUIRE(s.seams.size() == 1);
  CHECK(std::abs(pieces_area(s) - top.area) <= 1e-9 * top.area);
  for (const KitchenPiece& p : s.pieces) CHECK(fits_slab(p.outer, quartz));
  // The seam leaves the inside corner at right angles to the front edge.
  CHECK(std::abs(s.seams[0].from.x() - 650.0) < 1e-9);
  CHECK(std::abs(s.seams[0].to.x() - 650.0) < 1e-9);
  // A slab of 2000: the leg needs a seam of its own, and the run two (a seam
  // 100 clear of its 760 mm sink cannot leave both ends under 1990).
  const KitchenSplit short_slab = auto_split(top, {1990, 1380, true}, o);
  CHECK(short_slab.seams.size() == 3);
  for (const KitchenPiece& p : short_slab.pieces) CHECK(fits_slab(p.outer, {1990, 1380, true}));
  for (const SeamCut& c : short_slab.seams) CHECK(c.clearance >= 100.0);
  CHECK(std::abs(pieces_area(short_slab) - top.area) <= 1e-9 * top.area);
}

TEST_CASE("pieces: a straight run longer than two slabs gets two seams clear of the cut-outs",
          "[kitchen][pieces]") {
  const CompositeCurve outline = test::polygon({{0, 0}, {7000, 0}, {7000, 620}, {0, 620}});
  // A sink right where a greedy cut at 2980 would fall.
  std::vector<RegionHole> holes{{test::rounded_rect(2700, 100, 3300, 500, 30), "holes[0]", "holes[0]"}};
  const Top t = top_of(outline, holes);
  const Region2& top = t.region;
  SplitOptions o = t.options;
  const KitchenSplit s = auto_split(top, {2980, 1380, true}, o);
  CHECK(s.pieces.size() == 3);
  for (const KitchenPiece& p : s.pieces) CHECK(fits_slab(p.outer, {2980, 1380, true}));
  for (const SeamCut& c : s.seams) {
    CHECK(c.clearance >= 100.0);
    CHECK(std::abs(c.from.x() - c.to.x()) < 1e-9);  // square across the run
  }
}

TEST_CASE("pieces: a cut-out no slab can hold is named with its size", "[kitchen][pieces]") {
  const CompositeCurve outline = test::polygon({{0, 0}, {5000, 0}, {5000, 900}, {0, 900}});
  std::vector<RegionHole> holes{{test::rounded_rect(500, 100, 3700, 800, 30), "holes[0]", "holes[0]"}};
  const Top t = top_of(outline, holes);
  const Region2& top = t.region;
  SplitOptions o = t.options;
  const std::string m = message_of([&] { auto_split(top, {2980, 1380, true}, o); });
  CHECK(m.find("holes[0] |") == 0);
  CHECK(m.find("3200 x 700") != std::string::npos);
}

TEST_CASE("pieces: each piece's exact outline cuts the outline's arcs exactly at its seams",
          "[kitchen][pieces]") {
  // A 4000 x 600 top with 250 mm corner arcs: a seam at x = 150 cuts the left
  // arcs, one at x = 2000 the straight edges.
  const CompositeCurve outline = test::rounded_rect(0, 0, 4000, 600, 250);
  const Top t = top_of(outline, {}, true);
  const Region2& top = t.region;
  SplitOptions o = t.options;
  const KitchenSplit s =
      split_top(top, {{{150, 300}, {0, 1}, "seams[0]"}, {{2000, 0}, {0, 1}, "seams[1]"}}, o);
  REQUIRE(s.pieces.size() == 3);
  double area = 0.0;
  for (const KitchenPiece& p : s.pieces) {
    INFO(p.name);
    const CompositeCurve exact = exact_piece_outline(p, outline, top.reversed[0]);
    const double a = std::abs(test::exact_area(exact));
    // The exact piece differs from its loops by at most the deviation along the boundary.
    CHECK(std::abs(a - p.area) <= top.max_deviation * test::exact_length(exact));
    area += a;
    for (const Segment& seg : exact.segments()) {
      if (seg.kind() != SegmentKind::Line) continue;
      // A seam's ends lie on the exact corner circles (or the straight edges).
      for (const Vec2& q : {seg.point(0.0), seg.point(1.0)}) {
        const double on_arc = std::min((q - Vec2(250, 250)).norm(), (q - Vec2(250, 350)).norm());
        const bool on_edge = std::abs(q.y()) < 1e-9 || std::abs(q.y() - 600) < 1e-9 ||
                             std::abs(q.x()) < 1e-9 || std::abs(q.x() - 4000) < 1e-9;
        CHECK((on_edge || std::abs(on_arc - 250.0) < 1e-9));
      }
    }
  }
  // Together the exact pieces are the exact top.
  CHECK(std::abs(area - std::abs(test::exact_area(outline))) <= 1e-9 * area);
}

TEST_CASE("pieces: a seam ending inside a free-form segment has no exact piece outline",
          "[kitchen][pieces]") {
  // A T-Bezier end: the seam at x = 3950 cuts it.
  const CompositeCurve outline(
      {Segment::line({0, 0}, {3900, 0}),
       Segment::tbezier({Vec2(3900, 0), Vec2(4000, 0), Vec2(4000, 600), Vec2(3900, 600)}, 0.5, 0.5),
       Segment::line({3900, 600}, {0, 600}), Segment::line({0, 600}, {0, 0})},
      true);
  const Top t = top_of(outline, {}, true);
  const Region2& top = t.region;
  SplitOptions o = t.options;
  const KitchenSplit s = split_top(top, {{{3950, 300}, {0, 1}, "seams[0]"}}, o);
  REQUIRE(s.pieces.size() == 2);
  const std::string m = message_of([&] {
    for (const KitchenPiece& p : s.pieces) exact_piece_outline(p, outline, top.reversed[0]);
  });
  CHECK(m.find("outline segment 1 (tbezier)") != std::string::npos);
}

TEST_CASE("pieces: a router without dog-bones gets no piece with a sharp inside corner",
          "[kitchen][pieces]") {
  // A small L that one slab holds whole.
  const CompositeCurve outline =
      test::polygon({{0, 0}, {2000, 0}, {2000, 650}, {650, 650}, {650, 1200}, {0, 1200}});
  const Top t = top_of(outline);
  const Region2& top = t.region;
  SplitOptions o = t.options;
  SlabFit slab{2980, 1380, true};
  CHECK(auto_split(top, slab, o).pieces.size() == 1);
  slab.no_inside_corners = true;
  const KitchenSplit s = auto_split(top, slab, o);
  REQUIRE(s.seams.size() == 1);  // a butt joint at the inside corner
  const bool from_corner = s.seams[0].from.isApprox(Vec2(650, 650)) || s.seams[0].to.isApprox(Vec2(650, 650));
  CHECK(from_corner);
  CHECK(std::abs(pieces_area(s) - top.area) <= 1e-9 * top.area);
}
