#include "geometry/kitchen/nest.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "geometry/core/errors.h"

using namespace fabmesh;

namespace {

// A w x h rectangle, counter-clockwise from the origin.
std::vector<Vec2> rectangle(double w, double h) { return {Vec2(0, 0), Vec2(w, 0), Vec2(w, h), Vec2(0, h)}; }

// A w x h rectangle whose corners are rounded with radius r, each corner
// sampled at `per_corner` points (its ends included), counter-clockwise.
std::vector<Vec2> rounded_rectangle(double w, double h, double r, int per_corner) {
  const Vec2 centers[4] = {Vec2(w - r, r), Vec2(w - r, h - r), Vec2(r, h - r), Vec2(r, r)};
  std::vector<Vec2> out;
  for (int c = 0; c < 4; ++c) {
    for (int k = 0; k < per_corner; ++k) {
      const double a = M_PI / 2 * (c - 1 + static_cast<double>(k) / (per_corner - 1));
      const Vec2 p = centers[c] + r * Vec2(std::cos(a), std::sin(a));
      out.emplace_back(std::clamp(p.x(), 0.0, w), std::clamp(p.y(), 0.0, h));
    }
  }
  return out;
}

// An L: a w x h rectangle with a leg of width `leg` going up h2 at its left end.
std::vector<Vec2> l_shape(double w, double h, double leg, double h2) {
  return {Vec2(0, 0), Vec2(w, 0), Vec2(w, h), Vec2(leg, h), Vec2(leg, h2), Vec2(0, h2)};
}

SlabStock quartz() {
  SlabStock s;
  s.length = 3000;
  s.width = 1400;
  s.margin = 10;
  s.spacing = 14;
  return s;
}

NestPiece piece(const std::string& name, std::vector<Vec2> outer) {
  return NestPiece{name, std::move(outer)};
}

double segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * d)).norm();
}

// Crossing-number test (the point is far from the boundary in these tests).
bool contains(const std::vector<Vec2>& loop, const Vec2& p) {
  bool in = false;
  for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++) {
    const Vec2& a = loop[i];
    const Vec2& b = loop[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      in = !in;
    }
  }
  return in;
}

// A placement of piece `i` as place_point writes it.
Placement placed(const std::vector<NestPiece>& pieces, std::size_t i, std::size_t slab, int rotation,
                 const Vec2& offset) {
  Placement p;
  p.piece = i;
  p.slab = slab;
  p.rotation_deg = rotation;
  p.offset = offset;
  for (const Vec2& q : pieces[i].outer) p.outer.push_back(place_point(q, rotation, offset));
  return p;
}

std::string verify_error(const std::vector<NestPiece>& pieces, const SlabStock& stock,
                         const std::vector<Placement>& placements) {
  try {
    verify_nesting(pieces, stock, placements);
  } catch (const GeometryError& e) {
    CHECK(e.where() == "slab");
    return e.what();
  }
  return "";
}

std::vector<NestPiece> kitchen() {
  return {piece("piece-1", rounded_rectangle(2400, 650, 10, 40)),
          piece("piece-2", rounded_rectangle(1650, 650, 10, 40)),
          piece("piece-3", rounded_rectangle(1200, 650, 10, 40))};
}

}  // namespace

TEST_CASE("nest: place_point turns by exact quarter turns, then moves", "[kitchen][nest]") {
  const Vec2 p(3, 2);
  const Vec2 o(100, 10);
  CHECK(place_point(p, 0, o) == Vec2(103, 12));
  CHECK(place_point(p, 90, o) == Vec2(98, 13));
  CHECK(place_point(p, 180, o) == Vec2(97, 8));
  CHECK(place_point(p, 270, o) == Vec2(102, 7));
  CHECK_THROWS_AS(place_point(p, 45, o), RangeError);
}

