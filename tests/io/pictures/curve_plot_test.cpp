#include "io/pictures/curve_plot.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "geometry/core/errors.h"
#include "geometry/fairing/build_curve.h"
#include "io/pictures/curvature_profile.h"
#include "io/pictures/markup.h"
#include "tests/geometry/curves/segment_specs.h"
#include "tests/io/pictures/chromium.h"
#include "tests/io/pictures/png_decode.h"
#include "tests/io/pictures/xml_scan.h"

using namespace fabmesh;
using fabmesh::test::explicit_tbezier;
using fabmesh::test::joined;
using test::scan_xml;
using test::select;
using test::XmlElement;

namespace {

// Two T-Bézier segments joined G2 (alpha 1.5, beta 0.7): curvature continuous at the joint.
CurveSpec g2_pair() {
  CurveSpec spec;
  spec.segments = {explicit_tbezier({{0, 0}, {1, 2}, {3, 2.5}, {4, 1}}, -1.0, 0.3),
                   joined(Continuity::G2, {{7, 3}}, -0.6, 0.2, 1.5, 0.7)};
  return spec;
}

// Two T-Bézier segments joined G1 only: the tangent turns smoothly, the curvature jumps.
CurveSpec g1_pair() {
  CurveSpec spec;
  spec.segments = {explicit_tbezier({{1, 0.2}, {0.2, 0.4}, {1.6, 1.4}, {2, 1}}, 0.5, -0.5),
                   joined(Continuity::G1, {{3, 1}, {4, 0}}, -1.0, 0.0, 2.0)};
  return spec;
}

// A slot: line, exact half circle (radius 1), line.
CompositeCurve slot() {
  EllipseArcParams arc;
  arc.center = {4, 1};
  arc.a = arc.b = 1.0;
  arc.from_deg = -90;
  arc.to_deg = 90;
  return CompositeCurve(
      {Segment::line({0, 0}, {4, 0}), Segment::ellipse_arc(arc), Segment::line({4, 2}, {0, 2})}, false);
}

// A plot of `curve` alone, drawn as it is (no control polygon, no joints given), titled `name`.
CurvePlot one_curve_plot(const std::string& name, const CompositeCurve& curve) {
  CurvePlot plot;
  plot.title = name;
  PlotCurve c;
  c.name = name;
  c.curve = curve;
  plot.curves.push_back(c);
  return plot;
}

CurvePlot three_curves() {
  CurvePlot plot;
  plot.title = "three curves";
  plot.units = "cm";
  plot.curves.push_back(plot_curve(build_curve(g2_pair()), "G2 pair"));
  plot.curves.push_back(plot_curve(build_curve(g1_pair()), "G1 pair"));
  PlotCurve s;
  s.name = "slot";
  s.curve = slot();
  plot.curves.push_back(s);
  return plot;
}

// The numbers of an SVG path's d or a polyline's points, in order.
std::vector<double> numbers(const std::string& text) {
  std::string cleaned = text;
  for (char& c : cleaned) {
    if (std::isalpha(static_cast<unsigned char>(c)) || c == ',') c = ' ';
  }
  std::istringstream in(cleaned);
  std::vector<double> out;
  double v = 0;
  while (in >> v) out.push_back(v);
  return out;
}

// The end points of an SVG path's M, L and A commands (the arcs' radii and flags skipped).
std::vector<Vec2> path_points(const std::string& d) {
  std::vector<Vec2> out;
  std::size_t i = 0;
  while (i < d.size()) {
    const char command = d[i];
    std::size_t next = d.find_first_of("MLAZ", i + 1);
    if (next == std::string::npos) next = d.size();
    const std::vector<double> v = numbers(d.substr(i + 1, next - i - 1));
    if (command == 'A') {
      REQUIRE(v.size() == 7);
      out.emplace_back(v[5], v[6]);
    } else if (command == 'M' || command == 'L') {
      REQUIRE(v.size() == 2);
      out.emplace_back(v[0], v[1]);
    }
    i = next;
  }
  return out;
}

const XmlElement& only(const std::vector<const XmlElement*>& elements) {
  REQUIRE(elements.size() == 1);
  return *elements.front();
}

std::vector<const XmlElement*> named(const std::vector<const XmlElement*>& elements,
                                     const std::string& name) {
  std::vector<const XmlElement*> out;
  for (const XmlElement* e : elements) {
    if (e->attr("data-name") == name) out.push_back(e);
  }
  return out;
}

double number(const XmlElement& e, const std::string& key) { return std::stod(e.attr(key)); }

}  // namespace

