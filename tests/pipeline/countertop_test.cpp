#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "geometry/core/errors.h"
#include "geometry/core/soup.h"
#include "geometry/fairing/build_curve.h"
#include "geometry/mesh/weld.h"
#include "geometry/validation/validate.h"
#include "io/design/read_design.h"
#include "io/file.h"
#include "io/mesh/draco.h"
#include "io/mesh/stl.h"
#include "pipeline/cli/commands.h"
#include "pipeline/job.h"
#include "pipeline/output_table.h"
#include "tests/geometry/section/region_shapes.h"
#include "tests/io/cutting/dxf_read_back.h"
#include "tests/io/cutting/interpret.h"
#include "tests/io/design/nurbs_dxf.h"
#include "tests/pipeline/cli_harness.h"

using namespace fabmesh;
using namespace fabmesh::testing;
namespace fs = std::filesystem;

namespace {

// Exact area and perimeter of a countertop design's region, from its exact curves.
std::pair<double, double> exact_region(const CountertopDesign& c) {
  const CompositeCurve outline = build_curve(c.outline).curve;
  double area = std::abs(test::exact_area(outline)), perimeter = test::exact_length(outline);
  for (const auto& h : c.holes) {
    const CompositeCurve hole = build_curve(h.curve).curve;
    area -= std::abs(test::exact_area(hole));
    perimeter += test::exact_length(hole);
  }
  return {area, perimeter};
}

const char* kSmall =
    "name: small\nkind: countertop\ntolerance: 0.5\nthickness: 20\n"
    "outline:\n  family: tbezier\n  closed: true\n  segments:\n"
    "    - line: {from: [0, 0], to: [800, 0]}\n"
    "    - line: {to: [800, 400]}\n"
    "    - line: {to: [0, 400]}\n"
    "    - line: {to: [0, 0]}\n"
    "holes:\n"
    "  - ellipse: {center: [200, 200], a: 120, b: 80, rotation_deg: 20}\n"
    "  - rounded_rect: {center: [550, 200], size: [300, 200], radius: 30}\n";

// The drawing a run wrote as DIR/first/DXF, read back as a countertop of its
// own (outline on layer OUTLINE, cut-outs on HOLES) and run: its report item,
// checked to hold the first run's volume and region area within 1e-9 (of the
// volume, of size^2).
nlohmann::json run_written_drawing(const fs::path& dir, const std::string& dxf, const nlohmann::json& first,
                                   double size) {
  write_text(dir / "first" / "back.yaml",
             "name: back\nkind: countertop\nunits: mm\ntolerance: 0.05\nthickness: 30\n"
             "outline: {dxf: " +
                 dxf +
                 ", layer: OUTLINE}\n"
                 "holes: [{dxf: " +
                 dxf + ", layer: HOLES}]\noutputs: [stl]\n");
  std::string out;
  REQUIRE(
      run_cli_json({"run", (dir / "first" / "back.yaml").string(), "-o", (dir / "back").string(), "--json"},
                   &out) == 0);
  const auto back = only_item(out);
  CHECK(std::abs(back["volume"].get<double>() - first["volume"].get<double>()) <=
        1e-9 * first["volume"].get<double>());
  CHECK(std::abs(back["build"]["region_area"].get<double>() - first["build"]["region_area"].get<double>()) <=
        1e-9 * size * size);
  return back;
}

}  // namespace

TEST_CASE("countertop examples: valid slabs, genus = holes, volume = exact area x thickness",
          "[pipeline][countertop]") {
  const fs::path dir = fresh_dir("countertop_examples");
  for (const char* name : {"countertop_g1.yaml", "countertop_g2.yaml", "countertop_g1_fair_cv.yaml",
                           "countertop_g2_fair_cv.yaml", "countertop_symmetric_ellipse.yaml",
                           "countertop_asymmetric_line.yaml", "countertop_dxf_template.yaml"}) {
    INFO(name);
    Design design = read_design(example(name));
    design.common.outputs = {{"stl", "test", 0, 0}, {"dxf", "test", 0, 0}};
    const auto& c = std::get<CountertopDesign>(design.body);
    const Result r = run_job(design, into(dir));
    CHECK(verdict(r).valid());
    REQUIRE(verdict(r).genus);
    CHECK(*verdict(r).genus == static_cast<long>(c.holes.size()));
    CHECK(r.max_deviation <= design.common.tolerance);
    const auto [area, perimeter] = exact_region(c);
    CHECK(std::abs(verdict(r).volume - area * c.thickness) <= r.max_deviation * perimeter * c.thickness);
    // The STL read back passes the full validation, 3D self-intersection test included.
    const ValidationReport full = validate(weld(parse_stl(read_file(written_paths(r)[0]), "stl")).soup);
    CHECK(full.valid());
    CHECK(full.self_intersection == IntersectionCheck::Tested);
    CHECK(full.genus == verdict(r).genus);
    CHECK(full.triangles == verdict(r).triangles);
  }
}