TEST_CASE("nest: two pieces that fit one slab end on one slab", "[kitchen][nest]") {
  const std::vector<NestPiece> pieces = {piece("piece-1", rectangle(800, 600)),
                                         piece("piece-2", rectangle(1000, 600))};
  const SlabNesting n = nest_pieces(pieces, quartz());
  REQUIRE(n.slabs == 1);
  REQUIRE(n.placements.size() == 2);
  CHECK(n.placements[0].piece == 0);
  CHECK(n.placements[1].piece == 1);
  CHECK(n.placements[0].slab == 0);
  CHECK(n.placements[1].slab == 0);
  // Largest first at the margin corner, the other next to it, `spacing` away.
  CHECK(n.placements[1].rotation_deg == 0);
  CHECK(n.placements[1].offset == Vec2(10, 10));
  CHECK(n.placements[0].rotation_deg == 0);
  CHECK(n.placements[0].offset == Vec2(1024, 10));
  CHECK(n.placements[0].outer[0] == Vec2(1024, 10));
  CHECK(n.proof.find("verified exactly: 2 pieces on 1 slab") == 0);
  CHECK(n.proof.find("at least 14 apart") != std::string::npos);
}

TEST_CASE("nest: lower bound and utilisation are the areas over the usable area", "[kitchen][nest]") {
  // Usable 2980 x 1380 = 4112400. No two 2000 x 1000 pieces share a slab
  // (2000 + 14 + 2000 > 2980, 1000 + 14 + 1000 > 1380), so three take three
  // slabs, while their area (6e6) alone would need only two.
  const std::vector<NestPiece> pieces = {piece("a", rectangle(2000, 1000)), piece("b", rectangle(2000, 1000)),
                                         piece("c", rectangle(2000, 1000))};
  const SlabNesting n = nest_pieces(pieces, quartz());
  CHECK(n.slabs == 3);
  CHECK(n.lower_bound == 2);  // ceil(6e6 / 4112400) = ceil(1.459)
  REQUIRE(n.utilisation.size() == 3);
  for (const double u : n.utilisation) CHECK(u == Approx(2e6 / 4112400.0).epsilon(1e-12));
  for (std::size_t i = 0; i < 3; ++i) CHECK(n.placements[i].slab == i);

  // A set that exactly fills the usable area: the bound is 1, not 2.
  const std::vector<NestPiece> exact = {piece("whole", rectangle(2980, 1380))};
  const SlabNesting one = nest_pieces(exact, quartz());
  CHECK(one.lower_bound == 1);
  CHECK(one.slabs == 1);
  CHECK(one.utilisation.at(0) == 1.0);

  // Mixed: 1000x600 (6e5) + 500x400 (2e5) on one slab: 8e5 / 4112400.
  const std::vector<NestPiece> mixed = {piece("m", rectangle(1000, 600)), piece("n", rectangle(500, 400))};
  const SlabNesting m = nest_pieces(mixed, quartz());
  CHECK(m.lower_bound == 1);
  CHECK(m.utilisation.at(0) == Approx(8e5 / 4112400.0).epsilon(1e-12));
}

TEST_CASE("nest: grain_along restricts the turns", "[kitchen][nest]") {
  const std::vector<NestPiece> tall = {piece("tall", rectangle(600, 1000))};
  SlabStock stock = quartz();
  SECTION("with the grain a tall piece is turned 90 or 270 degrees") {
    stock.grain_along = true;
    const SlabNesting n = nest_pieces(tall, stock);
    const int r = n.placements[0].rotation_deg;
    CHECK((r == 90 || r == 270));
    // Its long side now runs along x.
    double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
    for (const Vec2& p : n.placements[0].outer) {
      x0 = std::min(x0, p.x());
      x1 = std::max(x1, p.x());
      y0 = std::min(y0, p.y());
      y1 = std::max(y1, p.y());
    }
    CHECK(x1 - x0 == 1000);
    CHECK(y1 - y0 == 600);
    CHECK(x0 == 10);
    CHECK(y0 == 10);
  }
  SECTION("without it the first turn that fits, 0, is kept") {
    stock.grain_along = false;
    const SlabNesting n = nest_pieces(tall, stock);
    CHECK(n.placements[0].rotation_deg == 0);
  }
  SECTION("a wide piece keeps 0 or 180 with the grain") {
    const std::vector<NestPiece> wide = {piece("wide", rectangle(1000, 600)),
                                         piece("w2", rectangle(1000, 600))};
    const SlabNesting n = nest_pieces(wide, stock);
    for (const Placement& p : n.placements) CHECK((p.rotation_deg == 0 || p.rotation_deg == 180));
  }
  SECTION("a piece that fits only across the grain is refused with it, placed without it") {
    // A slab stood on end: usable 1380 along x, 2980 along y.
    SlabStock upright = quartz();
    upright.length = 1400;
    upright.width = 3000;
    const std::vector<NestPiece> wide = {piece("wide", rectangle(2000, 650))};
    upright.grain_along = true;
    CHECK_THROWS_AS(nest_pieces(wide, upright), GeometryError);
    upright.grain_along = false;
    const SlabNesting n = nest_pieces(wide, upright);
    CHECK(n.placements[0].rotation_deg == 90);
  }
}

