#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "geometry/fairing/build_curve.h"
#include "geometry/sampling/cut_loop.h"
#include "io/cutting/dxf.h"
#include "io/cutting/svg.h"
#include "tests/geometry/section/region_shapes.h"
#include "tests/io/cutting/dxf_read_back.h"
#include "tests/io/mesh/external_tool.h"

using namespace fabmesh;
using namespace fabmesh::test;

namespace {

// An outline of a line, an exact elliptic arc and two T-Bézier segments
// (one polyline run), and two holes: a rotated ellipse and a rounded rectangle.
std::vector<CutLoop> kitchen_loops(double tolerance) {
  EllipseArcParams bump;
  bump.center = {600, 300};
  bump.a = 200;
  bump.b = 80;
  bump.from_deg = 0;
  bump.to_deg = 180;
  const CompositeCurve outline(
      {Segment::line({0, 0}, {1200, 0}),
       Segment::tbezier({Vec2(1200, 0), Vec2(1300, 0), Vec2(1300, 300), Vec2(1200, 300)}, 0, 0),
       Segment::line({1200, 300}, {800, 300}), Segment::ellipse_arc(bump),
       Segment::line({400, 300}, {0, 300}),
       Segment::tbezier({Vec2(0, 300), Vec2(-100, 300), Vec2(-100, 0), Vec2(0, 0)}, 0.5, 0.5)},
      true);
  CutLoopOptions o;
  o.tolerance = tolerance;
  std::vector<CutLoop> loops{cut_loop(outline, "outline", true, o)};
  o.reverse = true;
  loops.push_back(cut_loop(ellipse({300, 150}, 120, 60, 30), "holes[0] (ellipse)", false, o));
  loops.push_back(cut_loop(rounded_rect(700, 50, 1100, 250, 20), "holes[1] (rounded_rect)", false, o));
  return loops;
}

// The quarter (k = 0..3) of the circle about c of radius r, counter-clockwise
// from angle 90 k degrees, as the rational cubic Bézier a quadratic NURBS
// quarter raises to (docs/math/curves.md 5).
Segment circle_quarter(const Vec2& c, double r, int k) {
  const double s = std::sqrt(0.5), inner = 2 * s / (1 + 2 * s), w = (1 + 2 * s) / 3;
  const Eigen::Rotation2Dd turn(k * M_PI / 2);
  const auto at = [&](double x, double y) -> Vec2 { return c + turn * Vec2(r * x, r * y); };
  return Segment::rational_bezier({at(1, 0), at(1, inner), at(inner, 1), at(0, 1)}, {1, w, w, 1});
}

// An outline of two lines, a rational span with unequal weights, a span with
// equal weights (a polynomial cubic) and a T-Bézier; a hole: a circle of four
// rational quarters, reversed.
std::vector<CutLoop> spline_loops() {
  const CompositeCurve outline(
      {Segment::line({0, 0}, {600, 0}),
       Segment::rational_bezier({Vec2(600, 0), Vec2(750, 40), Vec2(720, 260), Vec2(600, 300)},
                                {1, 2, 0.5, 1.5}),
       Segment::line({600, 300}, {300, 300}),
       Segment::rational_bezier({Vec2(300, 300), Vec2(200, 380), Vec2(100, 220), Vec2(0, 300)}, {2, 2, 2, 2}),
       Segment::tbezier({Vec2(0, 300), Vec2(-100, 300), Vec2(-100, 0), Vec2(0, 0)}, 0.5, 0.5)},
      true);
  std::vector<Segment> quarters;
  for (int k = 0; k < 4; ++k) quarters.push_back(circle_quarter({300, 150}, 80, k));
  CutLoopOptions o;
  std::vector<CutLoop> loops{cut_loop(outline, "outline", true, o)};
  o.reverse = true;
  loops.push_back(cut_loop(CompositeCurve(quarters, true), "holes[0] (circle)", false, o));
  return loops;
}

// The group code / value pairs of a DXF text, trimmed.
std::vector<std::pair<std::string, std::string>> dxf_pairs(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::pair<std::string, std::string>> pairs;
  std::string code, value;
  auto trim = [](std::string s) {
    s.erase(0, s.find_first_not_of(" \r"));
    s.erase(s.find_last_not_of(" \r") + 1);
    return s;
  };
  while (std::getline(in, code) && std::getline(in, value)) pairs.emplace_back(trim(code), trim(value));
  return pairs;
}

// End points of the DXF entities on one layer chain into closed loops: every
// end point meets exactly one other entity's end point (within `eps`).
int closed_chains(const std::vector<DrawnEntity>& entities, const std::string& layer, double eps) {
  std::vector<std::pair<Vec2, Vec2>> ends;
  int whole = 0;
  for (const DrawnEntity& e : entities) {
    if (e.layer != layer) continue;
    if (e.closed) {
      ++whole;
      continue;
    }
    ends.emplace_back(e.points.front(), e.points.back());
  }
  // Union of entities that share an end point; each end point must have exactly one partner.
  std::vector<int> parent(ends.size());
  for (std::size_t i = 0; i < ends.size(); ++i) parent[i] = static_cast<int>(i);
  std::function<int(int)> find = [&](int i) { return parent[i] == i ? i : parent[i] = find(parent[i]); };
  for (std::size_t i = 0; i < ends.size(); ++i) {
    for (const Vec2& p : {ends[i].first, ends[i].second}) {
      int partners = 0;
      for (std::size_t j = 0; j < ends.size(); ++j) {
        for (const Vec2& q : {ends[j].first, ends[j].second}) {
          if (&p == &q) continue;
          if (j == i && (p - q).norm() > eps) continue;
          if (j != i && (p - q).norm() <= eps) {
            ++partners;
            parent[find(static_cast<int>(i))] = find(static_cast<int>(j));
          }
        }
      }
      if (partners != 1) return -1;
    }
  }
  int chains = 0;
  for (std::size_t i = 0; i < ends.size(); ++i) chains += find(static_cast<int>(i)) == static_cast<int>(i);
  return chains + whole;
}

}  // namespace