TEST_CASE("countertop run: default outputs are STL, Draco, DXF and SVG, and the DXF has exact arcs",
          "[pipeline][countertop]") {
  const fs::path dir = fresh_dir("countertop_run");
  std::string out;
  REQUIRE(run_cli_json({"run", example("countertop_symmetric_ellipse.yaml"), "-o", dir.string(), "--json"},
                       &out) == 0);
  const auto j = nlohmann::json::parse(out).at(0);
  CHECK(j["kind"] == "countertop");
  REQUIRE(j["outputs"].size() == 4);
  CHECK(j["watertight"] == true);
  CHECK(j["self_intersecting"] == false);
  CHECK(j["genus"] == 2);
  CHECK(j["build"]["holes"] == 2);
  CHECK(j.contains("self_intersection_proof"));
  // The slab's connectivity is proven by its construction (tests/geometry/mesh/slab_test.cpp
  // checks the proof against the analysis), and the STL as stored (float32) by the
  // extrusion's exact re-check.
  CHECK(j["topology"] == "proven by construction");
  CHECK_THAT(j["topology_proof"].get<std::string>(),
             Catch::Contains("extrusion of a triangulated region with 2 hole(s)"));
  CHECK(j["files"][0]["format"] == "stl");
  CHECK(j["files"][0]["valid_as_written"] == true);
  for (const char* stage : {"curve", "region", "build", "validate", "encode_stl", "encode_dxf", "write"}) {
    CHECK(j["timings_ms"].contains(stage));
  }
  for (const char* ext : {"stl", "drc", "dxf", "svg"})
    CHECK(fs::exists(dir / (std::string("countertop_symmetric_ellipse.") + ext)));
  CHECK(validate(parse_draco(read_file((dir / "countertop_symmetric_ellipse.drc").string()), "drc")).valid());
  const auto entities = parse_dxf(read_file((dir / "countertop_symmetric_ellipse.dxf").string()), "dxf");
  std::map<std::string, int> types;
  for (const auto& e : entities) ++types[e.type + "@" + e.layer];
  CHECK(types["ELLIPSE@OUTLINE"] == 1);  // the bar bump
  CHECK(types["LINE@OUTLINE"] == 5);
  CHECK(types["POLYLINE@OUTLINE"] == 2);  // the T-Bezier corners
  CHECK(types["ELLIPSE@HOLES"] == 1);     // the oval sink, whole
  CHECK(types["ARC@HOLES"] == 4);         // the cooktop's corners
  const std::string svg = read_file((dir / "countertop_symmetric_ellipse.svg").string());
  CHECK(std::count(svg.begin(), svg.end(), '\n') >= 3);
  CHECK(svg.find("<path id=\"outline\"") != std::string::npos);
  CHECK(svg.find("<path id=\"hole1\"") != std::string::npos);
}

TEST_CASE("countertop: max_edge is honoured on top and bottom, the slab stays valid",
          "[pipeline][countertop]") {
  const fs::path dir = fresh_dir("countertop_max_edge");
  Design design = parse_design(std::string(kSmall) + "max_edge: 40\noutputs: [stl]\n", "small.yaml");
  const Result r = run_job(design, into(dir));
  REQUIRE(verdict(r).valid());
  CHECK(r.facts.number("steiner_points") > 0);
  const TriangleSoup soup = weld(parse_stl(read_file(written_paths(r)[0]), "stl")).soup;
  CHECK(validate(soup).valid());
  double longest = 0.0;
  for (const auto& t : soup.triangles) {
    for (int i = 0; i < 3; ++i) {
      const Vec3 a = soup.vertices[t[i]], b = soup.vertices[t[(i + 1) % 3]];
      if (a.z() == b.z()) longest = std::max(longest, (a - b).norm());
    }
  }
  CHECK(longest <= 40.0 * (1 + 1e-6));  // float32 STL coordinates
  CHECK(longest > 20.0);
}

TEST_CASE("countertop bad input: exit 2, a message naming the problem, no file",
          "[pipeline][countertop][errors]") {
  const fs::path dir = fresh_dir("countertop_bad");
  const std::string small = kSmall;
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string t = small;
    REQUIRE(t.find(from) != std::string::npos);
    return t.replace(t.find(from), from.size(), to);
  };
  const std::vector<std::pair<std::string, std::string>> cases{
      {replaced("    - line: {to: [0, 0]}\n", "    - line: {to: [0, 10]}\n"), "does not close"},
      {replaced("    - line: {to: [800, 400]}\n    - line: {to: [0, 400]}\n",
                "    - line: {to: [0, 400]}\n    - line: {to: [800, 400]}\n"),
       "outline crosses itself"},
      {replaced("center: [200, 200], a: 120", "center: [1200, 200], a: 120"),
       "holes[0] (ellipse) is not inside the outline"},
      {replaced("center: [550, 200], size", "center: [300, 200], size"),
       "holes[1] (rounded_rect) overlaps holes[0]"},
      {replaced("thickness: 20", "thickness: 0"), "thickness = 0 must be > 0"},
      {replaced("thickness: 20", "thickness: -5"), "thickness = -5 must be > 0"},
      {replaced("closed: true", "closed: false"), "closed"},
  };
  int i = 0;
  for (const auto& [text, expected] : cases) {
    INFO(expected);
    const fs::path design = dir / fmt::format("bad{}.yaml", i++);
    std::ofstream(design) << text;
    const fs::path out_dir = dir / "out";
    std::string out;
    CHECK(run_cli({"run", design.string(), "-o", out_dir.string()}, &out) == 2);
    CHECK_THAT(out, Catch::Contains(expected));
    CHECK((!fs::exists(out_dir) || fs::is_empty(out_dir)));
  }
}

