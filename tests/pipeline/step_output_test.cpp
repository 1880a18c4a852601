// The `step` output read back by OpenCASCADE's own STEP reader: one valid
// closed solid per design, in the design's unit, its volume the exact one,
// the mesh's vertices on its faces within the mesh's proven deviation.
// An open surface: one shell of B-spline faces within the reported bound; a
// thickened one: one closed solid of its sheets and rim walls.

#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "geometry/fairing/build_curve.h"
#include "geometry/mesh/volume.h"
#include "geometry/mould/mould_options.h"
#include "geometry/surfaces/patch_network.h"
#include "io/design/read_design.h"
#include "io/file.h"
#include "io/mesh/read_mesh.h"
#include "io/step/step.h"
#include "tests/io/design/nurbs_dxf.h"
#include "tests/pipeline/cli_harness.h"

using namespace fabmesh;
using namespace fabmesh::testing;
namespace fs = std::filesystem;

namespace {

// The area a closed curve encloses, 1/2 of the integral of x dy - y dx over the
// exact segments (20 panels of 5-point Gauss-Legendre each: exact to rounding
// for these smooth segments), positive counter-clockwise.
double enclosed_area(const CompositeCurve& curve) {
  const double nodes[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                           0.9061798459386640};
  const double weights[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                             0.2369268850561891};
  constexpr int kPanels = 20;
  double twice = 0.0;
  for (const Segment& s : curve.segments()) {
    for (int p = 0; p < kPanels; ++p) {
      for (int k = 0; k < 5; ++k) {
        const double t = (p + 0.5 + 0.5 * nodes[k]) / kPanels;
        const CurveJet j = s.jet(t);
        twice += weights[k] * 0.5 / kPanels * (j[0].x() * j[1].y() - j[0].y() * j[1].x());
      }
    }
  }
  return 0.5 * twice;
}

struct Written {
  nlohmann::json item;
  std::string step;
};

Written run_step(const std::string& design, const fs::path& dir, const std::string& format = "step") {
  const std::vector<std::string> args = {"run",   design, "--export-format", format, "-o", dir.string() + "/",
                                         "--json"};
  std::string out;
  const int code = run_cli_json(args, &out);
  INFO(out);
  REQUIRE(code == 0);
  Written w;
  w.item = only_item(out);
  REQUIRE(w.item["files"].size() == 1);
  w.step = read_file(w.item["files"][0]["path"].get<std::string>());
  return w;
}

// The one shape OCCT's own reader takes back from `step`, read without an
// error; in `unit` when one is given.
StepShapeFacts only_shape(const std::string& step, const std::string& unit = "") {
  const StepRead r = read_step(step);
  INFO(r.error);
  REQUIRE(r.error.empty());
  if (!unit.empty()) CHECK(r.length_unit == unit);
  REQUIRE(r.roots.size() == 1);
  return r.roots[0];
}

// The design's mesh as `format` writes it (run as a user would), with the
// report's item, and every `step`-th vertex divided by `units` (the file's
// units per unit of the STEP file).
struct MeshRun {
  nlohmann::json item;
  std::vector<Vec3> points;
};

MeshRun mesh_run(const std::string& design, const std::string& format, const fs::path& dir, std::size_t step,
                 double units) {
  std::string out;
  REQUIRE(run_cli_json({"run", design, "--export-format", format, "-o", dir.string() + "/", "--json"},
                       &out) == 0);
  MeshRun r;
  r.item = only_item(out);
  const TriangleSoup mesh = read_mesh(r.item["files"][0]["path"].get<std::string>());
  for (std::size_t i = 0; i < mesh.vertices.size(); i += step) r.points.push_back(mesh.vertices[i] / units);
  return r;
}

}  // namespace

