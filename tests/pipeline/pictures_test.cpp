// The pictures a designer judges, through the command line: `plot` for every
// kind, `preview` of designs and mesh files, the `png`/`plot` outputs and the
// HTML report of `run --report`, loaded by Chromium.

#include "pipeline/pictures.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>

#include "geometry/mesh/bounding_box.h"
#include "io/file.h"
#include "io/mesh/stl.h"
#include "pipeline/load_design.h"
#include "tests/geometry/mesh/shapes.h"
#include "tests/io/pictures/chromium.h"
#include "tests/io/pictures/png_decode.h"
#include "tests/io/pictures/xml_scan.h"
#include "tests/pipeline/cli_harness.h"

using namespace fabmesh;
using namespace fabmesh::test;
using namespace fabmesh::testing;
namespace fs = std::filesystem;

namespace {

// The data-name of every drawn curve of a plot.
std::multiset<std::string> curve_names(const std::string& svg) {
  std::multiset<std::string> names;
  const auto doc = scan_xml(svg);
  for (const XmlElement* e : select(doc, "path", "curve")) names.insert(e->attr("data-name"));
  return names;
}

// Pixels of a decoded image that are not the preview's background.
std::size_t drawn_pixels(const DecodedPng& image) {
  std::size_t n = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) n += image.at(x, y) != std::array<std::uint8_t, 3>{235, 235, 235};
  }
  return n;
}

}  // namespace

TEST_CASE("plot: every kind draws its curves, a surface its patch borders and control net",
          "[pipeline][pictures][plot]") {
  const fs::path dir = fresh_dir("plot_kinds");
  REQUIRE(run_cli({"plot", example("vessel_golden_shell.yaml"), example("countertop_g1.yaml"),
                   example("surface_basin_shell.yaml"), example("golden_profile.yaml"), "-o",
                   dir.string()}) == 0);
  CHECK(curve_names(read_file((dir / "vessel_golden_shell.plot.svg").string())) ==
        std::multiset<std::string>{"profile"});
  const auto countertop = curve_names(read_file((dir / "countertop_g1.plot.svg").string()));
  CHECK(countertop.count("outline") == 1);
  CHECK(countertop.count("holes[0]") == 1);
  CHECK(countertop.count("holes[1]") == 1);
  const std::string surface = read_file((dir / "surface_basin_shell.plot.svg").string());
  const auto borders = curve_names(surface);
  CHECK(borders.size() % 4 == 0);
  CHECK(borders.size() >= 4);
  CHECK(select(scan_xml(surface), "path", "net").size() == 1);  // the control net in plan, dotted
  CHECK(curve_names(read_file((dir / "golden_profile.plot.svg").string())) ==
        std::multiset<std::string>{"curve"});
}

// The area a closed polyline encloses (shoelace), positive either way round.
double enclosed_area(const std::vector<Vec2>& loop) {
  double twice = 0.0;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Vec2& a = loop[i];
    const Vec2& b = loop[(i + 1) % loop.size()];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return std::abs(0.5 * twice);
}