TEST_CASE(
    "countertop design: outputs apply to the kinds and contents they are made for, holes read as exact "
    "closed curves",
    "[pipeline][countertop][design]") {
  const std::string vessel =
      "name: v\nkind: vessel\nprofile: {family: tbezier, segments: [{line: {from: [1, 0], to: [1, 1]}}]}\n"
      "body: {mode: solid}\n";
  CHECK_THROWS_WITH(
      resolve_outputs(parse_design(vessel + "outputs: [stl, nc]\n", "v.yaml")),
      Catch::Contains("v.yaml:5:16: outputs[1]: nc") && Catch::Contains("made for countertop designs"));
  CHECK_THROWS_WITH(resolve_outputs(parse_design(vessel + "outputs: [mould_stl]\n", "v.yaml")),
                    Catch::Contains("outputs[0]: mould_stl needs a `mould:` section"));
  CHECK_THROWS_WITH(resolve_outputs(parse_design(std::string(kSmall) + "outputs: [stl, nc]\n", "small.yaml")),
                    Catch::Contains("outputs[1]: nc needs a `cnc:` section"));
  const Design d = parse_design(kSmall, "small.yaml");
  std::vector<std::string> defaults;
  for (const OutputFormat* f : resolve_outputs(d)) defaults.emplace_back(f->name);
  CHECK(defaults == std::vector<std::string>{"stl", "drc", "dxf", "svg"});
  const auto& c = std::get<CountertopDesign>(d.body);
  REQUIRE(c.holes.size() == 2);
  const CompositeCurve ellipse = build_curve(c.holes[0].curve).curve;
  CHECK(ellipse.size() == 1);
  CHECK(std::abs(test::exact_area(ellipse)) == Approx(M_PI * 120 * 80).epsilon(1e-12));
  const CompositeCurve rect = build_curve(c.holes[1].curve).curve;
  CHECK(rect.size() == 8);
  for (const JointReport& j : rect.joints()) CHECK(j.achieved >= Continuity::G1);
  CHECK(std::abs(test::exact_area(rect)) == Approx(300 * 200 - (4 - M_PI) * 30 * 30).epsilon(1e-12));
}

TEST_CASE(
    "countertop run: a crossing outline or a hole over the edge is bad input at its file line and column",
    "[pipeline][countertop][errors]") {
  const fs::path dir = fresh_dir("countertop_located");
  const std::string design = (dir / "cross.yaml").string();
  write_file_atomically(design,
                        "name: cross\nkind: countertop\nunits: mm\ntolerance: 0.05\nthickness: 30\n"
                        "outline:\n  family: tbezier\n  closed: true\n  segments:\n"
                        "    - polyline: [[0, 0], [100, 100], [100, 0], [0, 100], [0, 0]]\n");
  std::string out;
  CHECK(run_cli({"run", design, "-o", (dir / "out").string()}, &out) == 2);
  CHECK_THAT(out, Catch::Contains(design + ":7:3: outline: outline crosses itself near (50, 50)"));
  CHECK_FALSE(fs::exists(dir / "out"));
  CHECK(run_cli({"run", example("countertop_g1.yaml"), "-o", (dir / "out").string(), "-D",
                 "holes[0].rounded_rect.center=[100,340]"},
                &out) == 2);
  CHECK_THAT(out,
             Catch::Contains("countertop_g1.yaml:41:5: holes[0]: holes[0] (rounded_rect) crosses or touches "
                             "the outline"));
}

TEST_CASE("countertop from a DXF template: the DXF fabmesh writes reads back into the same countertop",
          "[pipeline][countertop][dxf]") {
  const fs::path dir = fresh_dir("countertop_dxf_round_trip");
  std::string out;
  REQUIRE(
      run_cli_json({"run", example("countertop_dxf_template.yaml"), "-o", (dir / "first").string(), "--json"},
                   &out) == 0);
  const auto first = only_item(out);
  CHECK(first["genus"] == 3);
  CHECK(first["notes"].dump().find("$INSUNITS 4 (mm)") != std::string::npos);
  // The written outline (lines, arcs and ellipses on layers OUTLINE and HOLES) as a design of its own.
  const double size = 2400.0;
  run_written_drawing(dir, "countertop_dxf_template.dxf", first, size);
  // And the exact region of the design read back equals the template's, term by term.
  const auto [area, perimeter] =
      exact_region(std::get<CountertopDesign>(read_design((dir / "first" / "back.yaml").string()).body));
  const auto [area0, perimeter0] =
      exact_region(std::get<CountertopDesign>(read_design(example("countertop_dxf_template.yaml")).body));
  CHECK(std::abs(area - area0) <= 1e-9 * size * size);
  CHECK(std::abs(perimeter - perimeter0) <= 1e-9 * size);
}