TEST_CASE("cut_loop: lines, exact arcs and one polyline per T-Bezier run, each loop closed",
          "[io][cutting][countertop]") {
  const auto loops = kitchen_loops(0.01);
  REQUIRE(loops.size() == 3);
  std::map<CutKind, int> kinds;
  for (const CutEntity& e : loops[0].entities) ++kinds[e.kind];
  CHECK(kinds[CutKind::Line] == 3);
  CHECK(kinds[CutKind::Arc] == 1);
  CHECK(kinds[CutKind::Polyline] == 2);
  for (const CutLoop& l : loops) {
    for (std::size_t i = 0; i < l.entities.size(); ++i) {
      const Vec2 end = l.entities[i].points.back();
      const Vec2 next = l.entities[(i + 1) % l.entities.size()].points.front();
      CHECK((end - next).norm() < 1e-9);
    }
  }
  // Reversed holes run clockwise: the rounded rectangle's arcs go from a larger to a smaller angle.
  for (const CutEntity& e : loops[2].entities) {
    if (e.kind == CutKind::Arc) CHECK(e.arc.to_deg < e.arc.from_deg);
  }
}

TEST_CASE("dxf: lines, arcs, ellipses and polylines read back with dxflib as closed loops per layer",
          "[io][cutting][dxf][countertop]") {
  const auto loops = kitchen_loops(0.01);
  const std::string bytes = encode_dxf(loops);
  CHECK(bytes.find("LWPOLYLINE") != std::string::npos);
  CHECK(bytes.find("$INSUNITS") != std::string::npos);
  const std::vector<DrawnEntity> entities = parse_dxf(bytes, "kitchen.dxf");
  std::map<std::string, int> types;
  for (const DrawnEntity& e : entities) ++types[e.type + "@" + e.layer];
  CHECK(types["LINE@OUTLINE"] == 3);
  CHECK(types["ELLIPSE@OUTLINE"] == 1);
  CHECK(types["POLYLINE@OUTLINE"] == 2);
  CHECK(types["ELLIPSE@HOLES"] == 1);  // the whole rotated ellipse
  CHECK(types["ARC@HOLES"] == 4);      // the rounded rectangle's corners
  CHECK(types["LINE@HOLES"] == 4);
  CHECK(closed_chains(entities, "OUTLINE", 1e-6) == 1);
  CHECK(closed_chains(entities, "HOLES", 1e-6) == 2);
  // The whole ellipse spans 2 pi and its points lie on the exact ellipse.
  for (const DrawnEntity& e : entities) {
    if (e.type == "ELLIPSE" && e.layer == "HOLES") CHECK(e.closed);
    if (e.type != "POLYLINE") continue;
    CHECK(e.points.size() >= 3);
  }
}

