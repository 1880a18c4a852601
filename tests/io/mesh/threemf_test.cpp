// 3MF: fabmesh's writer read by PrusaSlicer (and sliced), and 3MF files from
// PrusaSlicer, OpenSCAD and hand-written packages read by fabmesh.

#include "io/mesh/threemf.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include "geometry/core/errors.h"
#include "geometry/mesh/weld.h"
#include "geometry/validation/validate.h"
#include "io/file.h"
#include "io/mesh/read_mesh.h"
#include "io/mesh/stl.h"
#include "tests/geometry/mesh/shapes.h"
#include "tests/io/mesh/external_tool.h"
#include "tests/io/mesh/temp_dir.h"
#include "tests/io/mesh/vessel_fixture.h"

using namespace fabmesh;
using test::quoted;
using test::run_tool;
using test::TempDir;

namespace {

/// `prusa-slicer ARGS` with a private HOME and data folder in `dir`, no GUI.
test::ToolRun prusa(const TempDir& dir, const std::string& args) {
  return test::prusa_slicer(dir.file("home"), args);
}

/// The "key = value" lines PrusaSlicer's --info prints, e.g. size_x, manifold.
std::map<std::string, std::string> prusa_info(const TempDir& dir, const std::string& file) {
  test::ToolRun run;
  std::map<std::string, std::string> info = test::prusa_info(dir.file("home"), file, &run);
  INFO(run.output);
  REQUIRE(run.code == 0);
  return info;
}

/// A 3MF package zipped by Python's zipfile (an independent producer) from
/// one 3D model part.
std::string zip_3mf(const TempDir& dir, const std::string& name, const std::string& model_xml) {
  REQUIRE_PROGRAM("python3");
  const std::string content_types =
      R"(<?xml version="1.0" encoding="UTF-8"?><Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">)"
      R"(<Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/>)"
      R"(<Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/></Types>)";
  const std::string rels =
      R"(<?xml version="1.0" encoding="UTF-8"?><Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">)"
      R"(<Relationship Target="/3D/3dmodel.model" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/>)"
      R"(</Relationships>)";
  dir.write(name + ".types", content_types);
  dir.write(name + ".rels", rels);
  dir.write(name + ".model", model_xml);
  const std::string script =
      "import sys, zipfile\n"
      "d, n = sys.argv[1], sys.argv[2]\n"
      "with zipfile.ZipFile(d + '/' + n, 'w', zipfile.ZIP_DEFLATED) as z:\n"
      "    z.write(d + '/' + n + '.types', '[Content_Types].xml')\n"
      "    z.write(d + '/' + n + '.rels', '_rels/.rels')\n"
      "    z.write(d + '/' + n + '.model', '3D/3dmodel.model')\n";
  dir.write("zip3mf.py", script);
  const test::ToolRun run =
      run_tool("python3 " + quoted(dir.file("zip3mf.py")) + " " + quoted(dir.file("")) + " " + quoted(name));
  INFO(run.output);
  REQUIRE(run.code == 0);
  return read_file(dir.file(name));
}

/// A unit cube [0,1]^3 as a 3MF <mesh> element.
std::string cube_mesh_xml() {
  const TriangleSoup box = test::box();
  std::string xml = "<mesh><vertices>";
  for (const Vec3& p : box.vertices) {
    xml += "<vertex x=\"" + std::to_string(p.x()) + "\" y=\"" + std::to_string(p.y()) + "\" z=\"" +
           std::to_string(p.z()) + "\"/>";
  }
  xml += "</vertices><triangles>";
  for (const auto& t : box.triangles) {
    xml += "<triangle v1=\"" + std::to_string(t[0]) + "\" v2=\"" + std::to_string(t[1]) + "\" v3=\"" +
           std::to_string(t[2]) + "\"/>";
  }
  return xml + "</triangles></mesh>";
}

constexpr const char* kModelHead =
    R"(<?xml version="1.0" encoding="UTF-8"?><model unit="millimeter" xml:lang="en-US" )"
    R"(xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">)";

ValidationReport welded_report(const TriangleSoup& soup) { return validate(weld(soup).soup); }

}  // namespace