TEST_CASE("step: a countertop is one valid closed solid whose volume is the exact area times the thickness",
          "[pipeline][step]") {
  const fs::path dir = fresh_dir("step_countertop");
  const Written w = run_step(example("countertop_g2.yaml"), dir);
  CHECK(w.item["files"][0]["units"] == "mm");
  CHECK(w.item["files"][0]["max_added_error"] == 0.0);  // lines, T-Bézier, ellipses and arcs: all exact

  const StepShapeFacts solid = only_shape(w.step, "millimetre");
  CHECK(solid.valid);
  CHECK(solid.closed);
  CHECK(solid.solids == 1);

  // The exact area: the outline's less the holes', from the exact curves.
  const Design design = read_design(example("countertop_g2.yaml"));
  const auto& top = std::get<CountertopDesign>(design.body);
  double area = std::abs(enclosed_area(build_curve(top.outline).curve));
  std::size_t edges = build_curve(top.outline).curve.size();
  std::vector<double> hole_areas;
  for (const CountertopHole& hole : top.holes) {
    const CompositeCurve c = build_curve(hole.curve).curve;
    hole_areas.push_back(std::abs(enclosed_area(c)));
    area -= hole_areas.back();
    edges += c.size();
  }
  // The integration checked where the areas are known: the oval sink is pi a b,
  // the cooktop 560 x 460 less its corners' (4 - pi) r^2.
  REQUIRE(hole_areas.size() == 2);
  CHECK(hole_areas[0] == Approx(M_PI * 260.0 * 190.0).epsilon(1e-13));
  CHECK(hole_areas[1] == Approx(560.0 * 460.0 - (4.0 - M_PI) * 100.0).epsilon(1e-13));
  CHECK(solid.volume == Approx(area * top.thickness).epsilon(1e-7));
  // One side face per exact edge, a top and a bottom.
  CHECK(solid.faces == static_cast<int>(edges) + 2);

  // The mesh's vertices lie on the solid's faces within the mesh's deviation.
  const MeshRun mesh =
      mesh_run(example("countertop_g2.yaml"), "obj", fresh_dir("step_countertop_mesh"), 7, 1.0);
  CHECK(max_distance_to_step(w.step, mesh.points) <= mesh.item["max_deviation"].get<double>() + 1e-9);
}

TEST_CASE("step: a countertop from DXF NURBS is exact, its spans rational B-splines of degree 3",
          "[pipeline][step][dxf][rational]") {
  const fs::path dir = fresh_dir("step_nurbs");
  // A round table of radius 250 with an oval cut-out of 120 x 70, both saved as NURBS.
  write_text(dir / "round.dxf",
             test::dxf_drawing(test::dxf_nurbs_ellipse("2A", "OUTLINE", {0, 0}, 250, 250) +
                               test::dxf_nurbs_ellipse("2B", "HOLES", {40, -30}, 120, 70)));
  write_text(dir / "round.yaml",
             "name: round\nkind: countertop\nunits: mm\ntolerance: 0.05\nthickness: 30\n"
             "outline: {dxf: round.dxf, layer: OUTLINE}\nholes: [{dxf: round.dxf, layer: HOLES}]\n");
  const Written w = run_step((dir / "round.yaml").string(), dir / "out");
  CHECK(w.item["files"][0]["max_added_error"] == 0.0);
  const StepShapeFacts solid = only_shape(w.step);
  CHECK(solid.valid);
  CHECK(solid.closed);
  CHECK(solid.solids == 1);
  CHECK(solid.faces == 4 + 4 + 2);  // one side face per span, a top and a bottom
  CHECK(solid.volume == Approx(M_PI * (250.0 * 250.0 - 120.0 * 70.0) * 30.0).epsilon(1e-7));
}

TEST_CASE("step: the golden solid is written in cm, its volume 46.171424531125 cm^3", "[pipeline][step]") {
  const fs::path dir = fresh_dir("step_vessel");
  const Written w = run_step(example("vessel_golden_solid.yaml"), dir);
  CHECK(w.item["files"][0]["units"] == "cm");
  CHECK(w.item["files"][0]["max_added_error"] == 0.0);  // quartic B-spline spans and lines
  const StepShapeFacts solid = only_shape(w.step, "centimetre");
  CHECK(w.step.find("LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.CENTI.,.METRE.)") != std::string::npos);
  CHECK(solid.valid);
  CHECK(solid.closed);
  CHECK(solid.solids == 1);
  CHECK(solid.faces == 6);  // four profile spans, the rim's and the base's discs
  CHECK(solid.volume == Approx(46.171424531125).epsilon(1e-7));

  // The same bytes twice: no time stamp, no addresses.
  const fs::path again = fresh_dir("step_vessel_again");
  CHECK(run_step(example("vessel_golden_solid.yaml"), again).step == w.step);

  // The mesh (STL in mm) on the solid (cm) within its deviation and float32's rounding.
  const MeshRun mesh =
      mesh_run(example("vessel_golden_solid.yaml"), "stl", fresh_dir("step_vessel_mesh"), 11, 10.0);
  const double allowed =
      mesh.item["max_deviation"].get<double>() + mesh.item["files"][0]["max_added_error"].get<double>();
  CHECK(max_distance_to_step(w.step, mesh.points) <= allowed + 1e-9);
}