TEST_CASE("plot: a vessel's axis, coordinates and section as built, a shell's inner wall in it",
          "[pipeline][pictures][plot]") {
  const fs::path dir = fresh_dir("plot_vessel_section");
  REQUIRE(run_cli({"plot", example("vessel_golden_shell.yaml"), "-o", dir.string()}) == 0);
  const auto svg = scan_xml(read_file((dir / "vessel_golden_shell.plot.svg").string()));
  CHECK(select(svg, "g", "axis").size() == 1);
  CHECK(select(svg, "text", "tick").size() >= 4);
  std::vector<std::string> names;
  for (const XmlElement* t : select(svg, "text", "axis-name")) names.push_back(t->text);
  CHECK(names == std::vector<std::string>{"r (cm)", "z (cm)"});
  CHECK(select(svg, "path", "outline").size() == 1);
  // The section the plot draws is the builder's: from `plot` (no mesh) and
  // from a build (the studio's, `run`'s plot output), a shell's encloses
  // less than the solid's of the same profile, by its cavity.
  const Design shell = load_design(example("vessel_golden_shell.yaml"));
  const Design solid = load_design(example("vessel_golden_solid.yaml"));
  for (const CurvePlot& plot : {design_plot(shell), shape_plot(shell.common, build_preview(shell))}) {
    CHECK(plot.revolution_axis);
    REQUIRE(plot.outlines.size() == 1);
    const double shell_area = enclosed_area(plot.outlines.front().points);
    const double solid_area = enclosed_area(design_plot(solid).outlines.at(0).points);
    CHECK(shell_area > 0.0);
    CHECK(shell_area < 0.5 * solid_area);
    // On the axis, the section runs from the bottom up to the cavity's floor: the base (0.4 cm) apart.
    double low = std::numeric_limits<double>::infinity(), high = -low;
    for (const Vec2& p : plot.outlines.front().points) {
      if (p.x() != 0.0) continue;
      low = std::min(low, p.y());
      high = std::max(high, p.y());
    }
    CHECK(high - low == Approx(0.4).epsilon(1e-9));
  }
  // The overall height and the widest diameter, as dimensions: those of the mesh the builder makes.
  const Result built = build_preview(shell);
  const Vec3 size = built.bbox_max - built.bbox_min;
  const CurvePlot plot = shape_plot(shell.common, built);
  REQUIRE(plot.dimensions.size() == 2);
  CHECK(plot.dimensions[0].name == "height");
  CHECK(plot.dimensions[0].value == Approx(size.z()).epsilon(1e-12));
  CHECK(plot.dimensions[1].name == "widest diameter");
  // The mesh's vertices lie on the exact surface, so no wider than the exact
  // widest diameter, and short of it by less than the proven deviation.
  CHECK(plot.dimensions[1].value >= std::max(size.x(), size.y()));
  CHECK(plot.dimensions[1].value - std::max(size.x(), size.y()) <= 2.0 * built.max_deviation);
  std::vector<std::string> dimensions;
  for (const XmlElement* g : select(svg, "g", "dimension")) dimensions.push_back(g->attr("data-name"));
  CHECK(dimensions == std::vector<std::string>{"height", "widest diameter"});
  CHECK_THAT(read_file((dir / "vessel_golden_shell.plot.svg").string()),
             Catch::Contains(">height 4.134 cm</text>") && Catch::Contains(">\u00d8 5.193 cm</text>"));
  // A countertop has no axis; its coordinates are x and y.
  REQUIRE(run_cli({"plot", example("countertop_g1.yaml"), "-o", dir.string()}) == 0);
  const auto top = scan_xml(read_file((dir / "countertop_g1.plot.svg").string()));
  CHECK(select(top, "g", "axis").empty());
  CHECK(select(top, "text", "tick").size() >= 4);
  CHECK(select(top, "g", "dimension").empty());
}

TEST_CASE("plot: one file for one design, overrides apply, a bad design writes nothing",
          "[pipeline][pictures][plot]") {
  const fs::path dir = fresh_dir("plot_one");
  const std::string one = (dir / "cup.svg").string();
  REQUIRE(run_cli({"plot", example("vessel_golden_shell.yaml"), "-o", one, "-D", "profile.lambdas[0]=-1"}) ==
          0);
  const std::string changed = read_file(one);
  REQUIRE(run_cli({"plot", example("vessel_golden_shell.yaml"), "-o", one}) == 0);
  CHECK(read_file(one) != changed);
  CHECK(run_cli({"plot", example("vessel_golden_shell.yaml"), example("countertop_g1.yaml"), "-o", one}) ==
        2);
  std::string out;
  CHECK(
      run_cli({"plot", example("vessel_golden_shell.yaml"), "-o", (dir / "bad").string(), "-D", "body.wal=2"},
              &out) == 2);
  CHECK_THAT(out, Catch::Contains("wal"));
  CHECK_FALSE(fs::exists(dir / "bad"));
}