TEST_CASE("curve plot: one curve path, control polygon and comb per curve, one marker per joint",
          "[io][pictures][plot]") {
  const CurvePlot plot = three_curves();
  const auto svg = scan_xml(plot_curves_svg(plot));
  const auto curves = select(svg, "path", "curve");
  const auto polygons = select(svg, "g", "control-polygon");
  const auto combs = select(svg, "g", "comb");
  const auto joints = select(svg, "g", "joint");
  for (const PlotCurve& c : plot.curves) {
    INFO(c.name);
    CHECK(named(curves, c.name).size() == 1);
    CHECK(named(polygons, c.name).size() == 1);
    CHECK(named(combs, c.name).size() == 1);
    CHECK(named(select(svg, "g", "curvature"), c.name).size() == 1);
    const auto marks = named(joints, c.name);
    REQUIRE(marks.size() == c.curve.joints().size());
    for (std::size_t j = 0; j < marks.size(); ++j) {
      const std::string label = to_string(c.curve.joints()[j].achieved);
      CHECK(marks[j]->attr("data-achieved") == label);
      int labels = 0;
      for (const XmlElement& e : svg) {
        if (e.has_class("joint-label") && svg[e.parent].attr("data-name") == c.name &&
            svg[e.parent].attr("data-joint") == std::to_string(j)) {
          CHECK(e.text == label);
          ++labels;
        }
      }
      CHECK(labels == 1);
    }
  }
  CHECK(curves.size() == 3);
  CHECK(polygons.size() == 3);
  CHECK(combs.size() == 3);
  // Control points: 4 per T-Bézier segment, none for lines and exact arcs.
  CHECK(only(named(polygons, "G2 pair")).attr("data-points") == "8");
  CHECK(only(named(polygons, "slot")).attr("data-points") == "0");
  CHECK(select(svg, "circle", "control-point").size() == 16);
  // The slot's joints: line to half circle and back are G1 (curvature 0 -> 1 -> 0).
  for (const XmlElement* j : named(joints, "slot")) CHECK(j->attr("data-achieved") == "G1");
  CHECK(select(svg, "g", "lost").empty());
}

TEST_CASE("curve plot: the model panel is true to scale with y up", "[io][pictures][plot]") {
  const CurvePlot plot = three_curves();
  const auto svg = scan_xml(plot_curves_svg(plot));
  const XmlElement& panel = only(select(svg, "svg", "model-panel"));
  CHECK(panel.attr("data-units") == "cm");
  const std::vector<double> box = numbers(panel.attr("viewBox"));
  REQUIRE(box.size() == 4);
  // One scale both ways: the viewBox has the panel's aspect.
  CHECK(box[2] / box[3] == Approx(number(panel, "width") / number(panel, "height")).epsilon(1e-6));

  // The scale bar is as long in viewBox units as it says in model units.
  const XmlElement& bar = only(select(svg, "g", "scale-bar"));
  const double length = number(bar, "data-length");
  std::vector<const XmlElement*> bar_lines;
  for (std::size_t i = 0; i < svg.size(); ++i) {
    if (svg[i].name == "line" && test::inside_class(svg, static_cast<int>(i), "scale-bar"))
      bar_lines.push_back(&svg[i]);
  }
  const XmlElement& line = only(bar_lines);
  CHECK(number(line, "x2") - number(line, "x1") == Approx(length).epsilon(1e-9));
  CHECK(line.attr("y1") == line.attr("y2"));
  const auto texts = select(svg, "text");
  bool labelled = false;
  for (const XmlElement* t : texts) labelled = labelled || t->text == bar.attr("data-length") + " cm";
  CHECK(labelled);

  // The curve paths are in model coordinates with y negated, inside the viewBox.
  for (const PlotCurve& c : plot.curves) {
    const std::vector<Vec2> xy = path_points(only(named(select(svg, "path", "curve"), c.name)).attr("d"));
    REQUIRE(xy.size() >= 2);
    const Vec2 start = c.curve.point(0.0), end = c.curve.point(static_cast<double>(c.curve.size()));
    CHECK(xy.front().x() == Approx(start.x()).margin(1e-6));
    CHECK(xy.front().y() == Approx(-start.y()).margin(1e-6));
    CHECK(xy.back().x() == Approx(end.x()).margin(1e-6));
    CHECK(xy.back().y() == Approx(-end.y()).margin(1e-6));
    for (const Vec2& p : xy) {
      CHECK(p.x() >= box[0]);
      CHECK(p.x() <= box[0] + box[2]);
      CHECK(p.y() >= box[1]);
      CHECK(p.y() <= box[1] + box[3]);
    }
  }
  // Polyline points lie on the curve (within the drawing tolerance).
  const PlotCurve& g2 = plot.curves[0];
  const std::vector<double> xy = numbers(only(named(select(svg, "path", "curve"), "G2 pair")).attr("d"));
  double worst = 0.0;
  for (std::size_t i = 0; i + 1 < xy.size(); i += 2) {
    double best = INFINITY;
    for (int k = 0; k <= 20000; ++k)
      best = std::min(best, (g2.curve.point(2.0 * k / 20000) - Vec2(xy[i], -xy[i + 1])).norm());
    worst = std::max(worst, best);
  }
  CHECK(worst < 1e-3);
  // The half circle is an exact SVG arc of radius 1.
  CHECK_THAT(only(named(select(svg, "path", "curve"), "slot")).attr("d"), Catch::Contains(" A1,1 "));
}