TEST_CASE("nest: a piece too long for the slab is named with its size", "[kitchen][nest]") {
  const std::vector<NestPiece> pieces = {piece("piece-1", rectangle(1200, 650)),
                                         piece("piece-2", rectangle(3400, 650))};
  try {
    nest_pieces(pieces, quartz());
    FAIL("no error");
  } catch (const GeometryError& e) {
    CHECK(e.where() == "slab");
    const std::string m = e.what();
    CHECK(m.find("piece-2 is 3400 x 650 after turning for the grain") != std::string::npos);
    CHECK(m.find("2980 x 1380") != std::string::npos);
  }
  // A tall design piece is named in its turned size.
  const std::vector<NestPiece> tall = {piece("piece-7", rectangle(650, 3400))};
  try {
    nest_pieces(tall, quartz());
    FAIL("no error");
  } catch (const GeometryError& e) {
    CHECK(std::string(e.what()).find("piece-7 is 3400 x 650") != std::string::npos);
  }
}

TEST_CASE("nest: no pieces need no slab", "[kitchen][nest]") {
  const SlabNesting n = nest_pieces({}, quartz());
  CHECK(n.slabs == 0);
  CHECK(n.lower_bound == 0);
  CHECK(n.placements.empty());
  CHECK(n.utilisation.empty());
  CHECK(n.proof.find("verified exactly: 0 pieces on 0 slabs") == 0);
}

TEST_CASE("nest: a stock without usable area or with a negative spacing is a RangeError", "[kitchen][nest]") {
  const std::vector<NestPiece> pieces = {piece("piece-1", rectangle(100, 100))};
  SlabStock stock = quartz();
  stock.margin = 700;  // 1400 - 1400 = 0
  try {
    nest_pieces(pieces, stock);
    FAIL("no error");
  } catch (const RangeError& e) {
    CHECK(e.field() == "slab.margin");
    CHECK(e.key() == "slab.margin");
    CHECK(e.value() == 700);
  }
  stock = quartz();
  stock.spacing = -1;
  try {
    nest_pieces(pieces, stock);
    FAIL("no error");
  } catch (const RangeError& e) {
    CHECK(e.field() == "slab.spacing");
  }
  CHECK_THROWS_AS(verify_nesting(pieces, stock, {}), RangeError);
}