TEST_CASE("countertop from a DXF template: a circle saved as a NURBS is the exact circle",
          "[pipeline][countertop][dxf][rational]") {
  const fs::path dir = fresh_dir("countertop_dxf_nurbs");
  const double r = 250.0;
  const Vec2 c(400, 300);
  write_text(dir / "round.dxf", test::dxf_drawing(test::dxf_nurbs_ellipse("2A", "OUTLINE", c, r, r)));
  write_text(dir / "round.yaml",
             "name: round\nkind: countertop\nunits: mm\ntolerance: 0.05\nthickness: 30\n"
             "outline: {dxf: round.dxf, layer: OUTLINE}\noutputs: [stl]\n");
  Design design = read_design((dir / "round.yaml").string());
  design.common.outputs = {{"stl", "test", 0, 0}};
  const auto& top = std::get<CountertopDesign>(design.body);
  const CompositeCurve outline = build_curve(top.outline).curve;
  REQUIRE(outline.size() == 4);
  double worst = 0.0;
  for (const Segment& seg : outline.segments()) {
    CHECK(seg.kind() == SegmentKind::RationalBezier);
    for (int i = 0; i <= 1000; ++i) worst = std::max(worst, std::abs((seg.point(i / 1000.0) - c).norm() - r));
  }
  INFO("largest radius error " << worst);
  CHECK(worst <= 1e-9 * r);
  const auto [area, perimeter] = exact_region(top);
  CHECK(area == Approx(M_PI * r * r).epsilon(1e-9));
  CHECK(perimeter == Approx(2 * M_PI * r).epsilon(1e-9));
  // The slab: valid, its volume the exact area times the thickness within the sampling's deviation.
  const Result rep = run_job(design, into(dir));
  CHECK(verdict(rep).valid());
  CHECK(rep.max_deviation <= design.common.tolerance);
  CHECK(std::abs(verdict(rep).volume - area * top.thickness) <=
        rep.max_deviation * perimeter * top.thickness);
}

TEST_CASE(
    "countertop from a DXF template with NURBS: the DXF fabmesh writes reads back into the same countertop",
    "[pipeline][countertop][dxf][rational]") {
  const fs::path dir = fresh_dir("countertop_dxf_nurbs_round_trip");
  // An elliptic outline and a round hole saved as NURBS, a polynomial drop, and an egg-shaped
  // hole: a closed rational quadratic SPLINE with weights 2.5 and 0.4, no conic.
  const std::vector<Vec2> egg{{450, 400}, {650, 200}, {850, 400}, {650, 650}, {450, 400}};
  const std::vector<Vec2> drop{{200, 400}, {260, 320}, {330, 400}, {260, 480}, {200, 400}};
  write_text(dir / "nurbs.dxf",
             test::dxf_drawing(test::dxf_nurbs_ellipse("2A", "OUTLINE", Vec2(700, 400), 650, 380) +
                               test::dxf_nurbs("3A", "HOLES", egg, {1.0, 2.5, 1.0, 0.4, 1.0}) +
                               test::dxf_nurbs_ellipse("4A", "HOLES", Vec2(1100, 400), 60, 60) +
                               // a polynomial spline (equal weights), as CAD's fit-point splines are
                               test::dxf_nurbs("5A", "HOLES", drop, {1.0, 1.0, 1.0, 1.0, 1.0})));
  write_text(dir / "nurbs.yaml",
             "name: nurbs\nkind: countertop\nunits: mm\ntolerance: 0.05\nthickness: 30\n"
             "outline: {dxf: nurbs.dxf, layer: OUTLINE}\n"
             "holes: [{dxf: nurbs.dxf, layer: HOLES}]\noutputs: [stl, dxf]\n");
  std::string out;
  REQUIRE(run_cli_json({"run", (dir / "nurbs.yaml").string(), "-o", (dir / "first").string(), "--json"},
                       &out) == 0);
  const auto first = only_item(out);
  CHECK(first["genus"] == 3);
  // Every span written as the SPLINE it is: nothing sampled.
  const std::string written = read_file((dir / "first" / "nurbs.dxf").string());
  CHECK(written.find("LWPOLYLINE") == std::string::npos);
  std::map<std::string, int> types;
  for (const auto& e : parse_dxf(written, "nurbs.dxf")) ++types[e.type + "@" + e.layer];
  CHECK(types["SPLINE@OUTLINE"] == 4);
  CHECK(types["SPLINE@HOLES"] == 2 + 4 + 2);
  CHECK(types.size() == 2);
  // The written drawing as a design of its own.
  const double size = 1300.0;
  CHECK(run_written_drawing(dir, "nurbs.dxf", first, size)["genus"] == 3);
  // The design read back is made of the same rational spans, and its exact region is the template's.
  const Design read_back = read_design((dir / "first" / "back.yaml").string());
  const auto& top = std::get<CountertopDesign>(read_back.body);
  const CompositeCurve outline = build_curve(top.outline).curve;
  for (const Segment& seg : outline.segments()) CHECK(seg.kind() == SegmentKind::RationalBezier);
  const auto [area, perimeter] = exact_region(top);
  const auto [area0, perimeter0] =
      exact_region(std::get<CountertopDesign>(read_design((dir / "nurbs.yaml").string()).body));
  CHECK(std::abs(area - area0) <= 1e-9 * size * size);
  CHECK(std::abs(perimeter - perimeter0) <= 1e-9 * size);
  CHECK(area0 > 0.5 * M_PI * 650 * 380);  // the holes are small beside the outline
}