TEST_CASE("step: a curve design is a wireframe, its H-Bezier segments within the reported bound",
          "[pipeline][step]") {
  const fs::path dir = fresh_dir("step_curve");
  const Written w = run_step(example("hbezier_composite.yaml"), dir);
  const double added = w.item["files"][0]["max_added_error"].get<double>();
  CHECK(added > 0.0);
  // Within what the curve's sampling left of the tolerance.
  CHECK(w.item["max_deviation"].get<double>() + added <= w.item["tolerance"].get<double>());
  const StepShapeFacts wires = only_shape(w.step);
  CHECK(wires.valid);
  CHECK(wires.solids == 0);
  CHECK(wires.edges == 3);  // one edge per segment

  const Design design = read_design(example("hbezier_composite.yaml"));
  const CompositeCurve curve = build_curve(std::get<CurveDesign>(design.body).curve).curve;
  std::vector<Vec3> points;
  for (const Segment& s : curve.segments()) {
    for (int i = 0; i <= 200; ++i) {
      const Vec2 p = s.point(i / 200.0);
      points.emplace_back(p.x(), p.y(), 0.0);
    }
  }
  CHECK(max_distance_to_step(w.step, points) <= added + 1e-9);
}

TEST_CASE("step: a shell vessel's inner wall is within the reported bound of the exact offset",
          "[pipeline][step]") {
  const fs::path dir = fresh_dir("step_shell");
  const Written w = run_step(example("vessel_golden_shell.yaml"), dir);
  const double added = w.item["files"][0]["max_added_error"].get<double>();
  CHECK(added > 0.0);  // the offset is not a B-spline: approximated, proven
  CHECK(w.item["max_deviation"].get<double>() + added <= w.item["tolerance"].get<double>());
  const StepRead r = read_step(w.step);
  INFO(r.error);
  REQUIRE(r.roots.size() == 1);
  const StepShapeFacts& solid = r.roots[0];
  CHECK(solid.valid);
  CHECK(solid.closed);
  CHECK(solid.solids == 1);
  // Outer wall (4 spans), rim, inner wall (4 offset arcs), base and bottom discs.
  CHECK(solid.faces == 11);

  // The mesh and the solid bound the same shell: their volumes differ by at
  // most the area times the distance between their surfaces.
  const MeshRun mesh =
      mesh_run(example("vessel_golden_shell.yaml"), "stl", fresh_dir("step_shell_mesh"), 13, 10.0);
  const double apart = mesh.item["max_deviation"].get<double>() + added;
  CHECK(std::abs(solid.volume - mesh.item["volume"].get<double>()) <=
        mesh.item["area"].get<double>() * apart);
  CHECK(max_distance_to_step(w.step, mesh.points) <=
        apart + mesh.item["files"][0]["max_added_error"].get<double>() + 1e-9);
}

TEST_CASE("step: a batch writes one STEP solid per variant, each its own size", "[pipeline][step][batch]") {
  const fs::path dir = fresh_dir("step_batch");
  write_text(dir / "base.yaml", R"(name: slab
kind: countertop
units: mm
tolerance: 0.05
thickness: 30
outline:
  family: tbezier
  closed: true
  segments:
    - polyline: [[0, 0], [1000, 0], [1000, 600], [0, 600], [0, 0]]
holes:
  - ellipse: {center: [400, 300], a: 200, b: 150}
outputs: [step]
)");
  write_text(dir / "batch.yaml", "design: base.yaml\ngrid:\n  thickness: [20, 40]\n");
  std::string out;
  REQUIRE(run_cli({"batch", (dir / "batch.yaml").string(), "-o", (dir / "out").string(), "-q"}, &out) == 0);
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir / "out")) {
    if (entry.path().extension() == ".step") files.push_back(entry.path());
  }
  REQUIRE(files.size() == 2);
  std::vector<double> volumes;
  for (const fs::path& f : files) {
    const StepRead r = read_step(read_file(f.string()));
    INFO(f << ": " << r.error);
    REQUIRE(r.roots.size() == 1);
    CHECK(r.roots[0].valid);
    CHECK(r.roots[0].closed);
    volumes.push_back(r.roots[0].volume);
  }
  std::sort(volumes.begin(), volumes.end());
  const double area = 1000.0 * 600.0 - M_PI * 200.0 * 150.0;
  CHECK(volumes[0] == Approx(20.0 * area).epsilon(1e-9));
  CHECK(volumes[1] == Approx(40.0 * area).epsilon(1e-9));
}