TEST_CASE("preview: a design and a mesh file give a shaded PNG of the asked size",
          "[pipeline][pictures][preview]") {
  const fs::path dir = fresh_dir("preview");
  const std::string from_design = (dir / "cup.png").string();
  REQUIRE(run_cli({"preview", example("vessel_golden_shell.yaml"), "-o", from_design, "--width", "320",
                   "--height", "240", "--views", "2"}) == 0);
  const DecodedPng a = decode_png(read_file(from_design));
  CHECK(a.width == 320);
  CHECK(a.height == 240);
  CHECK(drawn_pixels(a) > 320 * 240 / 10);
  write_stl(test::torus(3, 1, 40, 20), (dir / "torus.stl").string());
  const std::string from_mesh = (dir / "torus.png").string();
  REQUIRE(run_cli({"preview", (dir / "torus.stl").string(), "-o", from_mesh}) == 0);
  const DecodedPng b = decode_png(read_file(from_mesh));
  CHECK(b.width == 800);
  CHECK(drawn_pixels(b) > 800 * 600 / 10);
  // Wrong ending, a curve design (no mesh), -D on a mesh file: exit 2, nothing written.
  CHECK(run_cli({"preview", example("vessel_golden_shell.yaml"), "-o", (dir / "x.jpg").string()}) == 2);
  CHECK(run_cli({"preview", example("golden_profile.yaml"), "-o", (dir / "c.png").string()}) == 2);
  CHECK(run_cli({"preview", (dir / "torus.stl").string(), "-o", (dir / "d.png").string(), "-D",
                 "units=mm"}) == 2);
  CHECK_FALSE(fs::exists(dir / "x.jpg"));
  CHECK_FALSE(fs::exists(dir / "c.png"));
  CHECK_FALSE(fs::exists(dir / "d.png"));
}

TEST_CASE("preview: a design's size in its units, a vessel's axis, a mould's parts exploded apart",
          "[pipeline][pictures][preview]") {
  CHECK(size_caption(test::box(Vec3(0, 0, 0), Vec3(3, 2, 1)), "cm") == "3.000 x 2.000 x 1.000 cm");
  CHECK(size_caption(test::box(Vec3(0, 0, 0), Vec3(1200, 600.25, 0.03)), "") == "1200 x 600.2 x 0.03000");
  const Design design = load_design(example("mould_golden.yaml"));
  const Result built = build_preview(design);
  REQUIRE(built.parts.size() >= 3);  // the vessel and at least two mould parts
  const TriangleSoup& vessel = product(built)->mesh;
  const TriangleSoup scene = exploded_scene(built);
  std::size_t triangles = 0;
  for (const Part& p : built.parts) triangles += p.mesh.triangles.size();
  CHECK(scene.triangles.size() == triangles);
  // Apart: no two parts' boxes overlap, and none overlaps the vessel's.
  std::vector<BoundingBox> boxes{bounding_box(vessel.vertices)};
  std::size_t first = vessel.vertices.size();
  for (const Part& p : built.parts) {
    if (p.role == PartRole::Product) continue;
    const std::vector<Vec3> moved(
        scene.vertices.begin() + static_cast<std::ptrdiff_t>(first),
        scene.vertices.begin() + static_cast<std::ptrdiff_t>(first + p.mesh.vertices.size()));
    boxes.push_back(bounding_box(moved));
    first += p.mesh.vertices.size();
  }
  auto overlap = [](const BoundingBox& a, const BoundingBox& b) {
    return (a.lo.array() < b.hi.array()).all() && (b.lo.array() < a.hi.array()).all();
  };
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    for (std::size_t j = i + 1; j < boxes.size(); ++j) {
      INFO("boxes " << i << " and " << j);
      CHECK_FALSE(overlap(boxes[i], boxes[j]));
    }
  }
  // The picture: the caption at the bottom left, the axis through the middle column.
  const fs::path dir = fresh_dir("preview_annotated");
  const std::string png = (dir / "cup.png").string();
  REQUIRE(run_cli({"preview", example("vessel_golden_solid.yaml"), "-o", png, "--width", "400", "--height",
                   "300"}) == 0);
  const DecodedPng image = decode_png(read_file(png));
  int ink_caption = 0, ink_axis = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      if (!(image.at(x, y) == Rgb{55, 55, 55})) continue;
      if (y >= image.height - 10 * (image.height / 200) && x < 200) ++ink_caption;
      if (y < image.height / 8 || y > image.height * 7 / 8) ink_axis += std::abs(x - 200) <= 2 ? 1 : 0;
    }
  }
  CHECK(ink_caption > 50);
  CHECK(ink_axis > 4);
}