TEST_CASE("curve plot: the grid's coordinates on both axes, named with the units, a vessel's axis in view",
          "[io][pictures][plot]") {
  // A vessel's profile (r, z) in mm with a control point at negative radius,
  // and its section (a shell's wall) as an outline.
  CurvePlot plot;
  plot.units = "mm";
  plot.axis_names = {"r", "z"};
  plot.revolution_axis = true;
  plot.curves.push_back(plot_curve(build_curve(g2_pair()), "profile"));
  plot.curves.front().control_polygons.push_back({{5, 1}, {-1.5, 1.5}, {5, 2}});
  plot.outlines.push_back({"section", {{3, 0}, {7, 3}, {6.5, 3}, {2.6, 0.3}}});
  const auto svg = scan_xml(plot_curves_svg(plot));
  const std::vector<double> box = numbers(only(select(svg, "svg", "model-panel")).attr("viewBox"));
  REQUIRE(box.size() == 4);
  // The axis, r = 0, over the whole panel, and the control point left of it in view.
  const auto axis = select(svg, "g", "axis");
  REQUIRE(axis.size() == 1);
  const XmlElement* axis_line = nullptr;
  for (const XmlElement& e : svg) {
    if (e.name == "line" && e.parent >= 0 && svg[e.parent].has_class("axis")) axis_line = &e;
  }
  REQUIRE(axis_line != nullptr);
  CHECK(number(*axis_line, "x1") == 0.0);
  CHECK(number(*axis_line, "x2") == 0.0);
  CHECK(number(*axis_line, "y1") == Approx(box[1]));
  CHECK(number(*axis_line, "y2") == Approx(box[1] + box[3]));
  CHECK(box[0] < -1.5);
  // Tick labels on both axes: each at its grid line, written as its value, a multiple of the grid's step.
  const double step = number(only(select(svg, "g", "scale-bar")), "data-length");
  int x_ticks = 0, y_ticks = 0;
  for (const XmlElement* t : select(svg, "text", "tick")) {
    const double v = number(*t, "data-value");
    INFO(t->attr("data-axis") << " " << t->text);
    CHECK(std::stod(t->text) == Approx(v).margin(1e-9 * step));
    CHECK(std::abs(v / step - std::round(v / step)) < 1e-9);
    if (t->attr("data-axis") == "x") {
      ++x_ticks;
      CHECK(number(*t, "x") == Approx(v).margin(1e-6));
      CHECK(v >= box[0]);
      CHECK(v <= box[0] + box[2]);
    } else {
      ++y_ticks;
      CHECK(-v >= box[1]);
      CHECK(-v <= box[1] + box[3]);
    }
  }
  CHECK(x_ticks >= 2);
  CHECK(y_ticks >= 2);
  std::vector<std::string> names;
  for (const XmlElement* t : select(svg, "text", "axis-name")) names.push_back(t->text);
  CHECK(names == std::vector<std::string>{"r (mm)", "z (mm)"});
  // The outline, closed, through its points.
  const std::vector<Vec2> outline = path_points(only(select(svg, "path", "outline")).attr("d"));
  REQUIRE(outline.size() == 4);
  CHECK(outline[1].x() == Approx(7.0));
  CHECK(outline[1].y() == Approx(-3.0));
  // Without a vessel: x and y, no axis.
  const auto plain = scan_xml(plot_curves_svg(three_curves()));
  CHECK(select(plain, "g", "axis").empty());
  names.clear();
  for (const XmlElement* t : select(plain, "text", "axis-name")) names.push_back(t->text);
  CHECK(names == std::vector<std::string>{"x (cm)", "y (cm)"});
}