TEST_CASE("countertop from a DXF template: bad drawings exit 2 at the design's key, nothing written",
          "[pipeline][countertop][dxf][errors]") {
  const fs::path dir = fresh_dir("countertop_dxf_bad");
  fs::copy_file(example("kitchen_template.dxf"), dir / "kitchen_template.dxf");
  write_text(
      dir / "open.dxf",
      "0\nSECTION\n2\nENTITIES\n0\nLINE\n5\n2F\n8\nOUTLINE\n10\n0\n20\n0\n30\n0\n11\n100\n21\n0\n31\n0\n"
      "0\nLINE\n5\n30\n8\nOUTLINE\n10\n100\n20\n0\n30\n0\n11\n100\n21\n50\n31\n0\n0\nENDSEC\n0\nEOF\n");
  write_text(dir / "empty.dxf", "");
  write_text(dir / "weightless.dxf",
             test::dxf_drawing(test::dxf_nurbs_ellipse("3A", "OUTLINE", Vec2(0, 0), 100.0, 100.0, 0.0)));
  const std::string head = "name: t\nkind: countertop\nunits: mm\ntolerance: 0.05\nthickness: 30\n";
  const std::vector<std::pair<std::string, std::string>> cases{
      {head + "outline: {dxf: open.dxf, layer: OUTLINE}\n",
       "outline.dxf: " + (dir / "open.dxf").string() +
           " layer OUTLINE: open chain: LINE #2F's start at (0, 0)"},
      {head + "outline: {dxf: empty.dxf}\n", "the file is empty, not a DXF drawing"},
      {head + "outline: {dxf: weightless.dxf, layer: OUTLINE}\n",
       "outline.dxf: " + (dir / "weightless.dxf").string() +
           " layer OUTLINE: SPLINE #3A: control point 2 has weight 0: a NURBS weight must be finite and > 0"},
      {head + "outline: {dxf: missing.dxf}\n", "missing.dxf"},
      {head + "outline: {dxf: kitchen_template.dxf, layer: HOLES}\n",
       "outline.dxf: 3 closed loops found on the layer; outline is one loop"},
      {head + "outline: {dxf: kitchen_template.dxf, layer: OUTLINE, colour: red}\n", "colour"},
      {head + "outline: {dxf: kitchen_template.dxf, layer: OUTLINE, max_gap: -1}\n",
       "max_gap = -1 must be >= 0"},
      {head +
           "outline: {dxf: kitchen_template.dxf, layer: OUTLINE}\nholes: [{ellipse: {center: [1, 1], a: 1, "
           "b: 1}, layer: HOLES}]\n",
       "holes[0]: a hole is a map with one key: ellipse, rounded_rect, outline or drill (or dxf with its "
       "layer)"},
  };
  int i = 0;
  for (const auto& [text, expected] : cases) {
    INFO(text);
    const fs::path design = dir / fmt::format("bad{}.yaml", i++);
    write_text(design, text);
    const fs::path out_dir = dir / "out";
    std::string out;
    CHECK(run_cli({"run", design.string(), "-o", out_dir.string()}, &out) == 2);
    CHECK_THAT(out, Catch::Contains(expected));
    CHECK_THAT(out, Catch::Contains(design.string() + ":"));
    CHECK((!fs::exists(out_dir) || fs::is_empty(out_dir)));
  }
}