TEST_CASE("dxf: an arc whose end points are wrong breaks the chain (the check can fail)",
          "[io][cutting][dxf][countertop]") {
  auto loops = kitchen_loops(0.01);
  for (CutEntity& e : loops[0].entities) {
    if (e.kind == CutKind::Arc) e.arc.to_deg = 170;  // no longer reaches the next line
  }
  CHECK(closed_chains(parse_dxf(encode_dxf(loops), "broken.dxf"), "OUTLINE", 1e-6) == -1);
}

TEST_CASE("dxf: two encodes are byte-identical and every handle reference names a handle of the file",
          "[io][cutting][dxf][determinism]") {
  const auto loops = kitchen_loops(0.01);
  const std::string first = encode_dxf(loops);
  CHECK(encode_dxf(loops) == first);
  // Group codes 330/340/350/360 point at handles (group 5 or 105): a pointer to
  // no handle is uninitialised memory (as DIMSTYLE's 340 was under a style not
  // named "Standard").
  const auto pairs = dxf_pairs(first);
  std::set<std::string> handles;
  for (const auto& [c, v] : pairs) {
    if (c == "5" || c == "105") handles.insert(v);
  }
  int references = 0;
  for (const auto& [c, v] : pairs) {
    if (c != "330" && c != "340" && c != "350" && c != "360") continue;
    INFO("group " << c << " -> " << v);
    CHECK(handles.count(v) == 1);
    ++references;
  }
  CHECK(references > 0);
}

TEST_CASE("dxf: ezdxf reads the file and its audit finds nothing to fix", "[io][cutting][dxf]") {
  // ezdxf from Debian (python3-ezdxf, installed by scripts/install-deps.sh --test)
  // under the system interpreter. dxflib alone leaves the OBJECTS without
  // owners: 13 "invalid owner handle" fixes a file.
  const std::string path = std::string(FABMESH_TEST_TMP) + "/audit-kitchen.dxf";
  { std::ofstream(path, std::ios::binary) << encode_dxf(kitchen_loops(0.01)); }
  const std::string script =
      "import sys, ezdxf\n"
      "doc = ezdxf.readfile(sys.argv[1])\n"
      "a = doc.audit()\n"
      "print(len(a.errors), len(a.fixes), len(doc.modelspace()))\n"
      "for e in list(a.errors) + list(a.fixes): print(e.message)\n";
  const test::ToolRun run = test::run_tool("/usr/bin/python3 -c '" + script + "' " + path);
  REQUIRE(run.code == 0);
  const std::string& out = run.output;
  INFO(out);
  std::istringstream first(out);
  int errors = -1, fixes = -1, entities = -1;
  first >> errors >> fixes >> entities;
  CHECK(errors == 0);
  CHECK(fixes == 0);
  CHECK(entities > 0);
}

TEST_CASE("dxf: a loop that is one T-Bezier run is a single closed LWPOLYLINE",
          "[io][cutting][dxf][countertop]") {
  const CompositeCurve blob(
      {Segment::tbezier({Vec2(0, 0), Vec2(100, -50), Vec2(200, 50), Vec2(100, 100)}, 0, 0),
       Segment::tbezier({Vec2(100, 100), Vec2(0, 150), Vec2(-100, 50), Vec2(0, 0)}, 0, 0)},
      true);
  const std::vector<CutLoop> loops{cut_loop(blob, "outline", true, {})};
  REQUIRE(loops[0].entities.size() == 1);
  const auto entities = parse_dxf(encode_dxf(loops), "blob.dxf");
  REQUIRE(entities.size() == 1);
  CHECK(entities[0].type == "POLYLINE");
  CHECK(entities[0].closed);
  CHECK((entities[0].points.front() - entities[0].points.back()).norm() > 1.0);  // not repeated
}