namespace {

// The solids of a STEP file as OpenCASCADE's reader gives them, each checked valid and closed.
std::vector<StepShapeFacts> solids_of(const std::string& step) {
  const StepRead r = read_step(step);
  INFO(r.error);
  REQUIRE(r.error.empty());
  std::vector<StepShapeFacts> solids;
  for (const StepShapeFacts& root : r.roots) {
    CHECK(root.valid);
    CHECK(root.closed);
    CHECK(root.solids == 1);
    solids.push_back(root);
  }
  return solids;
}

// Net volume of the keys on one split plane: bumps of radius r, sockets r + clearance.
double keys_volume(int keys, double radius, double clearance) {
  const double socket = radius + clearance;
  return keys * 2.0 / 3.0 * M_PI * (radius * radius * radius - socket * socket * socket);
}

}  // namespace

TEST_CASE("step: a mould's parts are exact solids with their keys, holding the exact plaster volume",
          "[pipeline][step][mould]") {
  const fs::path dir = fresh_dir("step_mould");
  const Written w = run_step(example("mould_golden.yaml"), dir, "mould_step");
  CHECK(w.item["files"][0]["path"].get<std::string>().find("mould_golden.mould.step") != std::string::npos);
  CHECK(w.item["files"][0]["units"] == "cm");
  CHECK(w.item["files"][0]["max_added_error"] == 0.0);  // quartic spans, lines, circles, spheres
  const std::vector<StepShapeFacts> parts = solids_of(w.step);
  REQUIRE(parts.size() == 2);

  // Each half: half the block less half the cavity (the cavity's revolution is
  // exact), its four sockets out and four bumps on: exact to OCCT's integration.
  const nlohmann::json& mould = w.item["build"]["mould"];
  const double block = mould["block_volume"].get<double>(), slip = mould["slip_volume"].get<double>();
  const double keys = keys_volume(4, 0.6, 0.02);
  for (const StepShapeFacts& part : parts)
    CHECK(part.volume == Approx((block - slip) / 2.0 + keys).epsilon(1e-7));
  // Each half: the block's sector (outside, top, bottom, two split faces), the
  // cavity's four profile spans, floor and reservoir wall, and a sphere per key.
  for (const StepShapeFacts& part : parts) CHECK(part.faces == 5 + 6 + 8);

  // The mesh's parts (STL in mm) lie on the solids (cm) within the mould's
  // proven deviation and float32's rounding.
  std::string out;
  const fs::path mesh_dir = fresh_dir("step_mould_mesh");
  REQUIRE(run_cli_json({"run", example("mould_golden.yaml"), "--export-format", "mould_stl", "-o",
                        mesh_dir.string() + "/", "--json"},
                       &out) == 0);
  const nlohmann::json item = only_item(out);
  REQUIRE(item["files"].size() == 2);
  std::vector<Vec3> points;
  double rounding = 0.0;
  for (const nlohmann::json& file : item["files"]) {
    const TriangleSoup mesh = read_mesh(file["path"].get<std::string>());
    for (std::size_t i = 0; i < mesh.vertices.size(); i += 17) points.push_back(mesh.vertices[i] / 10.0);
    rounding = std::max(rounding, file["max_added_error"].get<double>());
  }
  CHECK(max_distance_to_step(w.step, points) <=
        item["build"]["mould"]["max_deviation"].get<double>() + rounding + 1e-9);
}