TEST_CASE("curve plot: the plotted curvature is continuous at a G2 joint and jumps at a G1 joint",
          "[io][pictures][plot]") {
  const CurvePlot plot = three_curves();
  const auto svg = scan_xml(plot_curves_svg(plot));
  const auto segments = select(svg, "polyline", "curvature-segment");
  auto of_curve = [&](const std::string& name) {
    std::vector<const XmlElement*> out;
    for (std::size_t i = 0; i < svg.size(); ++i) {
      if (svg[i].has_class("curvature-segment") && svg[svg[i].parent].attr("data-name") == name)
        out.push_back(&svg[i]);
    }
    return out;
  };
  const auto g2 = of_curve("G2 pair");
  const auto g1 = of_curve("G1 pair");
  REQUIRE(g2.size() == 2);
  REQUIRE(g1.size() == 2);
  // In the data: curvature at the end of segment 0 and the start of segment 1.
  const double g2_before = number(*g2[0], "data-k-end"), g2_after = number(*g2[1], "data-k-start");
  CHECK(g2_before == Approx(plot.curves[0].curve.segments()[0].curvature(1.0)).epsilon(1e-9));
  CHECK(std::abs(g2_before - g2_after) <= 1e-7 * std::abs(g2_before));
  const double g1_before = number(*g1[0], "data-k-end"), g1_after = number(*g1[1], "data-k-start");
  CHECK(std::abs(g1_before - g1_after) > 0.1 * std::max(std::abs(g1_before), std::abs(g1_after)));
  // In the picture: the polylines meet at a G2 joint, and leave a visible step at a G1 joint.
  auto end_y = [](const XmlElement& e, bool last) {
    const std::vector<double> p = numbers(e.attr("points"));
    return last ? p[p.size() - 1] : p[1];
  };
  CHECK(std::abs(end_y(*g2[0], true) - end_y(*g2[1], false)) < 0.02);
  CHECK(std::abs(end_y(*g1[0], true) - end_y(*g1[1], false)) > 5.0);
  // The joint markers stand where the segments meet.
  const XmlElement& marker = only(named(select(svg, "g", "joint-marker"), "G2 pair"));
  CHECK(number(marker, "data-s") == Approx(number(*g2[0], "data-s-end")));
  CHECK(number(marker, "data-s") == Approx(number(*g2[1], "data-s-start")));
  CHECK(marker.attr("data-achieved") == "G2");
}

TEST_CASE("curvature profile: arc length by quadrature is exact for lines and a circular arc",
          "[io][pictures][plot]") {
  const CurvatureProfile p = curvature_profile(slot(), 16);
  CHECK(p.length == Approx(8.0 + M_PI).epsilon(1e-12));
  REQUIRE(p.segment_ends.size() == 3);
  CHECK(p.segment_ends[0] == Approx(4.0).epsilon(1e-12));
  CHECK(p.segment_ends[1] == Approx(4.0 + M_PI).epsilon(1e-12));
  for (const CurvatureSample& s : p.segments[1]) {
    CHECK(s.curvature == Approx(1.0).epsilon(1e-12));
    CHECK(s.arc_length == Approx(4.0 + M_PI * s.s).epsilon(1e-12));
  }
  for (const CurvatureSample& s : p.segments[2]) CHECK(s.curvature == 0.0);
}

TEST_CASE("curve plot: a declared continuity the joint lost is marked as lost", "[io][pictures][plot]") {
  CurvePlot plot;
  PlotCurve c = plot_curve(build_curve(g1_pair()), "declared G2");
  c.declared = {Continuity::G2};
  plot.curves.push_back(c);
  const auto svg = scan_xml(plot_curves_svg(plot));
  const XmlElement& joint = only(select(svg, "g", "joint"));
  CHECK(joint.has_class("lost"));
  CHECK(joint.attr("data-achieved") == "G1");
  CHECK(joint.attr("data-declared") == "G2");
  const XmlElement& note = only(select(svg, "text", "joint-declared"));
  CHECK(note.text == "G2 declared");
}

