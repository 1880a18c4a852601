#include "io/design/dxf_loops.h"

#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "geometry/core/errors.h"
#include "geometry/curves/composite.h"
#include "io/design/design_source.h"
#include "io/file.h"

using namespace fabmesh;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A DXF text: a header with $INSUNITS (none when < 0) and the given entities.
std::string drawing(const std::string& entities, int insunits = 4) {
  std::string text = "0\nSECTION\n2\nHEADER\n";
  if (insunits >= 0) text += "9\n$INSUNITS\n70\n" + std::to_string(insunits) + "\n";
  text += "0\nENDSEC\n0\nSECTION\n2\nENTITIES\n" + entities + "0\nENDSEC\n0\nEOF\n";
  return text;
}

std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string line(const char* handle, const char* layer, double x1, double y1, double x2, double y2) {
  return std::string("0\nLINE\n5\n") + handle + "\n8\n" + layer + "\n10\n" + num(x1) + "\n20\n" + num(y1) +
         "\n30\n0\n11\n" + num(x2) + "\n21\n" + num(y2) + "\n31\n0\n";
}

std::string arc(const char* handle, const char* layer, double cx, double cy, double r, double a1, double a2,
                bool mirrored = false) {
  return std::string("0\nARC\n5\n") + handle + "\n8\n" + layer + "\n10\n" + num(cx) + "\n20\n" + num(cy) +
         "\n30\n0\n40\n" + num(r) + "\n" + (mirrored ? "210\n0\n220\n0\n230\n-1\n" : "") + "50\n" + num(a1) +
         "\n51\n" + num(a2) + "\n";
}

// An LWPOLYLINE through (x, y, bulge) vertices.
std::string lwpolyline(const char* handle, const char* layer, const std::vector<std::array<double, 3>>& v,
                       bool closed) {
  std::string text = std::string("0\nLWPOLYLINE\n5\n") + handle + "\n8\n" + layer + "\n90\n" +
                     std::to_string(v.size()) + "\n70\n" + (closed ? "1" : "0") + "\n";
  for (const auto& p : v) {
    text += "10\n" + num(p[0]) + "\n20\n" + num(p[1]) + "\n";
    if (p[2] != 0.0) text += "42\n" + num(p[2]) + "\n";
  }
  return text;
}

// A SPLINE of the given degree, knots and control points (x, y), with weights when given (41).
std::string spline(const char* handle, const char* layer, int degree, const std::vector<double>& knots,
                   const std::vector<Vec2>& points, const std::vector<double>& weights = {}) {
  std::string text = std::string("0\nSPLINE\n5\n") + handle + "\n8\n" + layer + "\n70\n8\n71\n" +
                     std::to_string(degree) + "\n72\n" + std::to_string(knots.size()) + "\n73\n" +
                     std::to_string(points.size()) + "\n74\n0\n";
  for (const double k : knots) text += "40\n" + num(k) + "\n";
  for (std::size_t i = 0; i < points.size(); ++i) {
    text += "10\n" + num(points[i].x()) + "\n20\n" + num(points[i].y()) + "\n30\n0\n";
    if (!weights.empty()) text += "41\n" + num(weights[i]) + "\n";
  }
  return text;
}

// A B-spline's point at u by de Boor's algorithm (the reference the reader must match).
Vec2 de_boor(const std::vector<double>& knots, const std::vector<Vec2>& points, int p, double u) {
  std::size_t k = static_cast<std::size_t>(p);
  while (k + 1 < points.size() && u >= knots[k + 1]) ++k;
  std::vector<Vec2> d(points.begin() + static_cast<std::ptrdiff_t>(k) - p,
                      points.begin() + static_cast<std::ptrdiff_t>(k) + 1);
  for (int r = 1; r <= p; ++r) {
    for (int j = p; j >= r; --j) {
      const std::size_t i = k - static_cast<std::size_t>(p) + static_cast<std::size_t>(j);
      const double a = (u - knots[i]) /
                       (knots[i + static_cast<std::size_t>(p) + 1 - static_cast<std::size_t>(r)] - knots[i]);
      d[static_cast<std::size_t>(j)] =
          (1.0 - a) * d[static_cast<std::size_t>(j) - 1] + a * d[static_cast<std::size_t>(j)];
    }
  }
  return d[static_cast<std::size_t>(p)];
}

// A NURBS curve's point at u: de Boor on the homogeneous points (w x, w y)
// and on the weights (w, 0), divided.
Vec2 rational_de_boor(const std::vector<double>& knots, const std::vector<Vec2>& points,
                      const std::vector<double>& weights, int p, double u) {
  std::vector<Vec2> numerator, denominator;
  for (std::size_t i = 0; i < points.size(); ++i) {
    numerator.push_back(weights[i] * points[i]);
    denominator.emplace_back(weights[i], 0.0);
  }
  return de_boor(knots, numerator, p, u) / de_boor(knots, denominator, p, u).x();
}