TEST_CASE("step: a box mould with a base part, and a three-part mould, hold the exact plaster volume",
          "[pipeline][step][mould]") {
  struct Case {
    const char* design;
    std::size_t parts;
    int planes, keys, base_keys;
  };
  // The box: two side parts and a base, two keys on each of the two split
  // planes and one per side part on the base cut; three parts: three planes
  // of three keys.
  for (const Case& c :
       {Case{"mould_golden_box_base.yaml", 3, 2, 2, 2}, Case{"mould_p1_moved.yaml", 3, 3, 3, 0}}) {
    INFO(c.design);
    const Design design = read_design(example(c.design));
    const MouldOptions& options = *std::get<VesselDesign>(design.body).mould;
    const Written w = run_step(example(c.design), fresh_dir("step_mould_more"), "mould_step");
    const std::vector<StepShapeFacts> parts = solids_of(w.step);
    REQUIRE(parts.size() == c.parts);
    double volume = 0.0;
    for (const StepShapeFacts& part : parts) volume += part.volume;
    const nlohmann::json& mould = w.item["build"]["mould"];
    const double expected =
        mould["block_volume"].get<double>() - mould["slip_volume"].get<double>() +
        (c.planes * c.keys + c.base_keys) * keys_volume(1, options.key_radius, options.key_clearance);
    CHECK(volume == Approx(expected).epsilon(1e-7));
  }
}

TEST_CASE("step: a profile running along the axis between two parts gives one solid per part",
          "[pipeline][step]") {
  const fs::path dir = fresh_dir("step_two_parts");
  // Two double cones of radius 10 and height 20 on the axis, 10 apart.
  write_text(dir / "beads.yaml", R"(name: beads
kind: vessel
units: mm
tolerance: 0.05
profile:
  family: tbezier
  segments:
    - polyline: [[0, 0], [10, 10], [0, 20], [0, 30], [10, 40], [0, 50]]
body:
  mode: solid
)");
  const Written w = run_step((dir / "beads.yaml").string(), dir / "out");
  CHECK(w.item["files"][0]["max_added_error"] == 0.0);
  const std::vector<StepShapeFacts> parts = solids_of(w.step);
  REQUIRE(parts.size() == 2);
  for (const StepShapeFacts& part : parts)
    CHECK(part.volume == Approx(2.0 / 3.0 * M_PI * 1000.0).epsilon(1e-9));
  CHECK(w.step.find("'beads part 2'") != std::string::npos);
}

TEST_CASE("step: an open surface is one shell of B-spline faces, sewn along its shared borders",
          "[pipeline][step][surface]") {
  const fs::path dir = fresh_dir("step_surface");
  const Written w = run_step(example("surface_basin_open.yaml"), dir);
  CHECK(w.item["files"][0]["units"] == "mm");
  const double added = w.item["files"][0]["max_added_error"].get<double>();
  CHECK(added > 0.0);  // H-Bézier patches are not B-splines: approximated, proven
  CHECK(w.item["max_deviation"].get<double>() + added <= w.item["tolerance"].get<double>());

  const StepShapeFacts sheet = only_shape(w.step, "millimetre");
  INFO(sheet.problems);
  CHECK(sheet.valid);
  CHECK(sheet.solids == 0);
  CHECK(sheet.shells == 1);
  CHECK(sheet.faces == 4);  // one per patch
  CHECK_FALSE(sheet.closed);
  // Sewn: the 4 shared borders are one edge each, used by both faces; only
  // the rim's 8 sides (two per patch) are free.
  CHECK(sheet.edges == 12);
  CHECK(sheet.free_edges == 8);

  // The exact surface lies within the reported bound of the faces.
  const Design design = read_design(example("surface_basin_open.yaml"));
  const PatchNetwork network = build_patch_network(std::get<SurfaceDesign>(design.body).patches);
  std::vector<Vec3> points;
  for (const HBezierPatch& patch : network.patches) {
    for (int i = 0; i <= 16; ++i)
      for (int j = 0; j <= 16; ++j) points.push_back(patch.point(i / 16.0, j / 16.0));
  }
  CHECK(max_distance_to_step(w.step, points) <= added + 1e-9);

  // The viewing mesh lies on the faces within its deviation and the file's bound; the areas agree.
  const MeshRun mesh =
      mesh_run(example("surface_basin_open.yaml"), "stl", fresh_dir("step_surface_mesh"), 7, 1.0);
  CHECK(sheet.area == Approx(mesh.item["area"].get<double>()).epsilon(1e-3));
  CHECK(max_distance_to_step(w.step, mesh.points) <=
        mesh.item["max_deviation"].get<double>() + added +
            mesh.item["files"][0]["max_added_error"].get<double>() + 1e-9);
}