TEST_CASE("3mf: objects, names, unit and title survive a round trip within the 6-decimal bound",
          "[io][3mf]") {
  const TriangleSoup torus = test::rotated(test::torus(3.0, 1.0, 24, 12), Vec3(1, 1, 0), 0.3);
  TriangleSoup box = test::box(Vec3(5.25, -1.5, 0.125), Vec3(7.5, 1.0 / 3.0, 2.0));
  const std::vector<ThreeMfObject> objects = {{"ring", torus}, {"block", box}};
  ThreeMfOptions options;
  options.units = "cm";
  options.title = "two bodies";
  const std::string bytes = encode_3mf(objects, options);
  const ThreeMfContent back = parse_3mf(bytes, "two.3mf");
  CHECK(back.unit == "cm");
  CHECK(back.metres_per_unit == 0.01);
  REQUIRE(back.objects.size() == 2);
  for (std::size_t i = 0; i < 2; ++i) {
    INFO("object " << i);
    CHECK(back.objects[i].name == objects[i].name);
    CHECK(back.objects[i].soup.triangles == objects[i].soup.triangles);
    REQUIRE(back.objects[i].soup.vertices.size() == objects[i].soup.vertices.size());
    double worst = 0.0;
    double magnitude = 0.0;
    for (std::size_t v = 0; v < objects[i].soup.vertices.size(); ++v) {
      worst = std::max(worst, (back.objects[i].soup.vertices[v] - objects[i].soup.vertices[v]).norm());
      magnitude = std::max(magnitude, objects[i].soup.vertices[v].cwiseAbs().maxCoeff());
    }
    CHECK(worst <= threemf_max_error(magnitude));
    CHECK(welded_report(back.objects[i].soup).valid());
  }
  const TriangleSoup merged = merged_soup(back);
  CHECK(merged.triangles.size() == torus.triangles.size() + box.triangles.size());
  CHECK(welded_report(merged).valid());
  CHECK(detect_format(bytes, "no-extension") == MeshFormat::ThreeMf);
  CHECK(parse_mesh(bytes, "x").triangles.size() == merged.triangles.size());
}

TEST_CASE("3mf: the writer is deterministic and its UUIDs follow the content", "[io][3mf]") {
  const std::vector<ThreeMfObject> objects = {{"ring", test::torus(3.0, 1.0, 16, 8)}};
  ThreeMfOptions options;
  options.title = "ring";
  const std::string a = encode_3mf(objects, options);
  CHECK(encode_3mf(objects, options) == a);
  options.title = "another ring";
  CHECK(encode_3mf(objects, options) != a);
  // The zip entries carry no date: lib3mf 1.8 writes 0 (shown as 1980-00-00 00:00).
  const TempDir dir;
  dir.write("ring.3mf", a);
  REQUIRE_PROGRAM("python3");
  const test::ToolRun listing = run_tool(
      "python3 -c \"import sys, zipfile; [print(i.filename, i.date_time) for i in "
      "zipfile.ZipFile(sys.argv[1]).infolist()]\" " +
      quoted(dir.file("ring.3mf")));
  INFO(listing.output);
  CHECK(listing.output.find("3D/3dmodel.model (1980, 0, 0, 0, 0, 0)") != std::string::npos);
  CHECK(listing.output.find("_rels/.rels (1980, 0, 0, 0, 0, 0)") != std::string::npos);
}