TEST_CASE("curve plot: a faired curve shows its shape before fairing and both energies",
          "[io][pictures][plot]") {
  SECTION("T-Bézier composite, curvature variation") {
    CurveSpec spec = g1_pair();
    spec.fair = FairMode::CurvatureVariation;
    const PlotCurve c = plot_curve(build_curve(spec), "faired");
    REQUIRE(c.before_fairing);
    REQUIRE(c.energy_before);
    REQUIRE(c.energy_after);
    CHECK(*c.energy_after <= *c.energy_before);
    CHECK(c.energy_name == "curvature variation");
    CurvePlot plot;
    plot.curves = {c};
    const auto svg = scan_xml(plot_curves_svg(plot));
    CHECK(named(select(svg, "path", "curve-before"), "faired").size() == 1);
    const XmlElement& legend = only(select(svg, "g", "legend-entry"));
    const auto texts = select(svg, "text");
    bool both = false;
    for (const XmlElement* t : texts) {
      both = both || (t->text.find("before fairing") != std::string::npos &&
                      t->text.find(short_number(*c.energy_before, 6)) != std::string::npos);
    }
    CHECK(legend.attr("data-name") == "faired");
    CHECK(both);
  }
  SECTION("quasi-B-spline, strain (the papers' Example 4)") {
    CurveSpec spec;
    spec.family = CurveFamily::QuasiBSpline;
    spec.bspline_points = {{1.5, 6}, {0, 4.5}, {2, 4}, {3, 3}, {1.5, 2}};
    spec.fair = FairMode::Strain;
    const PlotCurve c = plot_curve(build_curve(spec), "example 4");
    REQUIRE(c.energy_before);
    REQUIRE(c.energy_after);
    CHECK(*c.energy_after < *c.energy_before);
    CHECK(c.energy_name == "strain");
    // One control polygon: the B-spline's p0 .. p4.
    REQUIRE(c.control_polygons.size() == 1);
    CHECK(c.control_polygons[0] == spec.bspline_points);
  }
}

TEST_CASE("curve plot: names and titles are escaped and survive a round trip", "[io][pictures][plot]") {
  CurvePlot plot;
  plot.title = "T <&> \"quoted\" 'single'";
  plot.units = "mm";
  PlotCurve c = plot_curve(build_curve(g2_pair()), "a<b & \"c\" 'd'");
  plot.curves.push_back(c);
  const std::string text = plot_curves_svg(plot);
  const auto svg = scan_xml(text);
  CHECK(only(select(svg, "path", "curve")).attr("data-name") == c.name);
  CHECK(only(select(svg, "text", "title")).text == plot.title);
  CHECK(text.find("a<b") == std::string::npos);
}

TEST_CASE("curve plot: the same plot gives the same SVG every time", "[io][pictures][plot]") {
  CHECK(plot_curves_svg(three_curves()) == plot_curves_svg(three_curves()));
}

TEST_CASE("curve plot: bad options and inconsistent input are refused", "[io][pictures][plot]") {
  CurvePlotOptions o;
  o.width = 10;
  CHECK_THROWS_AS(plot_curves_svg(three_curves(), o), RangeError);
  o = CurvePlotOptions{};
  o.sample_fraction = 0.0;
  CHECK_THROWS_AS(plot_curves_svg(three_curves(), o), RangeError);
  CHECK_THROWS_WITH(plot_curves_svg(CurvePlot{}), Catch::Contains("nothing to draw"));
  CurvePlot plot = three_curves();
  plot.curves[0].declared = {Continuity::G2, Continuity::G2};
  CHECK_THROWS_WITH(plot_curves_svg(plot), Catch::Contains("G2 pair"));
}