TEST_CASE("countertop cnc: tabs on cut-outs and a ramp entry from the design, bad ones located",
          "[pipeline][countertop][cnc]") {
  const fs::path dir = fresh_dir("countertop_hole_tabs");
  const std::string sink =
      "  - rounded_rect: {center: [\"=sink_x\", \"=sink_y\"], size: [560, 400], radius: 40}          # sink";
  const std::string design =
      edited_example(dir, "countertop_cnc.yaml", sink,
                     "  - rounded_rect: {center: [\"=sink_x\", \"=sink_y\"], size: [560, 400], radius: 40}\n"
                     "    tabs: {count: 2, height: 5}",
                     "tabbed.yaml");
  {
    std::string text = read_file(design);
    text += "  entry: ramp\n  ramp_angle: 4\n  finish: 0.5\n";
    write_text(design, text);
  }
  std::string json;
  REQUIRE(run_cli_json({"run", design, "-o", (dir / "out").string() + "/", "--json"}, &json) == 0);
  const auto item = nlohmann::json::parse(json)[0];
  CHECK(item["build"]["cnc"]["hole_tabs"] == 2);
  CHECK(item["build"]["cnc"]["tabs"] == 4);
  CHECK(item["build"]["cnc"]["entry"] == "ramp");
  CHECK(item["build"]["cnc"]["finish"] == 0.5);
  CHECK_FALSE(item.contains("warnings"));
  const std::string nc = read_file((dir / "out" / "countertop_cnc.nc").string());
  CHECK_THAT(nc, Catch::Contains("(holes[0] [rounded_rect]: tabs 2, 5 high)") &&
                     Catch::Contains("(entry: zig-zag ramp at 4 degrees along the path)") &&
                     Catch::Contains("(ramp)") &&
                     Catch::Contains("(outline: finishing pass at z -30, the last 0.5 of stock)"));

  // A helix entry and the fitted arcs' count in the report and the program's header.
  {
    const std::string helix = edited_example(dir, "countertop_cnc.yaml", "  lead_in: 8",
                                             "  lead_in: 8\n  entry: helix\n  helix_radius: 2", "helix.yaml");
    std::string helix_json;
    REQUIRE(run_cli_json({"run", helix, "-o", (dir / "helix").string() + "/", "--json"}, &helix_json) == 0);
    const auto cnc = nlohmann::json::parse(helix_json)[0]["build"]["cnc"];
    CHECK(cnc["entry"] == "helix");
    CHECK(cnc["arc_fit"]["enabled"] == true);
    CHECK(cnc["arc_fit"]["replaced"].get<int>() > cnc["arc_fit"]["arcs"].get<int>());
    CHECK(cnc["arc_fit"]["deviation"].get<double>() <= cnc["deviation"].get<double>());
    const std::string helix_nc = read_file((dir / "helix" / "countertop_cnc.nc").string());
    CHECK_THAT(helix_nc, Catch::Contains("(outline: entry: helix of radius 2 about ") &&
                             Catch::Contains("(helix)") && Catch::Contains("(arc fitting: "));
  }

  // More tabs than the cooktop's path has room for: placed where they fit, a warning, exit 0.
  const std::string crowded =
      edited_example(dir, "countertop_cnc.yaml", "radius: 10}   # cooktop",
                     "radius: 10}\n    tabs: {count: 40, width: 30, min_radius: 1000}", "crowded.yaml");
  const CliResult r = run_fabmesh({"run", crowded, "-o", (dir / "crowded").string() + "/"});
  CHECK(r.code == 0);
  CHECK_THAT(r.err,
             Catch::Contains("warning: holes[1] (rounded_rect): ") && Catch::Contains(" of 40 tabs placed"));

  // Located bad input: nothing written.
  struct Bad {
    std::string find, replace, key;
  };
  const std::vector<Bad> bad{
      {sink,
       "  - rounded_rect: {center: [650, 340], size: [560, 400], radius: 40}\n    tabs: {count: 2, height: "
       "30}",
       "holes[0].tabs.height"},
      {sink, "  - rounded_rect: {center: [650, 340], size: [560, 400], radius: 40}\n    tabs: {width: 5}",
       "holes[0].tabs"},
      {sink,
       "  - rounded_rect: {center: [650, 340], size: [560, 400], radius: 40}\n    tabs: {count: 2, wide: 5}",
       "holes[0].tabs.wide"},
      {"  lead_in: 8", "  lead_in: 8\n  ramp_angle: 4", "cnc.ramp_angle"},
      {"  lead_in: 8", "  lead_in: 8\n  entry: spiral", "cnc.entry"},
      {"  lead_in: 8", "  lead_in: 8\n  helix_radius: 2", "cnc.helix_radius"},
      {"  lead_in: 8", "  lead_in: 8\n  entry: helix\n  helix_radius: 7", "cnc.helix_radius"},
      {"  lead_in: 8", "  lead_in: 8\n  arc_fit: maybe", "cnc.arc_fit"},
      {"  lead_in: 8", "  lead_in: 8\n  entry: ramp\n  ramp_angle: 60", "cnc.ramp_angle"},
      {"  lead_in: 8", "  lead_in: 8\n  finish: 6", "cnc.finish"},
  };
  for (std::size_t i = 0; i < bad.size(); ++i) {
    INFO(bad[i].replace);
    const std::string file =
        edited_example(dir, "countertop_cnc.yaml", bad[i].find, bad[i].replace, fmt::format("bad{}.yaml", i));
    std::string out;
    CHECK(run_cli({"run", file, "-o", (dir / fmt::format("bad{}", i)).string() + "/"}, &out) == 2);
    CHECK(names_place(out, file, bad[i].key));
    CHECK_FALSE(fs::exists(dir / fmt::format("bad{}", i)));
  }
  // Tabs on a hole of a design without a cnc section.
  const std::string plain = edited_example(dir, "countertop_g1.yaml", "radius: 40}",
                                           "radius: 40}\n    tabs: {count: 2}", "plain.yaml");
  std::string out;
  CHECK(run_cli({"run", plain, "-o", (dir / "plain").string() + "/"}, &out) == 2);
  CHECK_THAT(out, Catch::Contains("has no cnc section"));
}