TEST_CASE("step: a thickened surface is one closed solid of B-spline faces within the reported bound",
          "[pipeline][step][surface]") {
  const fs::path dir = fresh_dir("step_surface_shell");
  const Written w = run_step(example("surface_basin_shell.yaml"), dir);
  const double added = w.item["files"][0]["max_added_error"].get<double>();
  const double deviation = w.item["max_deviation"].get<double>();
  // The offset sheet runs through the proven mesh's grid: its bound is the mesh's.
  CHECK(added >= deviation);
  CHECK(added <= w.item["tolerance"].get<double>());

  const StepShapeFacts solid = only_shape(w.step, "millimetre");
  INFO(solid.problems);
  CHECK(solid.valid);
  CHECK(solid.solids == 1);
  CHECK(solid.closed);
  CHECK(solid.free_edges == 0);
  CHECK(solid.faces == 16);  // 4 patches on each sheet, 8 walls along the rim's sides

  // The exact sheets (the surface and its offset along the exact unit
  // normal, as the report's span says) lie within the reported bound of the faces.
  const Design design = read_design(example("surface_basin_shell.yaml"));
  const PatchNetwork network = build_patch_network(std::get<SurfaceDesign>(design.body).patches);
  const double from = w.item["build"]["shell_span"][0].get<double>(),
               to = w.item["build"]["shell_span"][1].get<double>();
  std::vector<Vec3> points;
  for (const HBezierPatch& patch : network.patches) {
    for (int i = 0; i < 12; ++i) {
      for (int j = 0; j < 12; ++j) {
        const double s = (i + 0.5) / 12.0, t = (j + 0.5) / 12.0;
        for (const double offset : {from, to})
          points.push_back(patch.point(s, t) + offset * patch.normal(s, t));
      }
    }
  }
  CHECK(max_distance_to_step(w.step, points) <= added + 1e-9);

  // The mesh lies on the faces within its deviation and the file's bound;
  // the volumes differ by at most the area times both.
  const MeshRun mesh =
      mesh_run(example("surface_basin_shell.yaml"), "stl", fresh_dir("step_surface_shell_mesh"), 13, 1.0);
  const double both = deviation + added + mesh.item["files"][0]["max_added_error"].get<double>();
  CHECK(max_distance_to_step(w.step, mesh.points) <= both + 1e-9);
  const double volume = mesh.item["volume"].get<double>();
  INFO("STEP volume " << solid.volume << ", mesh volume " << volume);
  CHECK(std::abs(solid.volume - volume) <= mesh.item["area"].get<double>() * both);
  CHECK(solid.area == Approx(mesh.item["area"].get<double>()).epsilon(1e-2));
}

TEST_CASE("step: a centred shell has two offset sheets, each through the proven grid",
          "[pipeline][step][surface]") {
  const fs::path dir = fresh_dir("step_surface_centred");
  write_text(dir / "centred.yaml", R"(kind: surface
name: tray
units: mm
tolerance: 0.05
patches:
  - name: tray
    points:
      - [[0, 0, 0], [0, 30, 0], [0, 60, 0], [0, 90, 0]]
      - [[30, 0, 0], [30, 30, 12], [30, 60, 12], [30, 90, 0]]
      - [[60, 0, 0], [60, 30, 12], [60, 60, 12], [60, 90, 0]]
      - [[90, 0, 0], [90, 30, 0], [90, 60, 0], [90, 90, 0]]
thickness: 2
thicken: centered
)");
  const Written w = run_step((dir / "centred.yaml").string(), dir / "out");
  CHECK(w.item["build"]["shell_span"][0].get<double>() == -1.0);
  // Neither sheet is the surface: the file's bound is the mesh's own.
  CHECK(w.item["files"][0]["max_added_error"].get<double>() == w.item["max_deviation"].get<double>());
  const StepRead r = read_step(w.step);
  REQUIRE(r.roots.size() == 1);
  INFO(r.roots[0].problems);
  CHECK(r.roots[0].valid);
  CHECK(r.roots[0].closed);
  CHECK(r.roots[0].faces == 6);  // one patch: two sheets, four walls
  CHECK(r.roots[0].volume == Approx(w.item["volume"].get<double>()).epsilon(1e-3));
}