TEST_CASE("3mf: PrusaSlicer reads fabmesh's vessel as manifold with its size in mm, and slices it",
          "[io][3mf][prusaslicer]") {
  REQUIRE_PROGRAM("prusa-slicer");
  const TempDir dir;
  const TriangleSoup vessel_cm = test::golden_vessel_cm();
  const auto [lo, hi] = test::bounds(vessel_cm);
  const ValidationReport exact = validate(vessel_cm);
  REQUIRE(exact.valid());
  // The same vessel in cm and in mm: PrusaSlicer works in mm, so both show
  // 10x the cm numbers.
  ThreeMfOptions cm;
  cm.units = "cm";
  cm.title = "vessel_golden_shell";
  ThreeMfOptions mm = cm;
  mm.units = "mm";
  write_file_atomically(dir.file("vessel_cm.3mf"), encode_3mf({{"vessel", vessel_cm}}, cm));
  write_file_atomically(dir.file("vessel_mm.3mf"), encode_3mf({{"vessel", test::scaled(vessel_cm, 10)}}, mm));
  for (const char* file : {"vessel_cm.3mf", "vessel_mm.3mf"}) {
    INFO(file);
    std::map<std::string, std::string> info = prusa_info(dir, dir.file(file));
    CHECK(info["manifold"] == "yes");
    CHECK(info["number_of_parts"] == "1");
    const Vec3 size_mm = 10.0 * (hi - lo);
    CHECK(std::stod(info["size_x"]) == Approx(size_mm.x()).margin(1e-3));
    CHECK(std::stod(info["size_y"]) == Approx(size_mm.y()).margin(1e-3));
    CHECK(std::stod(info["size_z"]) == Approx(size_mm.z()).margin(1e-3));
    CHECK(std::stod(info["volume"]) == Approx(1000.0 * exact.volume).epsilon(1e-5));
  }
  const test::ToolRun slice = prusa(dir, "--export-gcode " + quoted(dir.file("vessel_cm.3mf")) +
                                             " --output " + quoted(dir.file("v.gcode")));
  INFO(slice.output);
  REQUIRE(slice.code == 0);
  const std::string gcode = read_file(dir.file("v.gcode"));
  // Layers of extrusion all the way up (PrusaSlicer's layers are at most 0.5 mm).
  std::size_t layers = 0;
  for (std::size_t at = gcode.find(";LAYER_CHANGE"); at != std::string::npos;
       at = gcode.find(";LAYER_CHANGE", at + 1))
    ++layers;
  CHECK(static_cast<double>(layers) >= 10.0 * (hi - lo).z() / 0.5);
  // Extrusion moves: "G1 X.. Y.. E.." lines (a scan: std::regex overflows the stack on long text under ASan).
  std::size_t extrusions = 0;
  for (std::size_t at = gcode.find("\nG1 X"); at != std::string::npos; at = gcode.find("\nG1 X", at + 1)) {
    const std::size_t end = gcode.find('\n', at + 1);
    const std::string line = gcode.substr(at + 1, end - at - 1);
    if (line.find(" Y") != std::string::npos && line.find(" E") != std::string::npos) ++extrusions;
  }
  CHECK(extrusions > 100);
}

TEST_CASE("3mf: a 3MF PrusaSlicer exports from fabmesh's STL reads back valid with the same volume",
          "[io][3mf][prusaslicer]") {
  REQUIRE_PROGRAM("prusa-slicer");
  const TempDir dir;
  const TriangleSoup vessel_mm = test::scaled(test::golden_vessel_cm(), 10);
  const ValidationReport exact = validate(vessel_mm);
  write_stl(vessel_mm, dir.file("vessel.stl"));
  const test::ToolRun run = prusa(
      dir, "--export-3mf " + quoted(dir.file("vessel.stl")) + " --output " + quoted(dir.file("prusa.3mf")));
  INFO(run.output);
  REQUIRE(run.code == 0);
  const ThreeMfContent content = parse_3mf(read_file(dir.file("prusa.3mf")), "prusa.3mf");
  CHECK(content.unit == "mm");
  REQUIRE(content.objects.size() == 1);
  const ValidationReport back = welded_report(merged_soup(content));
  CHECK(back.valid());
  CHECK(back.genus == 0);
  CHECK(back.volume == Approx(exact.volume).epsilon(1e-5));
  CHECK(read_mesh(dir.file("prusa.3mf")).triangles.size() == vessel_mm.triangles.size());
}

TEST_CASE("3mf: a 3MF OpenSCAD exports reads back as the exact solid", "[io][3mf][openscad]") {
  REQUIRE_PROGRAM("openscad");
  const TempDir dir;
  // A 20 mm cube with a 10 mm cavity: two closed shells, volume 8000 - 1000.
  dir.write("hollow.scad", "difference() { cube(20, center = true); cube(10, center = true); }\n");
  const test::ToolRun run = run_tool("HOME=" + quoted(dir.file("")) + " openscad -o " +
                                     quoted(dir.file("hollow.3mf")) + " " + quoted(dir.file("hollow.scad")));
  INFO(run.output);
  REQUIRE(run.code == 0);
  const ThreeMfContent content = parse_3mf(read_file(dir.file("hollow.3mf")), "hollow.3mf");
  CHECK(content.unit == "mm");
  const ValidationReport r = welded_report(merged_soup(content));
  CHECK(r.valid());
  CHECK(r.components == 2);
  CHECK(r.volume == Approx(7000.0).epsilon(1e-12));
  CHECK(r.area == Approx(6 * 400.0 + 6 * 100.0).epsilon(1e-12));
}