namespace {

// countertop_cnc.yaml with tap holes added after its cooktop (`holes`, hole
// entries), written to dir/name.
std::string with_tap_holes(const fs::path& dir, const std::string& name, const std::string& holes) {
  return edited_example(dir, "countertop_cnc.yaml", "radius: 10}   # cooktop\n",
                        "radius: 10}   # cooktop\n" + holes, name);
}

}  // namespace

TEST_CASE("countertop tap holes: the slab keeps them as exact round cut-outs, closed, genus = holes",
          "[pipeline][countertop][drill]") {
  const fs::path dir = fresh_dir("countertop_tap_holes");
  const std::string path = with_tap_holes(dir, "taps.yaml",
                                          "  - drill: {center: [650, 595], diameter: 35}\n"
                                          "  - drill: {center: [1150, 595], diameter: 28}\n");
  Design design = read_design(path);
  design.common.outputs = {{"stl", "test", 0, 0}, {"dxf", "test", 0, 0}};
  const auto& c = std::get<CountertopDesign>(design.body);
  const Result r = run_job(design, into(dir / "out"));
  CHECK(verdict(r).valid());
  REQUIRE(verdict(r).genus);
  CHECK(*verdict(r).genus == 4);  // the sink, the cooktop and the two tap holes
  // The exact area: each tap hole takes pi r^2 out of the top.
  for (const double d : {35.0, 28.0}) {
    const auto hole = std::find_if(c.holes.begin(), c.holes.end(), [&](const CountertopHole& h) {
      return h.drill && h.drill->diameter == d;
    });
    REQUIRE(hole != c.holes.end());
    CHECK(std::abs(test::exact_area(build_curve(hole->curve).curve)) ==
          Approx(M_PI * d * d / 4).epsilon(1e-12));
  }
  const auto [area, perimeter] = exact_region(c);
  Design plain = read_design(example("countertop_cnc.yaml"));
  const auto [area0, perimeter0] = exact_region(std::get<CountertopDesign>(plain.body));
  CHECK(area == Approx(area0 - M_PI * (35.0 * 35.0 + 28.0 * 28.0) / 4).epsilon(1e-12));
  CHECK(perimeter == Approx(perimeter0 + M_PI * (35.0 + 28.0)).epsilon(1e-12));
  CHECK(std::abs(verdict(r).volume - area * c.thickness) <= r.max_deviation * perimeter * c.thickness);
  CHECK(std::abs(r.facts.number("region_area") - area) <= r.max_deviation * perimeter);
  // The STL read back passes the full validation, its genus the same.
  const ValidationReport full = validate(weld(parse_stl(read_file(written_paths(r)[0]), "stl")).soup);
  CHECK(full.valid());
  CHECK(full.genus == verdict(r).genus);
  // The drawing has each tap hole as an exact circle (a point on it: the centre + (r, 0)).
  std::vector<Vec2> circles;
  for (const auto& e : parse_dxf(read_file((dir / "out" / "countertop_cnc.dxf").string()), "dxf")) {
    if (e.type == "CIRCLE" && e.layer == "HOLES") circles.push_back(e.points[0]);
  }
  CHECK(circles == std::vector<Vec2>{Vec2(667.5, 595), Vec2(1164, 595)});
}