TEST_CASE("plot: a declared continuity the curve does not have is drawn, flagged, with a warning",
          "[pipeline][pictures][plot]") {
  const fs::path dir = fresh_dir("plot_contradicted");
  write_text(dir / "kink.yaml", R"(name: kink
kind: curve
tolerance: 0.01
curve:
  family: tbezier
  segments:
    - points: [[0, 0], [1, 2], [3, 2], [4, 0]]
    - points: [[4, 0], [5, -1], [6, 1], [8, 0]]
      continuity: G1
)");
  const CliResult plot =
      run_fabmesh({"plot", (dir / "kink.yaml").string(), "-o", (dir / "kink.svg").string()});
  CHECK(plot.code == 0);
  CHECK_THAT(plot.err,
             Catch::Contains("warning") && Catch::Contains("kink.yaml:") && Catch::Contains("declared G1"));
  const auto svg = scan_xml(read_file((dir / "kink.svg").string()));
  const auto lost = select(svg, "g", "lost");
  REQUIRE(lost.size() == 1);
  CHECK(lost[0]->attr("data-declared") == "G1");
  CHECK(lost[0]->attr("data-achieved") == "G0");
  // run still refuses it, and a curve that cannot be built at all is still an error.
  CHECK(run_cli({"run", (dir / "kink.yaml").string(), "-o", (dir / "out").string() + "/"}) == 2);
  write_text(dir / "short.yaml", R"(name: short
kind: curve
tolerance: 0.01
curve:
  family: tbezier
  segments:
    - points: [[0, 0], [1, 2], [3, 2]]
)");
  CHECK(run_cli({"plot", (dir / "short.yaml").string(), "-o", (dir / "short.svg").string()}) == 2);
  CHECK_FALSE(fs::exists(dir / "short.svg"));
}

TEST_CASE("run --report: one page with every design, its pictures beside the outputs, loaded by Chromium",
          "[pipeline][pictures][report][chromium]") {
  REQUIRE(chromium_available());  // Debian package chromium (scripts/install-deps.sh --test)
  const fs::path dir = fresh_dir("run_report");
  const fs::path bad = dir / "bad.yaml";
  write_file_atomically(bad.string(), "name: bad\nkind: vessel\nunits: mm\n");
  const std::string page = (dir / "report" / "index.html").string();
  CHECK(run_cli({"run", example("vessel_golden_shell.yaml"), example("countertop_g1.yaml"),
                 example("golden_profile.yaml"), bad.string(), "-o", (dir / "out").string(), "--report",
                 page}) == 2);
  const std::string html = read_file(page);
  const auto doc = scan_xml(html, true);
  CHECK(select(doc, "tr").size() == 5);  // the header and four designs
  // Every image and link resolves to a file beside the page.
  std::size_t images = 0;
  for (const XmlElement* img : select(doc, "img")) {
    ++images;
    CHECK(fs::is_regular_file(fs::path(page).parent_path() / decode_entities(img->attr("src"))));
  }
  CHECK(images >= 5);  // two previews, three plots
  for (const char* file : {"vessel_golden_shell.png", "countertop_g1.plot.svg", "golden_profile.plot.svg"})
    CHECK(fs::is_regular_file(dir / "out" / file));
  CHECK(html.find("bad input") != std::string::npos);
  const ChromiumRun run =
      run_chromium("--window-size=1400,900 --virtual-time-budget=10000 --dump-dom", file_url(page));
  INFO(run.err);
  REQUIRE(run.code == 0);
  const auto dom = scan_xml(run.out, true);
  const XmlElement& body = *select(dom, "body").at(0);
  CHECK(body.attr("data-images-loaded") == std::to_string(images));
  CHECK(body.attr("data-images-failed") == "0");
}