TEST_CASE("nest: pieces keep clear of the slabs' defects", "[kitchen][nest]") {
  SlabStock stock = quartz();
  SlabDefect flaw;
  flaw.center = Vec2(60, 60);
  flaw.radius = 30;
  stock.defects.push_back(flaw);
  SlabDefect vein;  // a polygon across the middle of the slab
  vein.polygon = {Vec2(1500, 300), Vec2(1600, 300), Vec2(1600, 900), Vec2(1500, 900)};
  stock.defects.push_back(vein);
  const std::vector<NestPiece> pieces = {
      piece("piece-1", rectangle(1200, 650)), piece("piece-2", rectangle(1100, 650)),
      piece("piece-3", rectangle(400, 300)), piece("piece-4", l_shape(900, 200, 200, 600))};
  const SlabNesting n = nest_pieces(pieces, stock);
  CHECK(n.proof.find("clear of 2 defects") != std::string::npos);
  for (const Placement& p : n.placements) {
    const auto& loop = p.outer;
    CHECK_FALSE(contains(loop, flaw.center));
    for (std::size_t i = 0; i < loop.size(); ++i) {
      CHECK(segment_distance(flaw.center, loop[i], loop[(i + 1) % loop.size()]) >= 44.0 - 1e-9);
      for (const Vec2& v : vein.polygon) {
        CHECK(segment_distance(v, loop[i], loop[(i + 1) % loop.size()]) >= 14.0 - 1e-9);
      }
    }
    for (const Vec2& v : loop) CHECK_FALSE(contains(vein.polygon, v));
  }
  // The largest piece would have gone to the corner (10, 10) without the flaw.
  CHECK(n.placements[0].offset != Vec2(10, 10));

  // A defect that leaves no room for a piece on any slab.
  SlabStock blocked = quartz();
  SlabDefect middle;
  middle.center = Vec2(1500, 700);
  middle.radius = 200;
  blocked.defects.push_back(middle);
  try {
    nest_pieces({piece("piece-9", rectangle(2900, 1300))}, blocked);
    FAIL("no error");
  } catch (const GeometryError& e) {
    CHECK(std::string(e.what()).find("piece-9") != std::string::npos);
  }
}