TEST_CASE("step: a patch with a side collapsed to a point is a face with a degenerate edge",
          "[pipeline][step][surface]") {
  const fs::path dir = fresh_dir("step_surface_pole");
  const std::string dome = R"(kind: surface
name: dome
tolerance: 0.01
purpose: view
patches:
  - name: quarter
    points:
      - [[0, 0, 10], [0, 0, 10], [0, 0, 10], [0, 0, 10]]
      - [[5, 0, 10], [5, 2.8, 10], [2.8, 5, 10], [0, 5, 10]]
      - [[10, 0, 5], [10, 5.5, 5], [5.5, 10, 5], [0, 10, 5]]
      - [[10, 0, 0], [10, 5.5, 0], [5.5, 10, 0], [0, 10, 0]]
)";
  write_text(dir / "dome.yaml", dome);
  const Written w = run_step((dir / "dome.yaml").string(), dir / "out");
  const double added = w.item["files"][0]["max_added_error"].get<double>();
  CHECK(added <= 0.01);
  const StepRead r = read_step(w.step);
  INFO(r.error);
  REQUIRE(r.roots.size() == 1);
  INFO(r.roots[0].problems);
  CHECK(r.roots[0].valid);
  CHECK(r.roots[0].shells == 1);
  CHECK(r.roots[0].faces == 1);
  CHECK(r.roots[0].edges == 4);       // the pole a degenerate edge
  CHECK(r.roots[0].free_edges == 3);  // the others the border
}

TEST_CASE("step: patches that do not make one shell are an output error, nothing written",
          "[pipeline][step][surface]") {
  // Two patches apart: each a face, but no border joins them.
  const fs::path dir = fresh_dir("step_surface_apart");
  const std::string apart = R"(kind: surface
name: apart
tolerance: 0.01
purpose: view
patches:
  - name: left
    points:
      - [[0, 0, 0], [0, 1, 0], [0, 2, 0], [0, 3, 0]]
      - [[1, 0, 0], [1, 1, 1], [1, 2, 1], [1, 3, 0]]
      - [[2, 0, 0], [2, 1, 1], [2, 2, 1], [2, 3, 0]]
      - [[3, 0, 0], [3, 1, 0], [3, 2, 0], [3, 3, 0]]
  - name: right
    points:
      - [[5, 0, 0], [5, 1, 0], [5, 2, 0], [5, 3, 0]]
      - [[6, 0, 0], [6, 1, 1], [6, 2, 1], [6, 3, 0]]
      - [[7, 0, 0], [7, 1, 1], [7, 2, 1], [7, 3, 0]]
      - [[8, 0, 0], [8, 1, 0], [8, 2, 0], [8, 3, 0]]
)";
  write_text(dir / "apart.yaml", apart);
  std::string out;
  CHECK(run_cli({"run", (dir / "apart.yaml").string(), "--export-format", "step", "-o",
                 (dir / "out").string() + "/"},
                &out) != 0);
  CHECK_THAT(out, Catch::Contains("make 2 pieces, not one shell"));
  CHECK_FALSE(fs::exists(dir / "out" / "apart.step"));
}