TEST_CASE("batch --report: a page of every variant with a thumbnail of its mesh, loaded by Chromium",
          "[pipeline][pictures][report][batch][chromium]") {
  REQUIRE(chromium_available());  // Debian package chromium (scripts/install-deps.sh --test)
  const fs::path dir = fresh_dir("batch_report");
  const std::string page = (dir / "report.html").string();
  REQUIRE(run_cli({"batch", example("batch_vessel_sweep.yaml"), "-o", (dir / "sweep").string(), "--report",
                   page, "-q"}) == 0);
  const std::string html = read_file(page);
  const auto doc = scan_xml(html, true);
  std::size_t variants = 0;
  for (const auto& e : fs::directory_iterator(dir / "sweep"))
    variants += e.is_directory() && e.path().filename() != ".batch";
  REQUIRE(variants >= 10);
  CHECK(select(doc, "tr").size() == variants + 1);
  std::size_t images = 0;
  for (const XmlElement* img : select(doc, "img")) {
    ++images;
    CHECK(fs::is_regular_file(dir / decode_entities(img->attr("src"))));
  }
  CHECK(images == variants);
  // A rerun keeps the thumbnails; a report of a batch that never ran is bad input.
  CHECK(run_cli({"batch", "--merge", (dir / "sweep").string(), "--report", page}) == 0);
  CHECK(run_cli({"batch", "--merge", (dir / "nothing").string(), "--report", (dir / "x.html").string()}) !=
        0);
  CHECK(run_cli({"batch", example("batch_vessel_sweep.yaml"), "-o", (dir / "sweep").string(), "--report",
                 (dir / "r.txt").string()}) == 2);
  const ChromiumRun run =
      run_chromium("--window-size=1400,2400 --virtual-time-budget=10000 --dump-dom", file_url(page));
  INFO(run.err);
  REQUIRE(run.code == 0);
  const auto dom = scan_xml(run.out, true);
  const XmlElement& body = *select(dom, "body").at(0);
  CHECK(body.attr("data-images-failed") == "0");
  CHECK(body.attr("data-images-loaded") != "0");
}

TEST_CASE("report row: a page row shows an item's facts, measures only when measured", "[pipeline][report]") {
  ItemFacts item;
  item.name = "cup";
  item.status = ItemStatus::Ok;
  item.message = "valid for fabrication";
  MeshFacts mesh;
  mesh.kind = "vessel";
  mesh.units = "cm";
  mesh.triangles = 12;
  mesh.volume = 1.5;
  mesh.area = 7.25;
  mesh.bbox_min = Vec3(-1, -2, 0);
  mesh.bbox_max = Vec3(1, 2, 3);
  mesh.max_deviation = 0.01;
  item.mesh = mesh;
  item.files = {"out/cup/cup.stl"};
  item.timings_ms = {{"build", 1500.0}};
  const ReportRow row = report_row(item, "out");
  CHECK(row.name == "cup");
  CHECK(row.status == ReportStatus::Ok);
  CHECK(row.message == "valid for fabrication");
  CHECK(row.kind == "vessel");
  CHECK(row.units == "cm");
  CHECK(row.triangles == std::optional<std::size_t>(12));
  CHECK(row.volume == std::optional<double>(1.5));
  CHECK(row.area == std::optional<double>(7.25));
  CHECK(row.max_deviation == std::optional<double>(0.01));
  REQUIRE(row.bbox);
  CHECK((*row.bbox)[1] == Vec3(1, 2, 3));
  CHECK(row.files == std::vector<std::string>{"cup/cup.stl"});
  REQUIRE(row.timings.size() == 1);
  CHECK(row.timings[0].seconds == 1.5);

  item.mesh->measured = false;  // a drawing: no counts, volume or area
  const ReportRow drawn = report_row(item, "");
  CHECK_FALSE(drawn.triangles);
  CHECK_FALSE(drawn.volume);
  CHECK_FALSE(drawn.area);
  CHECK(drawn.bbox);
  CHECK(drawn.files == std::vector<std::string>{"out/cup/cup.stl"});
}

TEST_CASE("report row: a failed item has no measures, missing and environment show as errors",
          "[pipeline][report]") {
  const ReportRow failed = report_row(failed_facts("cup", kExitBadInput, "bad"), "");
  CHECK(failed.status == ReportStatus::BadInput);
  CHECK(failed.message == "bad");
  CHECK(failed.kind.empty());
  CHECK_FALSE(failed.bbox);
  CHECK_FALSE(failed.max_deviation);
  CHECK(report_status(ItemStatus::Ok) == ReportStatus::Ok);
  CHECK(report_status(ItemStatus::Invalid) == ReportStatus::Invalid);
  CHECK(report_status(ItemStatus::BadInput) == ReportStatus::BadInput);
  CHECK(report_status(ItemStatus::Error) == ReportStatus::Error);
  CHECK(report_status(ItemStatus::Missing) == ReportStatus::Error);
  CHECK(report_status(ItemStatus::Environment) == ReportStatus::Error);
}