// A circle of radius r about c as the rational quadratic NURBS CAD programs
// save: 9 control points on the square round it, corner weights sqrt(2)/2.
std::vector<Vec2> circle_points(const Vec2& c, double r) {
  std::vector<Vec2> out;
  for (int i = 0; i <= 8; ++i) {
    const double a = i * kPi / 4;
    const double reach = i % 2 == 0 ? r : r * std::sqrt(2.0);
    out.push_back(c + reach * Vec2(std::cos(a), std::sin(a)));
  }
  out.back() = out.front();
  return out;
}
const std::vector<double> kCircleWeights{1, std::sqrt(0.5), 1, std::sqrt(0.5), 1, std::sqrt(0.5),
                                         1, std::sqrt(0.5), 1};
const std::vector<double> kCircleKnots{0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1};

DxfLoopQuery on_layer(const std::string& layer, double max_gap = 1e-6, const std::string& units = "mm") {
  DxfLoopQuery q;
  q.layer = layer;
  q.max_gap = max_gap;
  q.units = units;
  return q;
}

// The area a closed loop encloses (signed: counter-clockwise positive), from
// Green's theorem with Gauss-Legendre quadrature on the exact segments; the
// loop's declared joints are verified first.
double loop_area(const CurveSpec& spec) {
  const CompositeCurve curve = construct_curve(spec);
  verify_declared_continuity(spec, curve);
  static const double x[5] = {0.0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640,
                              0.9061798459386640};
  static const double w[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665, 0.2369268850561891,
                              0.2369268850561891};
  double twice = 0.0;
  constexpr int kPieces = 64;
  for (const Segment& s : curve.segments()) {
    for (int k = 0; k < kPieces; ++k) {
      for (int i = 0; i < 5; ++i) {
        const double t = (k + 0.5 + 0.5 * x[i]) / kPieces;
        const CurveJet j = s.jet(t);
        twice += w[i] * 0.5 / kPieces * (j[0].x() * j[1].y() - j[0].y() * j[1].x());
      }
    }
  }
  return 0.5 * twice;
}