TEST_CASE("svg: one path per loop, A commands for arcs, L for lines and polylines, viewBox in mm",
          "[io][cutting][svg][countertop]") {
  const auto loops = kitchen_loops(0.01);
  const std::string svg = encode_svg(loops);
  // Plain scanning, not std::regex: libstdc++'s regex recurses per character
  // and overflows the stack on long path data under AddressSanitizer.
  std::vector<std::pair<std::string, std::string>> paths;
  for (std::size_t at = svg.find("<path id=\""); at != std::string::npos;
       at = svg.find("<path id=\"", at + 1)) {
    const std::size_t id_begin = at + 10, id_end = svg.find('"', id_begin);
    const std::size_t d_begin = svg.find("d=\"", id_end) + 3, d_end = svg.find('"', d_begin);
    paths.emplace_back(svg.substr(id_begin, id_end - id_begin), svg.substr(d_begin, d_end - d_begin));
  }
  REQUIRE(paths.size() == 3);
  CHECK(paths[0].first == "outline");
  for (const auto& [id, d] : paths) {
    CHECK(d.rfind("M ", 0) == 0);
    CHECK(d.substr(d.size() - 2) == " Z");
    CHECK(std::count(d.begin(), d.end(), 'M') == 1);
  }
  auto count = [](const std::string& d, char c) { return std::count(d.begin(), d.end(), c); };
  CHECK(count(paths[0].second, 'A') == 2);  // the 180-degree bump in two pieces
  CHECK(count(paths[0].second, 'L') > 10);  // lines and the sampled T-Bezier runs
  CHECK(count(paths[1].second, 'A') == 3);  // a whole ellipse in 120-degree pieces
  CHECK(count(paths[1].second, 'L') == 0);
  CHECK(count(paths[2].second, 'A') == 4);
  CHECK(count(paths[2].second, 'L') == 4);
  // viewBox: the bounds plus the 5 mm margin; x from the sampled T-Bezier ends, y from the line (0) and the
  // bump's apex (380).
  double lo = INFINITY, hi = -INFINITY;
  for (const CutEntity& e : loops[0].entities) {
    for (const Vec2& p : e.points) lo = std::min(lo, p.x()), hi = std::max(hi, p.x());
  }
  const std::size_t view = svg.find("viewBox=\"");
  REQUIRE(view != std::string::npos);
  std::istringstream box(svg.substr(view + 9, svg.find('"', view + 9) - view - 9));
  double x0 = 0, y0 = 0, w = 0, h = 0;
  REQUIRE(static_cast<bool>(box >> x0 >> y0 >> w >> h));
  CHECK(x0 == Approx(lo - 5).margin(0.02));
  CHECK(y0 == Approx(-380 - 5).margin(1e-9));
  CHECK(w == Approx(hi - lo + 10).margin(0.02));
  CHECK(h == Approx(380 + 10).margin(1e-9));
}