TEST_CASE("step: a profile that stops on a wall or a seam is cut exactly where the mesh stops it",
          "[pipeline][step][kitchen]") {
  // The U's rounded front corners run on tangentially into its side walls and its legs' inner edges
  // straight on into the seams; the L's leg's inner edge into the butt joint's seam. There the round
  // stops on a quarter turn, which OpenCASCADE's fillets (they follow a chain of tangent edges) cannot
  // make: the solid is the prism minus each exposed curve's swept section and the caps revolved at
  // the stops. Every vertex of the piece's mesh lies within the mesh's proven deviation of that
  // solid's faces (a cap or a sweep left out would leave the mesh's rolled corner millimetres inside
  // the square one), and the volumes agree within the deviation times the mesh's area. A round as tall
  // as the edge (a bullnose of half the thickness, its default; a half bullnose of all of it) stops
  // made smaller by a slack the file's added error states: within the deviation plus that.
  struct Case {
    const char* design;
    const char* edges;
  };
  for (const Case& k : {Case{"kitchen_u.yaml", "{exposed: half_bullnose, radius: 12}"},
                        Case{"kitchen_u.yaml", "{exposed: eased, radius: 3}"},
                        Case{"kitchen_l.yaml", "{exposed: bevel, radius: 6}"},
                        Case{"kitchen_l.yaml", "{exposed: bullnose, radius: 10}"},
                        Case{"kitchen_u.yaml", "{exposed: bullnose}"},
                        Case{"kitchen_u.yaml", "{exposed: half_bullnose, radius: 30}"}}) {
    INFO(k.design << " " << k.edges);
    const fs::path dir = fresh_dir("step_kitchen_profile");
    std::string out;
    const int code =
        run_cli_json({"run", example(k.design), "-o", dir.string() + "/", "--json", "-D",
                      std::string("edges=") + k.edges, "-D", "slab.spacing=40", "-D", "outputs=[step, obj]"},
                     &out);
    INFO(out);
    REQUIRE(code == 0);
    const nlohmann::json item = only_item(out);
    CHECK(item.at("skipped_outputs").empty());
    const double deviation = item["max_deviation"].get<double>();
    std::map<std::string, double> added;  // file name -> its stated added error
    for (const auto& file : item["files"]) {
      added[fs::path(file["path"].get<std::string>()).filename().string()] =
          file["max_added_error"].get<double>();
    }
    const bool full = std::string(k.edges).find("radius") == std::string::npos ||
                      std::string(k.edges).find("radius: 30") != std::string::npos;
    std::size_t pieces = 0;
    for (const auto& f : fs::directory_iterator(dir)) {
      if (f.path().extension() != ".step") continue;
      const double slack = added.at(f.path().filename().string());
      // Only where a round as tall as the edge stops, and then half the output's share of the tolerance.
      CHECK((slack > 0.0) == (full && f.path().filename().string() != "kitchen_u.piece-2.step"));
      CHECK(slack <= 0.5 * item["tolerance"].get<double>());
      const fs::path obj = fs::path(f.path()).replace_extension(".obj");
      INFO(f.path().filename().string());
      REQUIRE(fs::exists(obj));
      const std::string step = read_file(f.path().string());
      const StepShapeFacts solid = only_shape(step, "millimetre");
      CHECK(solid.valid);
      CHECK(solid.closed);
      CHECK(solid.solids == 1);
      const TriangleSoup mesh = read_mesh(obj.string());
      double area = 0.0;
      for (const auto& t : mesh.triangles) {
        area += 0.5 * (mesh.vertices[t[1]] - mesh.vertices[t[0]])
                          .cross(mesh.vertices[t[2]] - mesh.vertices[t[0]])
                          .norm();
      }
      CHECK(max_distance_to_step(step, mesh.vertices) <= deviation + slack + 1e-9);
      CHECK(std::abs(solid.volume - signed_volume(mesh)) <= (deviation + slack) * area);
      pieces += f.path().filename().string().find(".piece-") != std::string::npos ? 1 : 0;
    }
    CHECK(pieces >= 2);
  }
}

TEST_CASE("step: a spline in a piece whose round stops on a wall is skipped with the reason",
          "[pipeline][step][kitchen]") {
  // The asymmetric top as a one-piece kitchen with its straight back edge on a wall: the T-Bezier
  // corners run on tangentially into it (G1), and no exact stopped round is made along a spline. The
  // mesh is written; the STEP file is skipped, saying why.
  const fs::path dir = fresh_dir("step_kitchen_spline_stop");
  std::string text;
  const int code =
      run_cli({"run", example("countertop_asymmetric_line.yaml"), "-o", dir.string() + "/", "-D",
               "slab={length: 3000, width: 1400, spacing: 40}", "-D", "outline.segments[3].edge=wall", "-D",
               "edges={exposed: half_bullnose, radius: 10}", "-D", "outputs=[step, stl]"},
              &text);
  CHECK(code == 0);
  INFO(text);
  CHECK(text.find("is neither a line nor a circle arc") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "countertop_asymmetric_line.piece-1.step"));
  CHECK(fs::exists(dir / "countertop_asymmetric_line.piece-1.stl"));
}