TEST_CASE("nest: verify_nesting rejects hand-made layouts that break a rule", "[kitchen][nest]") {
  const std::vector<NestPiece> pieces = {piece("piece-1", rectangle(100, 100)),
                                         piece("piece-2", rectangle(100, 100))};
  const SlabStock stock = quartz();

  SECTION("exactly the spacing apart passes") {
    const std::string proof = verify_nesting(
        pieces, stock, {placed(pieces, 0, 0, 0, Vec2(10, 10)), placed(pieces, 1, 0, 0, Vec2(124, 10))});
    CHECK(proof.find("verified exactly") == 0);
  }
  SECTION("overlapping") {
    const std::string m = verify_error(
        pieces, stock, {placed(pieces, 0, 0, 0, Vec2(10, 10)), placed(pieces, 1, 0, 0, Vec2(60, 10))});
    CHECK(m.find("slab 1: piece-1 and piece-2 overlap") == 0);
  }
  SECTION("on different slabs they may overlap") {
    CHECK_NOTHROW(verify_nesting(
        pieces, stock, {placed(pieces, 0, 0, 0, Vec2(10, 10)), placed(pieces, 1, 1, 0, Vec2(10, 10))}));
  }
  SECTION("1e-9 nearer than the spacing") {
    const std::string m =
        verify_error(pieces, stock,
                     {placed(pieces, 0, 0, 0, Vec2(10, 10)), placed(pieces, 1, 0, 0, Vec2(124 - 1e-9, 10))});
    CHECK(m.find("less than the spacing 14") != std::string::npos);
    CHECK(m.find("piece-1 and piece-2") != std::string::npos);
  }
  SECTION("a gap that double arithmetic calls the spacing but is not") {
    // 10 + 0.1 rounds to the double 10.1, which is 3.6e-16 short of it.
    CHECK(10.0 + 0.1 <= 10.1);
    SlabStock fine = stock;
    fine.margin = 0;
    fine.spacing = 0.1;
    const std::vector<NestPiece> small = {piece("piece-1", rectangle(10, 10)),
                                          piece("piece-2", rectangle(10, 10))};
    const std::string m = verify_error(
        small, fine, {placed(small, 0, 0, 0, Vec2(0, 0)), placed(small, 1, 0, 0, Vec2(10.1, 0))});
    CHECK(m.find("less than the spacing 0.1") != std::string::npos);
    // nest_pieces finds the exact position (it verifies its own layout).
    const SlabNesting n = nest_pieces(small, fine);
    REQUIRE(n.slabs == 1);
    CHECK(n.placements[1].offset.x() > 10.1);
    CHECK(n.placements[1].offset.x() == std::nextafter(10.1, 11.0));
  }
  SECTION("outside the margin") {
    const std::string m = verify_error(
        pieces, stock, {placed(pieces, 0, 0, 0, Vec2(9, 10)), placed(pieces, 1, 0, 0, Vec2(200, 10))});
    CHECK(m.find("slab 1: piece-1 reaches outside the usable area") == 0);
    const std::string far = verify_error(
        pieces, stock, {placed(pieces, 0, 0, 0, Vec2(10, 10)), placed(pieces, 1, 1, 0, Vec2(2890.5, 10))});
    CHECK(far.find("slab 2: piece-2 reaches outside") == 0);
    CHECK_NOTHROW(verify_nesting(
        pieces, stock, {placed(pieces, 0, 0, 0, Vec2(10, 10)), placed(pieces, 1, 1, 0, Vec2(2890, 1290))}));
  }
  SECTION("an outer loop that is not place_point's result") {
    std::vector<Placement> layout = {placed(pieces, 0, 0, 0, Vec2(10, 10)),
                                     placed(pieces, 1, 0, 0, Vec2(200, 10))};
    layout[1].outer[2].x() = std::nextafter(layout[1].outer[2].x(), 0.0);
    CHECK(verify_error(pieces, stock, layout).find("piece-2's placed point 2") != std::string::npos);
    layout = {placed(pieces, 0, 0, 0, Vec2(10, 10)), placed(pieces, 1, 0, 90, Vec2(300, 10))};
    layout[1].rotation_deg = 270;
    CHECK(verify_error(pieces, stock, layout).find("not its design point") != std::string::npos);
  }
  SECTION("a piece placed twice or left out") {
    CHECK(verify_error(pieces, stock,
                       {placed(pieces, 0, 0, 0, Vec2(10, 10)), placed(pieces, 0, 1, 0, Vec2(10, 10))})
              .find("piece-1 is placed twice") != std::string::npos);
    CHECK(verify_error(pieces, stock, {placed(pieces, 0, 0, 0, Vec2(10, 10))})
              .find("1 placement for 2 pieces") != std::string::npos);
  }
  SECTION("one piece inside another") {
    const std::vector<NestPiece> nested = {piece("big", rectangle(1000, 1000)),
                                           piece("small", rectangle(100, 100))};
    const std::string m = verify_error(
        nested, stock, {placed(nested, 0, 0, 0, Vec2(10, 10)), placed(nested, 1, 0, 0, Vec2(400, 400))});
    CHECK(m.find("slab 1: small lies inside big") == 0);
  }
  SECTION("too near a defect") {
    SlabStock flawed = stock;
    SlabDefect flaw;
    flaw.center = Vec2(500, 60);
    flaw.radius = 30;
    flawed.defects.push_back(flaw);
    // Its right side at x = 456: 44 from the centre, exactly radius + spacing.
    CHECK_NOTHROW(verify_nesting(
        pieces, flawed, {placed(pieces, 0, 0, 0, Vec2(356, 10)), placed(pieces, 1, 0, 0, Vec2(10, 10))}));
    const std::string m =
        verify_error(pieces, flawed,
                     {placed(pieces, 0, 0, 0, Vec2(356 + 1e-9, 10)), placed(pieces, 1, 0, 0, Vec2(10, 10))});
    CHECK(m.find("slab 1: piece-1 comes within") == 0);
    CHECK(m.find("defect 1") != std::string::npos);
    // A flaw wholly inside a piece.
    const std::string inside = verify_error(
        pieces, flawed, {placed(pieces, 0, 0, 0, Vec2(10, 10)), placed(pieces, 1, 0, 0, Vec2(1000, 1000))});
    CHECK(inside.empty());
    flawed.defects[0].center = Vec2(1050, 1050);
    flawed.defects[0].radius = 5;
    CHECK(verify_error(pieces, flawed,
                       {placed(pieces, 0, 0, 0, Vec2(10, 10)), placed(pieces, 1, 0, 0, Vec2(1000, 1000))})
              .find("defect 1 (a circle of radius 5 at (1050, 1050)) lies inside piece-2") !=
          std::string::npos);
  }
}