TEST_CASE("3mf: build item and component transforms are applied, and a mirror stays outward", "[io][3mf]") {
  const TempDir dir;
  // Object 1: the unit cube. Object 2: two components of it, one moved by
  // (10, 0, 0) and scaled by 2, one mirrored in x. The build item lifts it by 5.
  const std::string xml =
      std::string(kModelHead) + "<resources><object id=\"1\" type=\"model\">" + cube_mesh_xml() +
      "</object><object id=\"2\" type=\"model\"><components>"
      "<component objectid=\"1\" transform=\"2 0 0 0 2 0 0 0 2 10 0 0\"/>"
      "<component objectid=\"1\" transform=\"-1 0 0 0 1 0 0 0 1 -3 0 0\"/>"
      "</components></object></resources>"
      "<build><item objectid=\"2\" transform=\"1 0 0 0 1 0 0 0 1 0 0 5\"/></build></model>";
  const ThreeMfContent content = parse_3mf(zip_3mf(dir, "parts.3mf", xml), "parts.3mf");
  REQUIRE(content.objects.size() == 1);
  const TriangleSoup& soup = content.objects[0].soup;
  CHECK(soup.triangles.size() == 24);
  const ValidationReport r = welded_report(soup);
  CHECK(r.valid());
  CHECK(r.components == 2);
  CHECK(r.volume == Approx(8.0 + 1.0));  // positive: the mirrored cube is still outward
  const auto [lo, hi] = test::bounds(soup);
  CHECK(lo == Vec3(-4, 0, 5));
  CHECK(hi == Vec3(12, 2, 7));

  ThreeMfReadOptions tight;
  tight.max_triangles = 20;
  CHECK_THROWS_AS(parse_3mf(read_file(dir.file("parts.3mf")), "parts.3mf", tight), FileError);
}

TEST_CASE("3mf: malformed packages are FileErrors naming the file", "[io][3mf]") {
  const std::string good = encode_3mf({{"cube", test::box()}}, {});
  for (const std::string& bad :
       {std::string(), std::string("PK\x03\x04", 4), good.substr(0, good.size() / 2),
        std::string("PK\x03\x04", 4) + " not really a zip archive at all", good.substr(1)}) {
    try {
      parse_3mf(bad, "bad.3mf");
      FAIL("no exception");
    } catch (const FileError& e) {
      CHECK(e.path() == "bad.3mf");
      CHECK(std::string(e.what()).rfind("bad.3mf: ", 0) == 0);
    }
  }
  const TempDir dir;
  const std::string index_out_of_range =
      std::string(kModelHead) +
      "<resources><object id=\"1\" type=\"model\"><mesh><vertices><vertex x=\"0\" y=\"0\" z=\"0\"/>"
      "<vertex x=\"1\" y=\"0\" z=\"0\"/><vertex x=\"0\" y=\"1\" z=\"0\"/></vertices><triangles>"
      "<triangle v1=\"0\" v2=\"1\" v3=\"7\"/></triangles></mesh></object></resources>"
      "<build><item objectid=\"1\"/></build></model>";
  CHECK_THROWS_AS(parse_3mf(zip_3mf(dir, "idx.3mf", index_out_of_range), "idx.3mf"), FileError);
  const std::string no_build = std::string(kModelHead) + "<resources><object id=\"1\" type=\"model\">" +
                               cube_mesh_xml() + "</object></resources><build/></model>";
  CHECK_THROWS_AS(parse_3mf(zip_3mf(dir, "empty.3mf", no_build), "empty.3mf"), FileError);
}

TEST_CASE("3mf: the writer refuses what 3MF cannot hold", "[io][3mf]") {
  ThreeMfOptions options;
  CHECK_THROWS_AS(encode_3mf({}, options), InputError);
  CHECK_THROWS_AS(encode_3mf({{"empty", TriangleSoup{}}}, options), InputError);
  TriangleSoup huge = test::box();
  huge.vertices[3].x() = 2e9;  // lib3mf writes x * 1e6 as a 64-bit integer
  CHECK_THROWS_AS(encode_3mf({{"huge", huge}}, options), InputError);
  TriangleSoup nan = test::box();
  nan.vertices[0].y() = std::nan("");
  CHECK_THROWS_AS(encode_3mf({{"nan", nan}}, options), InputError);
  options.units = "furlong";
  CHECK_THROWS_AS(encode_3mf({{"cube", test::box()}}, options), InputError);
  for (const char* u : {"micron", "mm", "cm", "m", "in", "ft"}) {
    options.units = u;
    INFO(u);
    const ThreeMfContent back = parse_3mf(encode_3mf({{"cube", test::box()}}, options), "u.3mf");
    CHECK(back.unit == u);
    CHECK(back.metres_per_unit == threemf_metres_per_unit(u));
  }
}