TEST_CASE("countertop tap holes: bad ones exit 2 at the hole's key, nothing written",
          "[pipeline][countertop][drill][errors]") {
  const fs::path dir = fresh_dir("countertop_bad_taps");
  struct Bad {
    std::string holes, cnc, key, says;
  };
  // The sink spans x 370..930, y 140..540; the back edge is at y = 650.
  const std::vector<Bad> bad{
      // Too close to the sink for the web the router leaves (12 mm: one tool diameter).
      {"  - drill: {center: [650, 565], diameter: 35}\n", "", "holes[2] (drill)",
       "the web between it and holes[0] (rounded_rect) is at most 7.5"},
      // Into the sink; out of the top.
      {"  - drill: {center: [650, 550], diameter: 35}\n", "", "holes[2]", ""},
      {"  - drill: {center: [650, 640], diameter: 35}\n", "", "holes[2]", ""},
      // Located reading errors, from the command line too.
      {"  - drill: {center: [650, 595], diameter: -35}\n", "", "holes[2].drill.diameter", "must be > 0"},
      {"  - drill: {center: [650, 595], diameter: 30}\n",
       "  tools: [{number: 1, type: end_mill, diameter: 12}, {number: 2, type: drill, diameter: 35}]\n",
       "holes[2].drill.diameter", "no drill of that diameter"},
      {"  - drill: {center: [650, 595], diameter: 35}\n",
       "  tools: [{number: 2, type: drill, diameter: 35}, {number: 2, type: end_mill, diameter: 12}]\n",
       "cnc.tools[1].number", "has that number already"},
      {"  - drill: {center: [650, 595], diameter: 35}\n", "  drill: {peck: -2}\n", "cnc.drill.peck",
       "must be >= 0"},
  };
  for (std::size_t i = 0; i < bad.size(); ++i) {
    INFO(bad[i].holes << bad[i].cnc);
    std::string file = with_tap_holes(dir, fmt::format("bad{}.yaml", i), bad[i].holes);
    write_text(file, read_file(file) + bad[i].cnc);
    std::string out;
    CHECK(run_cli({"run", file, "-o", (dir / fmt::format("bad{}", i)).string() + "/"}, &out) == 2);
    INFO(out);
    CHECK(names_place(out, file, bad[i].key));
    CHECK_THAT(out, Catch::Contains(bad[i].says));
    CHECK_FALSE(fs::exists(dir / fmt::format("bad{}", i)));
  }
}

TEST_CASE("countertop: the island's edge profile, meshed, and profiled by the router after the routing",
          "[pipeline][countertop]") {
  const fs::path dir = fresh_dir("countertop_island");
  const Design design = read_design(example("countertop_island.yaml"));
  const Result r = run_job(design, into(dir));
  CHECK(verdict(r).valid());
  CHECK(verdict(r).self_intersection == IntersectionCheck::Tested);
  CHECK(verdict(r).genus == std::optional<long>(1));
  CHECK(r.max_deviation <= design.common.tolerance);
  // The mesh takes off at most the exact profile (the chords of its arcs lie inside them).
  const double exact = 2400.0 * 1000 * 30 - 2.0 * 3400 * 100 * (1 - M_PI / 4) +
                       4.0 * 1000 * (5.0 / 3 - M_PI / 2) - 30.0 * (760 * 460 - (4 - M_PI) * 40 * 40);
  CHECK(verdict(r).volume <= exact * (1 + 1e-12));
  CHECK(verdict(r).volume >= exact - r.max_deviation * 2 * 3400 * (M_PI / 2 * 10 + 30) - 1.0);
  // The program: routed with T1, then T2, the profile bit, once round the outline at z -10.
  const std::string program = read_file((dir / "countertop_island.nc").string());
  const std::size_t change = program.find("M6 T2");
  REQUIRE(change != std::string::npos);
  CHECK(program.find("M6 T1") < change);
  CHECK(program.find("(countertop_island exposed edges 1)") > change);
  const test::Trace trace = test::interpret(program, "countertop_island.nc");
  const int profiling_from =
      static_cast<int>(std::count(program.begin(), program.begin() + change, '\n')) + 1;
  const double radius = 6.0;
  double along = 0.0, cutting = 0.0, plunging = 0.0;
  for (const test::TraceMotion& m : trace.motions) {
    if (m.motion == "G0") continue;
    const double length = std::hypot(test::motion_length(m), m.end.z() - m.start.z());
    if (m.feed == 3000.0) cutting += length;
    if (m.feed == 600.0) plunging += length;
    if (m.line <= profiling_from) continue;  // the routing (its first pass is at z -10 too)
    if (std::abs(m.start.z() + 10.0) > 1e-6 || std::abs(m.end.z() + 10.0) > 1e-6) continue;
    const int steps = std::max(1, static_cast<int>(std::ceil(test::motion_length(m) / 0.5)));
    for (int i = 0; i <= steps; ++i) {
      const Vec3 c = test::motion_point(m, static_cast<double>(i) / steps);
      // The tip's radius off the outline, outside it, all the way round.
      const double dx = std::max({0.0 - c.x(), c.x() - 2400.0, 0.0}),
                   dy = std::max({0.0 - c.y(), c.y() - 1000.0, 0.0});
      CHECK(std::hypot(dx, dy) == Approx(radius).margin(0.01));
    }
    along += test::motion_length(m);
  }
  // Round the outline: its perimeter plus a quarter circle of the tip's radius at each corner.
  CHECK(along == Approx(2 * 3400 + 2 * M_PI * radius).margin(0.05));
  // The estimate counts the profiling pass: CNCjs's own lengths at each feed.
  const Facts& cnc = r.facts.group("cnc");
  const double slack = 4e-3 * static_cast<double>(trace.motions.size());
  CHECK(std::abs(cutting - cnc.number("cutting_length")) <= slack);
  CHECK(std::abs(plunging - cnc.number("plunging_length")) <= slack);
}