TEST_CASE("curve plot: headless Chromium renders the SVG with the red curve visible",
          "[io][pictures][plot][chromium]") {
  REQUIRE(test::chromium_available());  // Debian package chromium (scripts/install-deps.sh --test)
  // Kept under the build folder for people to look at.
  const std::filesystem::path dir = std::filesystem::path(FABMESH_TEST_TMP) / "pictures-samples";
  std::filesystem::create_directories(dir);
  const std::string svg_path = (dir / "three_curves.svg").string();
  const std::string png_path = (dir / "three_curves_chromium.png").string();
  std::filesystem::remove(png_path);
  std::ofstream(svg_path, std::ios::binary) << plot_curves_svg(three_curves());
  const test::ChromiumRun run =
      test::run_chromium("--window-size=1200,600 --screenshot='" + png_path + "'", test::file_url(svg_path));
  INFO(run.err);
  REQUIRE(run.code == 0);
  std::ifstream in(png_path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const test::DecodedPng image = test::decode_png(bytes);
  REQUIRE(image.width == 1200);
  REQUIRE(image.height == 600);
  int red = 0, blue = 0, dark = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const auto c = image.at(x, y);
      red += c[0] > 180 && c[1] < 90 && c[2] < 90;    // the first curve, #d62728
      blue += c[2] > 150 && c[0] < 90 && c[1] < 130;  // control polygons, #1f4fd0
      dark += c[0] < 60 && c[1] < 60 && c[2] < 60;    // text, axes, scale bar
    }
  }
  CHECK(red > 300);
  CHECK(blue > 50);
  CHECK(dark > 500);
  // Left (model) and right (curvature) halves both draw red.
  int red_left = 0, red_right = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const auto c = image.at(x, y);
      if (c[0] > 180 && c[1] < 90 && c[2] < 90) (x < 600 ? red_left : red_right) += 1;
    }
  }
  CHECK(red_left > 100);
  CHECK(red_right > 100);
}

TEST_CASE("curve plot: curvature below rounding draws no comb and plots as zero", "[io][pictures][plot]") {
  // Collinear control points whose coordinates are not binary fractions: the
  // computed curvature is rounding noise of alternating sign near 1e-16.
  CompositeCurve flat(
      {Segment::tbezier({Vec2(0.1, 0.3), Vec2(0.7, 2.1), Vec2(1.3, 3.9), Vec2(2.3, 6.9)}, 0.3, -0.7)}, false);
  double noise = 0.0;
  for (int j = 0; j <= 64; ++j) noise = std::max(noise, std::abs(flat.segments()[0].curvature(j / 64.0)));
  INFO("largest computed curvature " << noise);
  CHECK(noise > 0.0);  // the noise is there to be left out
  CHECK(noise < 1e-10);
  CHECK(drawn_curvature(flat.segments()[0], 0.3) == 0.0);
  CurvePlot plot = one_curve_plot("flat", flat);
  const auto svg = scan_xml(plot_curves_svg(plot));
  for (std::size_t i = 0; i < svg.size(); ++i) {
    if (svg[i].has_class("comb-teeth")) CHECK(svg[i].attr("d").empty());
    if (svg[i].has_class("curvature-segment")) {
      CHECK(number(svg[i], "data-k-start") == 0.0);
      CHECK(number(svg[i], "data-k-end") == 0.0);
    }
  }
  // A real bend keeps its comb beside the flat curve.
  plot.curves.push_back(plot_curve(build_curve(g2_pair()), "G2 pair"));
  const auto both = scan_xml(plot_curves_svg(plot));
  int drawn = 0;
  for (std::size_t i = 0; i < both.size(); ++i) {
    if (both[i].has_class("comb-teeth") && !both[i].attr("d").empty()) ++drawn;
  }
  CHECK(drawn == 1);
}

TEST_CASE("curve plot: a tight corner arc does not set the comb's scale", "[io][pictures][plot]") {
  // A gentle T-Bezier bulge (curvature well under 1) and a corner arc of radius 0.05 (curvature 20).
  EllipseArcParams corner;
  corner.center = {4, 0.95};
  corner.a = corner.b = 0.05;
  corner.from_deg = -90;
  corner.to_deg = 0;
  const CompositeCurve top({Segment::tbezier({Vec2(0, 0), Vec2(1, 1), Vec2(3, 1), Vec2(4, 0)}, 0, 0),
                            Segment::line({4, 0}, {4, 0.9}), Segment::ellipse_arc(corner)},
                           false);
  const auto teeth_of = [](const CompositeCurve& curve) {
    const auto svg = scan_xml(plot_curves_svg(one_curve_plot("top", curve)));
    return select(svg, "path", "comb-teeth").at(0)->attr("d");
  };
  // One tooth per comb sample of the bulge: the arc, 400 times more curved than the
  // comb's scale allows, has none (its constant curvature is on the right panel).
  const std::string d = teeth_of(top);
  const auto count = [](const std::string& s) { return std::count(s.begin(), s.end(), 'M'); };
  CHECK(count(d) == 33);
  // Alone, an arc sets the scale itself and has its comb.
  const CompositeCurve arc_only({Segment::ellipse_arc(corner)}, false);
  CHECK(count(teeth_of(arc_only)) == 33);
}