TEST_CASE("dxf: rational Bezier spans are SPLINE entities of degree 3 with their points, knots and weights",
          "[io][cutting][dxf][rational]") {
  const auto loops = spline_loops();
  std::vector<const CutEntity*> splines;
  for (const CutLoop& l : loops) {
    for (const CutEntity& e : l.entities) {
      if (e.kind == CutKind::Spline) splines.push_back(&e);
    }
  }
  REQUIRE(splines.size() == 6);
  const std::string bytes = encode_dxf(loops);
  // The groups of each SPLINE, as written.
  std::vector<std::map<std::string, std::vector<std::string>>> groups;
  bool in_spline = false;
  for (const auto& [code, value] : dxf_pairs(bytes)) {
    if (code == "0") {
      in_spline = value == "SPLINE";
      if (in_spline) groups.emplace_back();
      continue;
    }
    if (in_spline) groups.back()[code].push_back(value);
  }
  REQUIRE(groups.size() == 6);
  for (std::size_t i = 0; i < groups.size(); ++i) {
    auto& g = groups[i];
    const CutEntity& e = *splines[i];
    const bool rational =
        !(e.weights[1] == e.weights[0] && e.weights[2] == e.weights[0] && e.weights[3] == e.weights[0]);
    INFO("SPLINE " << i);
    CHECK(g["100"] == std::vector<std::string>{"AcDbEntity", "AcDbSpline"});
    CHECK(g["8"] == std::vector<std::string>{i < 2 ? "OUTLINE" : "HOLES"});
    CHECK(g["70"] == std::vector<std::string>{rational ? "12" : "8"});  // planar, and rational with weights
    CHECK(g["71"] == std::vector<std::string>{"3"});
    CHECK(g["72"] == std::vector<std::string>{"8"});
    CHECK(g["73"] == std::vector<std::string>{"4"});
    CHECK(g["74"] == std::vector<std::string>{"0"});
    REQUIRE(g["40"].size() == 8);
    for (std::size_t k = 0; k < 8; ++k) CHECK(std::stod(g["40"][k]) == (k < 4 ? 0.0 : 1.0));
    REQUIRE(g["10"].size() == 4);
    REQUIRE(g["20"].size() == 4);
    REQUIRE(g["30"].size() == 4);
    for (std::size_t j = 0; j < 4; ++j) {
      CHECK(std::stod(g["10"][j]) == Approx(e.points[j].x()).margin(1e-12));
      CHECK(std::stod(g["20"][j]) == Approx(e.points[j].y()).margin(1e-12));
      CHECK(std::stod(g["30"][j]) == 0.0);
    }
    if (rational) {
      REQUIRE(g["41"].size() == 4);
      for (std::size_t j = 0; j < 4; ++j) CHECK(std::stod(g["41"][j]) == e.weights[j]);  // exactly
    } else {
      CHECK(g["41"].empty());
    }
  }
  // The outline's second span has equal weights: a polynomial cubic, no weights written.
  CHECK(groups[1]["70"] == std::vector<std::string>{"8"});
  // dxflib reads them back with their points and weights; the chains close.
  const std::vector<DrawnEntity> entities = parse_dxf(bytes, "splines.dxf");
  std::map<std::string, int> types;
  for (const DrawnEntity& e : entities) ++types[e.type + "@" + e.layer];
  CHECK(types["LINE@OUTLINE"] == 2);
  CHECK(types["SPLINE@OUTLINE"] == 2);
  CHECK(types["POLYLINE@OUTLINE"] == 1);
  CHECK(types["SPLINE@HOLES"] == 4);
  std::size_t i = 0;
  for (const DrawnEntity& d : entities) {
    if (d.type != "SPLINE") continue;
    REQUIRE(i < splines.size());
    const CutEntity& e = *splines[i++];
    CHECK(d.degree == 3);
    CHECK(d.knots == std::vector<double>{0, 0, 0, 0, 1, 1, 1, 1});
    REQUIRE(d.points.size() == 4);
    REQUIRE(d.weights.size() == 4);
    for (std::size_t j = 0; j < 4; ++j) {
      CHECK((d.points[j] - e.points[j]).norm() <= 1e-12);
      // Equal weights are written as none: they read as 1, the same curve.
      CHECK(d.weights[j] == (d.flags & 4 ? e.weights[j] : 1.0));
    }
  }
  CHECK(closed_chains(entities, "OUTLINE", 1e-9) == 1);
  CHECK(closed_chains(entities, "HOLES", 1e-9) == 1);
}