TEST_CASE("nest: the same input gives the same layout", "[kitchen][nest]") {
  SlabStock stock = quartz();
  stock.grain_along = false;
  SlabDefect flaw;
  flaw.center = Vec2(2900, 1300);
  flaw.radius = 40;
  stock.defects.push_back(flaw);
  std::vector<NestPiece> pieces = kitchen();
  pieces.push_back(piece("piece-4", l_shape(1300, 650, 650, 1200)));
  pieces.push_back(piece("piece-5", rectangle(650, 650)));
  pieces.push_back(piece("piece-6", rectangle(650, 650)));  // the same area: index order breaks the tie
  const SlabNesting a = nest_pieces(pieces, stock);
  const SlabNesting b = nest_pieces(pieces, stock);
  REQUIRE(a.placements.size() == b.placements.size());
  CHECK(a.slabs == b.slabs);
  for (std::size_t i = 0; i < a.placements.size(); ++i) {
    CHECK(a.placements[i].piece == b.placements[i].piece);
    CHECK(a.placements[i].slab == b.placements[i].slab);
    CHECK(a.placements[i].rotation_deg == b.placements[i].rotation_deg);
    CHECK(a.placements[i].offset == b.placements[i].offset);
    CHECK(a.placements[i].outer == b.placements[i].outer);
  }
  CHECK(a.proof == b.proof);
  // Ties by index: piece-5 is placed before piece-6, so no later than it.
  const Placement& p5 = a.placements[4];
  const Placement& p6 = a.placements[5];
  CHECK((p5.slab < p6.slab ||
         (p5.slab == p6.slab && (p5.offset.y() < p6.offset.y() ||
                                 (p5.offset.y() == p6.offset.y() && p5.offset.x() < p6.offset.x())))));
}

TEST_CASE("nest: a kitchen's pieces use the lower bound of slabs", "[kitchen][nest]") {
  const std::vector<NestPiece> pieces = kitchen();
  REQUIRE(pieces[0].outer.size() == 160);
  const SlabNesting n = nest_pieces(pieces, quartz());
  CHECK(n.lower_bound == 1);
  CHECK(n.slabs == 1);
  CHECK(n.proof.find(
            "verified exactly: 3 pieces on 1 slab inside margins of 10, at least 14 apart and clear of 0 "
            "defects") == 0);
  // The 2400 at the corner; the 1650 and 1200 side by side above it,
  // their straight sides exactly 14 apart.
  CHECK(n.placements[0].offset == Vec2(10, 10));
  CHECK(n.placements[1].offset == Vec2(10, 674));
  CHECK(n.placements[2].offset == Vec2(1674, 674));
  CHECK(n.utilisation.at(0) > 0.8);

  // A larger kitchen: two runs, an island, upstands; the count is reported.
  std::vector<NestPiece> big = kitchen();
  big.push_back(piece("piece-4", rounded_rectangle(2400, 650, 10, 40)));
  big.push_back(piece("piece-5", rounded_rectangle(2200, 900, 30, 60)));
  big.push_back(piece("piece-6", l_shape(1800, 650, 650, 1300)));
  for (int i = 0; i < 4; ++i) big.push_back(piece("upstand-" + std::to_string(i + 1), rectangle(1400, 100)));
  const SlabNesting m = nest_pieces(big, quartz());
  INFO("slabs " << m.slabs << ", lower bound " << m.lower_bound);
  CHECK(m.slabs >= m.lower_bound);
  CHECK(m.slabs <= m.lower_bound + 1);
  CHECK(m.utilisation.size() == m.slabs);
}

TEST_CASE("nest: verify_nesting handles two 500-point loops at exactly the spacing", "[kitchen][nest]") {
  const std::vector<NestPiece> pieces = {piece("piece-1", rounded_rectangle(1000, 650, 40, 125)),
                                         piece("piece-2", rounded_rectangle(1000, 650, 40, 125))};
  REQUIRE(pieces[0].outer.size() == 500);
  const SlabStock stock = quartz();
  CHECK_NOTHROW(verify_nesting(
      pieces, stock, {placed(pieces, 0, 0, 0, Vec2(10, 10)), placed(pieces, 1, 0, 180, Vec2(2024, 660))}));
  const SlabNesting n = nest_pieces(pieces, stock);
  CHECK(n.slabs == 1);
  CHECK(n.placements[1].offset == Vec2(1024, 10));
}