std::string error_of(const std::string& text, const DxfLoopQuery& q) {
  try {
    parse_dxf_loops(text, "t.dxf", q);
  } catch (const FileError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("dxf loops: lines drawn in mixed directions and a corner arc chain into one exact loop",
          "[io][design][dxf]") {
  // A 100 x 50 rectangle whose lower-left corner is a quarter circle of radius 10.
  const std::string text = drawing(line("1A", "OUT", 10, 0, 100, 0) + line("1B", "OUT", 100, 50, 100, 0) +
                                   line("1C", "OUT", 100, 50, 0, 50) + line("1D", "OUT", 0, 10, 0, 50) +
                                   arc("1E", "OUT", 10, 10, 10, 180, 270) + line("1F", "OTHER", 0, 0, 5, 5));
  const DxfLoops got = parse_dxf_loops(text, "t.dxf", on_layer("OUT"));
  REQUIRE(got.loops.size() == 1);
  const CurveSpec& loop = got.loops[0].curve;
  CHECK(loop.closed);
  REQUIRE(loop.segments.size() == 5);
  CHECK(std::abs(loop_area(loop)) == Approx(100.0 * 50.0 - (100.0 - 25.0 * kPi)).epsilon(1e-13));
  CHECK(got.loops[0].first_entity == "LINE #1A");
  bool arc_named = false;
  for (const SegmentSpec& s : loop.segments) arc_named = arc_named || s.name == "ARC #1E";
  CHECK(arc_named);
  REQUIRE_FALSE(got.notes.empty());
  CHECK(got.notes[0] == "t.dxf: $INSUNITS 4 (mm)");
}

TEST_CASE("dxf loops: polyline bulges are exact arcs, either way round", "[io][design][dxf]") {
  // A 20 x 10 stadium: bulge 1 is a half circle; the second polyline runs clockwise.
  const double stadium = 20.0 * 10.0 + kPi * 25.0;
  for (const double sign : {1.0, -1.0}) {
    const std::vector<std::array<double, 3>> ccw{{0, 0, 0}, {20, 0, 1}, {20, 10, 0}, {0, 10, 1}};
    std::vector<std::array<double, 3>> v = ccw;
    if (sign < 0) v = {{0, 10, 0}, {20, 10, -1}, {20, 0, 0}, {0, 0, -1}};
    const DxfLoops got = parse_dxf_loops(drawing(lwpolyline("2A", "H", v, true)), "t.dxf", on_layer("H"));
    REQUIRE(got.loops.size() == 1);
    CHECK(loop_area(got.loops[0].curve) == Approx(sign * stadium).epsilon(1e-13));
  }
}

TEST_CASE("dxf loops: circles, ellipses and mirrored arcs", "[io][design][dxf]") {
  const std::string circle = "0\nCIRCLE\n5\n3A\n8\nH\n10\n5\n20\n5\n30\n0\n40\n2\n";
  const std::string ellipse =
      "0\nELLIPSE\n5\n3B\n8\nH\n10\n50\n20\n5\n30\n0\n11\n0\n21\n4\n31\n0\n40\n0.5\n41\n0\n42\n" +
      num(2 * kPi) + "\n";
  const DxfLoops got = parse_dxf_loops(drawing(circle + ellipse), "t.dxf", on_layer("H"));
  REQUIRE(got.loops.size() == 2);
  CHECK(std::abs(loop_area(got.loops[0].curve)) == Approx(kPi * 4.0).epsilon(1e-13));
  CHECK(std::abs(loop_area(got.loops[1].curve)) == Approx(kPi * 4.0 * 2.0).epsilon(1e-13));

  // A half disc whose arc has the extrusion (0, 0, -1): in world coordinates
  // its centre is at x = -10 and it runs clockwise from (0, 0) over the top to (-20, 0).
  const std::string half = arc("4A", "M", 10, 0, 10, 0, 180, true) + line("4B", "M", -20, 0, 0, 0);
  const DxfLoops mirrored = parse_dxf_loops(drawing(half), "t.dxf", on_layer("M"));
  REQUIRE(mirrored.loops.size() == 1);
  CHECK(std::abs(loop_area(mirrored.loops[0].curve)) == Approx(kPi * 50.0).epsilon(1e-13));
}

TEST_CASE("dxf loops: units are scaled into the design's, or assumed and said", "[io][design][dxf]") {
  const std::string square = line("5A", "S", 0, 0, 1, 0) + line("5B", "S", 1, 0, 1, 1) +
                             line("5C", "S", 1, 1, 0, 1) + line("5D", "S", 0, 1, 0, 0);
  const DxfLoops inches = parse_dxf_loops(drawing(square, 1), "t.dxf", on_layer("S", 1e-6, "mm"));
  CHECK(loop_area(inches.loops[0].curve) == Approx(25.4 * 25.4).epsilon(1e-14));
  CHECK(inches.notes[0] == "t.dxf: $INSUNITS 1 (in), scaled by 25.4 into mm");
  const DxfLoops none = parse_dxf_loops(drawing(square, -1), "t.dxf", on_layer("S", 1e-6, "cm"));
  CHECK(loop_area(none.loops[0].curve) == Approx(1.0));
  CHECK(none.notes[0] == "t.dxf gives no units ($INSUNITS missing): read in the design's units (cm)");
  CHECK(error_of(drawing(square, 3), on_layer("S")) ==
        "t.dxf: $INSUNITS 3 is not a unit fabmesh reads (1 in, 2 ft, 4 mm, 5 cm, 6 m)");
}

TEST_CASE("dxf loops: gaps within max_gap are closed, exactly", "[io][design][dxf]") {
  // Two half circles whose ends miss by 1e-4, and a line ending 1e-4 short of an arc.
  const std::string two_arcs = arc("6A", "G", 0, 0, 10, 0, 180) + arc("6B", "G", 0, 1e-4, 10, 180, 360);
  const DxfLoops got = parse_dxf_loops(drawing(two_arcs), "t.dxf", on_layer("G", 1e-3));
  REQUIRE(got.loops.size() == 1);
  CHECK(got.loops[0].curve.segments.size() == 4);  // two arcs, two short lines between them
  CHECK(loop_area(got.loops[0].curve) == Approx(kPi * 100.0).epsilon(1e-4));
  CHECK(got.notes.back() == "t.dxf layer G: 2 gap(s) between arcs, up to max_gap, joined by short lines");

  const std::string d = arc("7A", "D", 0, 0, 10, 0, 180) + line("7B", "D", -10, 0, 10.0001, 0);
  const DxfLoops snapped = parse_dxf_loops(drawing(d), "t.dxf", on_layer("D", 1e-3));
  REQUIRE(snapped.loops.size() == 1);
  CHECK(loop_area(snapped.loops[0].curve) ==
        Approx(kPi * 50.0).epsilon(1e-14));  // the line moved onto the arc

  // Beyond max_gap: an open chain, named by entity, place and the nearest end.
  CHECK(error_of(drawing(d), on_layer("D", 1e-5)) ==
        "t.dxf layer D: open chain: ARC #7A's start at (10, 0) meets no other end within max_gap 1e-05 "
        "(the nearest, LINE #7B's end, is 0.0001 away)");
}

TEST_CASE("dxf loops: bad drawings are refused naming the file, layer, entity and place",
          "[io][design][dxf]") {
  const std::string tri =
      line("8A", "T", 0, 0, 10, 0) + line("8B", "T", 10, 0, 0, 10) + line("8C", "T", 0, 10, 0, 0);
  // Overlap: the same edge twice makes three ends meet.
  CHECK(error_of(drawing(tri + line("8D", "T", 0, 0, 10, 0)), on_layer("T")) ==
        "t.dxf layer T: 3 ends meet at (0, 0): LINE #8A's start, LINE #8C's end, LINE #8D's start; entities "
        "overlap or branch there (a loop passes a point once)");
  CHECK(error_of(drawing(tri), on_layer("NOPE")) ==
        "t.dxf layer NOPE: no LINE, ARC, CIRCLE, ELLIPSE, polyline or SPLINE in model space (layers that "
        "have them: "
        "T)");
  const std::string paper = "0\nLINE\n5\n9A\n67\n1\n8\nP\n10\n0\n20\n0\n30\n0\n11\n1\n21\n0\n31\n0\n";
  CHECK(error_of(drawing(paper), on_layer("P")) ==
        "t.dxf layer P: the layer's 1 entities are all in paper space; the outline must be in model space");
  const std::string fit_only = "0\nSPLINE\n5\n9B\n8\nT\n70\n8\n71\n3\n72\n0\n73\n0\n74\n0\n";
  CHECK_THAT(error_of(drawing(tri + fit_only), on_layer("T")),
             Catch::StartsWith("t.dxf layer T: SPLINE #9B: a SPLINE without control points"));
  const std::string insert = "0\nINSERT\n5\n9C\n8\nT\n2\nSINK\n10\n0\n20\n0\n30\n0\n";
  CHECK_THAT(error_of(drawing(tri + insert), on_layer("T")),
             Catch::StartsWith("t.dxf layer T: INSERT #9C: a block reference on the layer"));
  const std::string tilted = "0\nCIRCLE\n5\n9D\n8\nT\n10\n0\n20\n0\n30\n0\n40\n1\n210\n1\n220\n0\n230\n0\n";
  CHECK_THAT(error_of(drawing(tilted), on_layer("T")),
             Catch::StartsWith("t.dxf layer T: CIRCLE #9D: its plane (extrusion (1, 0, 0))"));
  CHECK(error_of("", on_layer("T")) == "t.dxf: the file is empty, not a DXF drawing");
  CHECK(error_of(std::string("AutoCAD Binary DXF\r\n\x1a", 21) + std::string(40, '\0'), on_layer("T")) ==
        "t.dxf: a binary DXF; fabmesh reads ASCII DXF (save the drawing as ASCII DXF)");
  CHECK(error_of("solid cube\nfacet normal 0 0 1\n", on_layer("T")) ==
        "t.dxf:1: 'solid cube' is not a DXF group code: the file is not a DXF drawing");
  CHECK(error_of("0\nLINE\n", on_layer("T")) ==
        "t.dxf: the file does not start with a DXF SECTION: not a DXF drawing");
  // A count larger than the file could hold is refused before dxflib allocates for it.
  const std::string greedy = "0\nLWPOLYLINE\n5\n9E\n8\nT\n90\n2000000000\n70\n1\n10\n0\n20\n0\n";
  CHECK_THAT(error_of(drawing(greedy), on_layer("T")),
             Catch::Contains("LWPOLYLINE group 90 announces 2000000000 entries; the file has"));
}

TEST_CASE("dxf loops: a SPLINE is read as the exact spline it is, in cubic spans", "[io][design][dxf]") {
  // A cubic spline of two spans (an interior knot at 0.4) from (100, 0) over to (0, 0), closed by a line.
  const std::vector<double> knots{0, 0, 0, 0, 0.4, 1, 1, 1, 1};
  const std::vector<Vec2> points{{100, 0}, {110, 60}, {50, 90}, {-10, 60}, {0, 0}};
  const DxfLoops got = parse_dxf_loops(
      drawing(line("A0", "S", 0, 0, 100, 0) + spline("A1", "S", 3, knots, points)), "t.dxf", on_layer("S"));
  REQUIRE(got.loops.size() == 1);
  const CurveSpec& loop = got.loops[0].curve;
  const CompositeCurve curve = construct_curve(loop);
  verify_declared_continuity(loop, curve);
  int spans = 0;
  for (std::size_t i = 0; i < loop.segments.size(); ++i) {
    if (loop.segments[i].name.rfind("SPLINE #A1", 0) != 0) continue;
    const double u0 = spans == 0 ? 0.0 : 0.4, u1 = spans == 0 ? 0.4 : 1.0;
    ++spans;
    CHECK(loop.segments[i].kind == SegmentKind::QuasiBSpline);
    for (int j = 0; j <= 50; ++j) {
      const double t = j / 50.0;
      const Vec2 want = de_boor(knots, points, 3, u0 + t * (u1 - u0));
      CHECK((curve.segments()[i].point(t) - want).norm() <= 1e-12 * 100);
    }
  }
  CHECK(spans == 2);
  // The spans meet C2: every joint inside the spline measures G2.
  for (const JointReport& j : curve.joints()) {
    if (loop.segments[j.before].name.rfind("SPLINE", 0) == 0 &&
        loop.segments[j.after].name.rfind("SPLINE", 0) == 0)
      CHECK(j.achieved == Continuity::G2);
  }
  // A quadratic spline is a parabola: the area it cuts off its chord is 2/3 of the control triangle's.
  const DxfLoops parabola =
      parse_dxf_loops(drawing(line("B0", "Q", 100, 0, 0, 0) +
                              spline("B1", "Q", 2, {0, 0, 0, 1, 1, 1}, {{0, 0}, {50, 80}, {100, 0}})),
                      "t.dxf", on_layer("Q"));
  REQUIRE(parabola.loops.size() == 1);
  CHECK(std::abs(loop_area(parabola.loops[0].curve)) == Approx(2.0 / 3.0 * 4000.0).epsilon(1e-13));
  // A closed spline is a loop by itself: a periodic cubic of 8 points round a circle.
  std::vector<Vec2> ring;
  for (int i = 0; i < 8; ++i) ring.emplace_back(50 * std::cos(i * kPi / 4), 50 * std::sin(i * kPi / 4));
  for (int i = 0; i < 3; ++i) ring.push_back(ring[static_cast<std::size_t>(i)]);
  std::vector<double> uniform;
  for (int i = 0; i < 15; ++i) uniform.push_back(i);
  const DxfLoops closed =
      parse_dxf_loops(drawing(spline("C1", "R", 3, uniform, ring)), "t.dxf", on_layer("R"));
  REQUIRE(closed.loops.size() == 1);
  CHECK(closed.loops[0].curve.segments.size() == 8);
  CHECK(std::abs(loop_area(closed.loops[0].curve)) > 0.9 * kPi * 45 * 45);
  // A long digitised spline (100000 control points) is read span by span, in linear time.
  std::vector<Vec2> wave;
  std::vector<double> wave_knots{0, 0, 0, 0};  // clamped: 4 + 99996 interior + 4 knots
  for (int i = 0; i < 100000; ++i) wave.emplace_back(i, std::sin(i * 1e-3));
  for (int i = 1; i <= 99996; ++i) wave_knots.push_back(i);
  for (int i = 0; i < 4; ++i) wave_knots.push_back(99997);
  const DxfLoops long_spline = parse_dxf_loops(
      drawing(spline("E1", "L", 3, wave_knots, wave) + line("E2", "L", 99999, std::sin(99.999), 0, 0)),
      "t.dxf", on_layer("L"));
  REQUIRE(long_spline.loops.size() == 1);
  CHECK(long_spline.loops[0].curve.segments.size() == 99997 + 1);
  // What is not read, named.
  CHECK_THAT(error_of(drawing(spline("D1", "W", 3, knots, points, {1, 0, 1, 1, 1})), on_layer("W")),
             Catch::StartsWith("t.dxf layer W: SPLINE #D1: control point 2 has weight 0: a NURBS weight must "
                               "be finite and > 0"));
  CHECK_THAT(error_of(drawing(spline("D2", "W", 3, {0, 0, 0, 1, 1, 1}, points)), on_layer("W")),
             Catch::StartsWith("t.dxf layer W: SPLINE #D2: 6 knots; 5 control points of degree 3 take 9"));
  CHECK_THAT(
      error_of(drawing(spline("D3", "W", 5, std::vector<double>(11, 0.0),
                              {{0, 0}, {1, 1}, {2, 0}, {3, 1}, {4, 0}})),
               on_layer("W")),
      Catch::StartsWith("t.dxf layer W: SPLINE #D3: degree 5; fabmesh reads splines of degree 1, 2 or 3"));
  CHECK_THAT(error_of(drawing(spline("D4", "W", 3, {0, 0, 0, 0, 0.5, 0.4, 1, 1, 1}, points)), on_layer("W")),
             Catch::StartsWith("t.dxf layer W: SPLINE #D4: knot 6 (0.4) is not finite and non-decreasing"));
}

TEST_CASE("dxf loops: a rational SPLINE (NURBS) is read exactly, as rational cubic spans",
          "[io][design][dxf][rational]") {
  // A full circle of radius 250 saved as a rational quadratic NURBS: a loop of four exact spans.
  const Vec2 c(1200, 300);
  const double r = 250.0;
  const DxfLoops circle =
      parse_dxf_loops(drawing(spline("5A", "C", 2, kCircleKnots, circle_points(c, r), kCircleWeights)),
                      "t.dxf", on_layer("C"));
  REQUIRE(circle.loops.size() == 1);
  const CurveSpec& loop = circle.loops[0].curve;
  REQUIRE(loop.segments.size() == 4);
  const CompositeCurve curve = construct_curve(loop);
  double worst = 0.0;
  for (std::size_t i = 0; i < 4; ++i) {
    CHECK(loop.segments[i].kind == SegmentKind::RationalBezier);
    CHECK(loop.segments[i].name == fmt::format("SPLINE #5A piece {}", i + 1));
    for (int j = 0; j <= 100; ++j) {
      const double t = j / 100.0;
      worst = std::max(worst, std::abs((curve.segments()[i].point(t) - c).norm() - r));
      const Vec2 want = rational_de_boor(kCircleKnots, circle_points(c, r), kCircleWeights, 2,
                                         (static_cast<double>(i) + t) / 4.0);
      CHECK((curve.segments()[i].point(t) - want).norm() <= 1e-12 * 1500);
    }
  }
  WARN("NURBS circle of radius 250: largest radius error " << worst);
  CHECK(worst <= 1e-9 * r);
  // Exactly round: every joint G2, the area that of the circle.
  for (const JointReport& j : curve.joints()) CHECK(j.achieved == Continuity::G2);
  CHECK(loop_area(loop) == Approx(kPi * r * r).epsilon(1e-9));
  // The same circle in the four-quadrant knot form, in inches: the weights are not scaled.
  std::vector<double> quadrants{0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4};
  const DxfLoops inches = parse_dxf_loops(
      drawing(spline("5B", "C", 2, quadrants, circle_points(Vec2(1, 2), 10), kCircleWeights), 1), "t.dxf",
      on_layer("C"));
  REQUIRE(inches.loops.size() == 1);
  CHECK(loop_area(inches.loops[0].curve) == Approx(kPi * 254.0 * 254.0).epsilon(1e-9));
  // A half circle drawn against the loop's direction: its spans and weights are reversed.
  const std::vector<Vec2> round = circle_points(Vec2(0, 0), r);
  const std::vector<Vec2> half(round.begin(), round.begin() + 5);
  const DxfLoops d = parse_dxf_loops(
      drawing(line("6A", "D", r, 0, -r, 0) + spline("6B", "D", 2, {0, 0, 0, 0.5, 0.5, 1, 1, 1}, half,
                                                    {1, std::sqrt(0.5), 1, std::sqrt(0.5), 1})),
      "t.dxf", on_layer("D"));
  REQUIRE(d.loops.size() == 1);
  CHECK(loop_area(d.loops[0].curve) == Approx(-kPi * r * r / 2).epsilon(1e-10));
  // A cubic NURBS: the spans whose points weigh alike stay polynomial, the others are rational.
  const std::vector<double> knots{0, 0, 0, 0, 0.4, 1, 1, 1, 1};
  const std::vector<Vec2> points{{100, 0}, {110, 60}, {50, 90}, {-10, 60}, {0, 0}};
  for (const std::vector<double>& weights : {std::vector<double>{1, 2, 1, 1, 1}, {1, 1, 1, 1, 3.5}}) {
    const DxfLoops got =
        parse_dxf_loops(drawing(line("A0", "S", 0, 0, 100, 0) + spline("A1", "S", 3, knots, points, weights)),
                        "t.dxf", on_layer("S"));
    REQUIRE(got.loops.size() == 1);
    const CurveSpec& spec = got.loops[0].curve;
    const CompositeCurve built = construct_curve(spec);
    verify_declared_continuity(spec, built);
    std::vector<SegmentKind> kinds;
    for (std::size_t i = 0; i < spec.segments.size(); ++i) {
      if (spec.segments[i].name.rfind("SPLINE #A1", 0) != 0) continue;
      const double u0 = kinds.empty() ? 0.0 : 0.4, u1 = kinds.empty() ? 0.4 : 1.0;
      kinds.push_back(spec.segments[i].kind);
      for (int j = 0; j <= 50; ++j) {
        const double t = j / 50.0;
        const Vec2 want = rational_de_boor(knots, points, weights, 3, u0 + t * (u1 - u0));
        CHECK((built.segments()[i].point(t) - want).norm() <= 1e-12 * 100);
      }
    }
    // Weight 2 on point 2 reaches both spans; weight 3.5 on the last point only the second.
    const SegmentKind first = weights[1] == 2 ? SegmentKind::RationalBezier : SegmentKind::QuasiBSpline;
    CHECK(kinds == std::vector<SegmentKind>{first, SegmentKind::RationalBezier});
    for (const JointReport& j : built.joints()) {
      if (spec.segments[j.before].name.rfind("SPLINE", 0) == 0 &&
          spec.segments[j.after].name.rfind("SPLINE", 0) == 0)
        CHECK(j.achieved == Continuity::G2);
    }
  }
  // Weights far apart (a factor 1e20) and a rational polyline of degree 1: still the NURBS's own points.
  for (const int degree : {1, 2}) {
    const std::vector<double> open =
        degree == 2 ? std::vector<double>{0, 0, 0, 1, 1, 1} : std::vector<double>{0, 0, 1, 1};
    const std::vector<Vec2> arch{{0, 0}, {50, 80}, {100, 0}};
    const std::vector<double> far{1e-10, 1, 1e10};
    const std::vector<Vec2> used(arch.begin(), arch.begin() + degree + 1);
    const std::vector<double> used_weights(far.begin(), far.begin() + degree + 1);
    const DxfLoops got = parse_dxf_loops(drawing(spline("7A", "F", degree, open, used, used_weights) +
                                                 line("7B", "F", used.back().x(), used.back().y(), -40, -40) +
                                                 line("7C", "F", -40, -40, 0, 0)),
                                         "t.dxf", on_layer("F"));
    REQUIRE(got.loops.size() == 1);
    const CurveSpec& spec = got.loops[0].curve;
    const CompositeCurve built = construct_curve(spec);
    std::size_t found = 0;
    for (std::size_t i = 0; i < spec.segments.size(); ++i) {
      if (spec.segments[i].name != "SPLINE #7A") continue;
      ++found;
      CHECK(spec.segments[i].kind == SegmentKind::RationalBezier);
      for (int j = 0; j <= 50; ++j) {
        const double t = j / 50.0;
        const Vec2 want = rational_de_boor(open, used, used_weights, degree, t);
        CHECK((built.segments()[i].point(t) - want).norm() <= 1e-12 * 100);
      }
    }
    CHECK(found == 1);
  }
  // Weights that are not finite and > 0: bad input naming the entity and the control point.
  CHECK_THAT(error_of(drawing(spline("5C", "W", 2, kCircleKnots, circle_points(c, r),
                                     {1, std::sqrt(0.5), 1, -0.5, 1, std::sqrt(0.5), 1, std::sqrt(0.5), 1})),
                      on_layer("W")),
             Catch::Equals(
                 "t.dxf layer W: SPLINE #5C: control point 4 has weight -0.5: a NURBS weight must be finite "
                 "and > 0"));
}

TEST_CASE("dxf loops: the example template, written with ezdxf, reads into its outline and holes",
          "[io][design][dxf]") {
  const std::string path = std::string(FABMESH_SOURCE_DIR) + "/configs/examples/kitchen_template.dxf";
  const DxfLoops outline = read_dxf_loops(path, on_layer("OUTLINE", 0.05));
  REQUIRE(outline.loops.size() == 1);
  // 2400 x 650 less a quarter-round corner of radius 80 and a bulged one of radius 100.
  const double corners = (80.0 * 80.0 - kPi * 1600.0) + (100.0 * 100.0 - kPi * 2500.0);
  CHECK(std::abs(loop_area(outline.loops[0].curve)) == Approx(2400.0 * 650.0 - corners).epsilon(1e-13));
  const DxfLoops holes = read_dxf_loops(path, on_layer("HOLES", 0.05));
  REQUIRE(holes.loops.size() == 3);
  const double sink = 760.0 * 440.0 - 4.0 * (3600.0 - kPi * 900.0);
  CHECK(std::abs(loop_area(holes.loops[0].curve)) == Approx(sink).epsilon(1e-13));
  CHECK(std::abs(loop_area(holes.loops[1].curve)) == Approx(kPi * 17.5 * 17.5).epsilon(1e-13));
  CHECK(std::abs(loop_area(holes.loops[2].curve)) == Approx(kPi * 200.0 * 120.0).epsilon(1e-13));
  CHECK(holes.notes.back() == path + " layer HOLES: left out 1 POINT (no outline in them)");
}

TEST_CASE("dxf loops: a batch's content key holds the drawing's bytes, not its name", "[io][design][dxf]") {
  // A batch reuses a variant's files when its canonical text is unchanged:
  // an edited drawing must change it, a renamed one must not.
  const std::filesystem::path dir = std::filesystem::path(FABMESH_TEST_TMP) / "dxf_canonical";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string square = line("5A", "S", 0, 0, 1, 0) + line("5B", "S", 1, 0, 1, 1) +
                             line("5C", "S", 1, 1, 0, 1) + line("5D", "S", 0, 1, 0, 0);
  auto canonical = [&](const std::string& file, const std::string& bytes) {
    write_file_atomically((dir / file).string(), bytes);
    const std::string text = "kind: countertop\nthickness: 1\noutline: {dxf: " + file +
                             ", layer: S}\nholes: [{dxf: " + file + ", layer: S}]\n";
    return DesignSource(text, (dir / "d.yaml").string()).canonical({});
  };
  const std::string a = canonical("a.dxf", drawing(square));
  CHECK(a == canonical("b.dxf", drawing(square)));
  CHECK(a != canonical("a.dxf", drawing(square, 1)));
  CHECK(a.find("a.dxf") == std::string::npos);
}

TEST_CASE("dxf loops: every fuzz seed reads into loops that build", "[io][design][dxf]") {
  // The fuzzer starts from these: each must reach the chaining, not stop at a refusal.
  const std::filesystem::path seeds = std::filesystem::path(FABMESH_SOURCE_DIR) / "tests/data/fuzz-seeds/dxf";
  int read = 0;
  for (const auto& entry : std::filesystem::directory_iterator(seeds)) {
    if (entry.path().filename().string().rfind("refused-", 0) == 0) continue;  // must be refused (below)
    INFO(entry.path().string());
    // As the fuzzer reads them: every layer, then the example's layers.
    std::size_t loops = 0;
    for (const char* layer : {"", "OUTLINE", "HOLES"}) {
      try {
        const DxfLoops got = read_dxf_loops(entry.path().string(), on_layer(layer, 1e-3));
        for (const DxfLoop& loop : got.loops) CHECK(std::isfinite(loop_area(loop.curve)));
        loops += got.loops.size();
      } catch (const FileError&) {
        // A layer the seed does not have, or (every layer) the template's notes.
      }
    }
    CHECK(loops > 0);
    ++read;
  }
  CHECK(read >= 3);
}

TEST_CASE("dxf loops: an LWPOLYLINE without group 90 is its own vertices, not the one before it",
          "[io][design][dxf]") {
  // Issue 43: a 1000 x 600 outline after a 2100 x 1100 one built 2100 x 1100.
  std::string first = lwpolyline("10", "BIG", {{0, 0, 0}, {2100, 0, 0}, {2100, 1100, 0}, {0, 1100, 0}}, true);
  std::string second =
      lwpolyline("11", "OUTLINE", {{0, 0, 0}, {1000, 0, 0}, {1000, 600, 0}, {0, 600, 0}}, true);
  second.erase(second.find("90\n4\n"), 5);  // no vertex count
  const DxfLoops got = parse_dxf_loops(drawing(first + second), "t.dxf", on_layer("OUTLINE"));
  REQUIRE(got.loops.size() == 1);
  CHECK(loop_area(got.loops[0].curve) == Approx(1000.0 * 600.0).epsilon(1e-14));
  CHECK(got.loops[0].curve.segments.size() == 4);
}

TEST_CASE("dxf loops: a bulge of rounding noise is a straight span, a real one stays an exact arc",
          "[io][design][dxf]") {
  // CAD writes 1e-12 ... 1e-300 for straight spans: they were refused as arcs of radius 2.5e18.
  for (const double noise : {1e-12, -1e-15, 1e-100, 1e-300}) {
    INFO(noise);
    const DxfLoops got = parse_dxf_loops(
        drawing(lwpolyline("20", "R", {{0, 0, noise}, {1000, 0, noise}, {1000, 600, -noise}, {0, 600, noise}},
                           true)),
        "t.dxf", on_layer("R"));
    REQUIRE(got.loops.size() == 1);
    for (const SegmentSpec& s : got.loops[0].curve.segments) CHECK(s.kind == SegmentKind::Line);
    CHECK(loop_area(got.loops[0].curve) == Approx(600000.0).epsilon(1e-14));
    CHECK(got.notes.back() ==
          "t.dxf layer R: 4 polyline span(s) with a bulge of at most 1e-09 of the drawing's size read as "
          "straight");
  }
  // A sagitta above 1e-9 of the drawing's size is an arc: 1e-6 on a 1000 mm side lifts it 0.5 um
  // (outward: a positive bulge on a counter-clockwise loop), adding 2/3 of chord x sagitta.
  const DxfLoops arc = parse_dxf_loops(
      drawing(lwpolyline("21", "R", {{0, 0, 1e-6}, {1000, 0, 0}, {1000, 600, 0}, {0, 600, 0}}, true)),
      "t.dxf", on_layer("R"));
  REQUIRE(arc.loops.size() == 1);
  CHECK(arc.loops[0].curve.segments[0].kind == SegmentKind::EllipseArc);
  CHECK(loop_area(arc.loops[0].curve) == Approx(600000.0 + 2.0 / 3.0 * 1000.0 * 0.5e-3).epsilon(1e-9));
}

TEST_CASE("dxf loops: an entity off the XY plane is bad input, naming it and its height",
          "[io][design][dxf]") {
  const std::string square =
      line("5A", "S", 0, 0, 100, 0) + line("5B", "S", 100, 0, 100, 100) + line("5C", "S", 100, 100, 0, 100);
  std::string high = line("5D", "S", 0, 100, 0, 0);
  high.replace(high.find("30\n0\n"), 5, "30\n50\n");
  high.replace(high.find("31\n0\n"), 5, "31\n50\n");
  CHECK_THAT(error_of(drawing(square + high), on_layer("S")),
             Catch::Equals("t.dxf layer S: LINE #5D: at z = 50, off the drawing's XY plane (z = 0)"));
  std::string raised_arc = arc("6A", "S", 50, 0, 50, 180, 360);
  raised_arc.replace(raised_arc.find("30\n0\n"), 5, "30\n50\n");
  CHECK_THAT(error_of(drawing(raised_arc + line("6B", "S", 100, 0, 0, 0)), on_layer("S")),
             Catch::EndsWith("ARC #6A: at z = 50, off the drawing's XY plane (z = 0)"));
  std::string lifted = lwpolyline("6C", "S", {{0, 0, 0}, {10, 0, 0}, {10, 10, 0}}, true);
  lifted.insert(lifted.find("70\n"), "38\n50\n");
  CHECK_THAT(error_of(drawing(lifted), on_layer("S")),
             Catch::EndsWith("LWPOLYLINE #6C: at z = 50, off the drawing's XY plane (z = 0)"));
  // Rounding noise in z is the plane.
  std::string noise = line("5D", "S", 0, 100, 0, 0);
  noise.replace(noise.find("30\n0\n"), 5, "30\n1e-12\n");
  CHECK(parse_dxf_loops(drawing(square + noise), "t.dxf", on_layer("S")).loops.size() == 1);
}

TEST_CASE("dxf loops: a template cut short is refused, never read without its last entities",
          "[io][design][dxf]") {
  // Issue 43: three holes drawn, the file cut before ENDSEC/EOF: one hole was cut.
  const std::string holes =
      "0\nCIRCLE\n5\nA1\n8\nHOLES\n10\n100\n20\n100\n30\n0\n40\n20\n"
      "0\nCIRCLE\n5\nA2\n8\nHOLES\n10\n200\n20\n100\n30\n0\n40\n20\n"
      "0\nCIRCLE\n5\nA3\n8\nHOLES\n10\n300\n20\n100\n30\n0\n40\n20\n";
  const std::string whole = drawing(holes);
  REQUIRE(parse_dxf_loops(whole, "t.dxf", on_layer("HOLES")).loops.size() == 3);
  for (const std::string& cut :
       {whole.substr(0, whole.find("0\nENDSEC", whole.find("A3"))), whole.substr(0, whole.rfind("0\nEOF")),
        whole.substr(0, whole.find("40\n20\n", whole.find("A3")) + 4)}) {
    CHECK_THAT(error_of(cut, on_layer("HOLES")), Catch::Matches("t\\.dxf:[0-9]+: .*(cut short|no value).*"));
  }
}

TEST_CASE("dxf loops: every refused fuzz seed is refused naming the file and the line", "[io][design][dxf]") {
  // refused-*.dxf: cut short, a count that disagrees, a value that is no number, off the plane.
  const std::filesystem::path seeds = std::filesystem::path(FABMESH_SOURCE_DIR) / "tests/data/fuzz-seeds/dxf";
  int refused = 0;
  for (const auto& entry : std::filesystem::directory_iterator(seeds)) {
    if (entry.path().filename().string().rfind("refused-", 0) != 0) continue;
    const std::string path = entry.path().string();
    INFO(path);
    try {
      read_dxf_loops(path, on_layer("", 1e-3));
      FAIL("read without a refusal");
    } catch (const FileError& e) {
      CHECK(e.line() > 0);
      CHECK_THAT(e.what(), Catch::StartsWith(path));
    }
    ++refused;
  }
  CHECK(refused >= 6);
}