TEST_CASE("dxf: ezdxf reads the SPLINEs back with their control points, knots and weights, nothing to fix",
          "[io][cutting][dxf][rational]") {
  const auto loops = spline_loops();
  const std::string path = std::string(FABMESH_TEST_TMP) + "/audit-splines.dxf";
  const std::string script_path = std::string(FABMESH_TEST_TMP) + "/audit-splines.py";
  { std::ofstream(path, std::ios::binary) << encode_dxf(loops); }
  {
    std::ofstream(script_path, std::ios::binary)
        << "import sys, ezdxf\n"
           "doc = ezdxf.readfile(sys.argv[1])\n"
           "a = doc.audit()\n"
           "print(len(a.errors), len(a.fixes))\n"
           "for e in list(a.errors) + list(a.fixes): print('#', e.message)\n"
           "for s in doc.modelspace().query('SPLINE'):\n"
           "    w = list(s.weights)\n"
           "    print(s.dxf.layer, s.dxf.degree, s.dxf.flags, len(s.knots), *s.knots)\n"
           "    print(len(s.control_points), *[repr(c) for p in s.control_points for c in p])\n"
           "    print(len(w), *[repr(x) for x in w])\n";
  }
  const test::ToolRun run = test::run_tool("/usr/bin/python3 " + script_path + " " + path);
  REQUIRE(run.code == 0);
  INFO(run.output);
  std::istringstream out(run.output);
  int errors = -1, fixes = -1;
  out >> errors >> fixes;
  CHECK(errors == 0);
  CHECK(fixes == 0);
  std::size_t read = 0;
  for (const CutLoop& l : loops) {
    for (const CutEntity& e : l.entities) {
      if (e.kind != CutKind::Spline) continue;
      const bool rational =
          !(e.weights[1] == e.weights[0] && e.weights[2] == e.weights[0] && e.weights[3] == e.weights[0]);
      std::string layer;
      int degree = 0, flags = 0;
      std::size_t knots = 0, points = 0, weights = 0;
      REQUIRE(static_cast<bool>(out >> layer >> degree >> flags >> knots));
      CHECK(layer == (l.outer ? "OUTLINE" : "HOLES"));
      CHECK(degree == 3);
      CHECK(flags == (rational ? 12 : 8));
      REQUIRE(knots == 8);
      for (std::size_t k = 0; k < 8; ++k) {
        double v = -1;
        out >> v;
        CHECK(v == (k < 4 ? 0.0 : 1.0));
      }
      REQUIRE(static_cast<bool>(out >> points));
      REQUIRE(points == 4);
      for (std::size_t j = 0; j < 4; ++j) {
        double x = 0, y = 0, z = 1;
        out >> x >> y >> z;
        CHECK(x == Approx(e.points[j].x()).margin(1e-12));
        CHECK(y == Approx(e.points[j].y()).margin(1e-12));
        CHECK(z == 0.0);
      }
      REQUIRE(static_cast<bool>(out >> weights));
      if (rational) {
        REQUIRE(weights == 4);
        for (std::size_t j = 0; j < 4; ++j) {
          double w = 0;
          out >> w;
          CHECK(w == e.weights[j]);  // exactly: written as the shortest decimal of the double
        }
      } else {
        CHECK(weights == 0);  // ezdxf: no weights, a polynomial
      }
      ++read;
    }
  }
  CHECK(read == 6);
}

TEST_CASE("svg: a Spline with equal weights is an exact C command, a rational one L within the tolerance",
          "[io][cutting][svg][rational]") {
  const auto loops = spline_loops();
  const std::string svg = encode_svg(loops);
  const std::size_t outline = svg.find("<path id=\"outline\" d=\"");
  REQUIRE(outline != std::string::npos);
  const std::string d = svg.substr(outline, svg.find('"', outline + 24) - outline);
  CHECK(std::count(d.begin(), d.end(), 'C') == 1);  // the polynomial span, exactly
  // It is the span's control points 1..3, y negated.
  const CutEntity& poly = loops[0].entities[3];
  REQUIRE(poly.kind == CutKind::Spline);
  CHECK(d.find("C " + fmt::format("{} {}", poly.points[1].x(), -poly.points[1].y())) != std::string::npos);
  CHECK(d.find(fmt::format(" {} {} {} {}", poly.points[2].x(), -poly.points[2].y(), poly.points[3].x(),
                           -poly.points[3].y())) != std::string::npos);
  // The hole: four rational quarters, sampled: L commands only, each point on the circle within the
  // tolerance.
  const std::size_t hole = svg.find("<path id=\"hole0\" d=\"");
  REQUIRE(hole != std::string::npos);
  const std::string h = svg.substr(hole + 20, svg.find('"', hole + 20) - hole - 20);
  CHECK(std::count(h.begin(), h.end(), 'C') == 0);
  CHECK(std::count(h.begin(), h.end(), 'L') > 16);
  std::istringstream in(h);
  std::string command;
  int points = 0;
  while (in >> command) {
    if (command == "Z") break;
    double x = 0, y = 0;
    REQUIRE(static_cast<bool>(in >> x >> y));
    CHECK(std::abs((Vec2(x, -y) - Vec2(300, 150)).norm() - 80) <= 1e-9);
    ++points;
  }
  CHECK(points > 16);
  // The viewBox spans the outline's exact bounds (the rational span's interior extreme in x) plus 5.
  const auto [lo, hi] = cut_bounds(loops);
  CHECK(svg.find(fmt::format("viewBox=\"{} {} {} {}\"", lo.x() - 5, -(hi.y() + 5), hi.x() - lo.x() + 10,
                             hi.y() - lo.y() + 10)) != std::string::npos);
  CHECK(hi.x() > 650);
}
