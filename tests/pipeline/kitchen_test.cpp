// Kitchens: a countertop cut into pieces at seams, nested on slabs and cut
// one router program per slab; the programs run through the CNCjs
// interpreter and are measured against the placed pieces.

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "geometry/core/errors.h"
#include "geometry/mesh/weld.h"
#include "geometry/sampling/cut_loop.h"
#include "geometry/section/simple_polygon.h"
#include "geometry/validation/validate.h"
#include "io/design/read_design.h"
#include "io/file.h"
#include "io/mesh/stl.h"
#include "tests/io/cutting/drill_checks.h"
#include "tests/io/cutting/interpret.h"
#include "tests/io/mesh/external_tool.h"
#include "tests/pipeline/cli_harness.h"

using namespace fabmesh;
using namespace fabmesh::testing;
namespace fs = std::filesystem;

namespace {

double segment_distance(const Vec2& a, const Vec2& b, const Vec2& p) {
  const Vec2 d = b - a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (a + t * d - p).norm();
}

// Distance from p to a closed loop.
double loop_distance(const std::vector<Vec2>& loop, const Vec2& p) {
  double best = INFINITY;
  for (std::size_t k = 0; k < loop.size(); ++k)
    best = std::min(best, segment_distance(loop[k], loop[(k + 1) % loop.size()], p));
  return best;
}

// A placed piece: its outline and cut-outs in slab coordinates.
struct Placed {
  std::string name;
  std::vector<Vec2> outer;
  std::vector<std::vector<Vec2>> holes;
  double perimeter = 0.0;
};

std::vector<Placed> placed_on(const KitchenProducts& k, std::size_t slab) {
  std::vector<Placed> out;
  for (const Placement& p : k.nesting.placements) {
    if (p.slab != slab) continue;
    Placed q{k.split.pieces[p.piece].name, p.outer, {}, 0.0};
    for (const auto& h : k.split.pieces[p.piece].holes) q.holes.push_back(place_loop(h, p));
    for (std::size_t e = 0; e < q.outer.size(); ++e)
      q.perimeter += (q.outer[(e + 1) % q.outer.size()] - q.outer[e]).norm();
    out.push_back(std::move(q));
  }
  return out;
}

// Signed distance of the tool centre from a piece's material: < 0 inside it.
double from_material(const Placed& piece, const Vec2& c) {
  double d = loop_distance(piece.outer, c);
  for (const auto& h : piece.holes) d = std::min(d, loop_distance(h, c));
  bool inside = point_in_polygon(piece.outer, c) > 0;
  for (const auto& h : piece.holes) inside = inside && point_in_polygon(h, c) < 0;
  return inside ? -d : d;
}

// A design edit that must be bad input: `find` replaced by `replace` in an
// example, exit 2 naming `key` at its place and saying `says`, nothing written.
struct BadEdit {
  const char* find;
  const char* replace;
  const char* key;
  const char* says;
};

void check_bad_edits(const fs::path& dir, const std::string& example_name, const std::string& prefix,
                     const std::vector<BadEdit>& cases) {
  int n = 0;
  for (const BadEdit& c : cases) {
    const std::string name = fmt::format("{}{}.yaml", prefix, n++);
    const std::string path = edited_example(dir, example_name, c.find, c.replace, name);
    const fs::path out = dir / (name + "-out");
    std::string text;
    INFO(c.replace);
    CHECK(run_cli({"run", path, "-o", out.string() + "/"}, &text) == 2);
    INFO(text);
    CHECK(names_place(text, path, c.key));
    CHECK(text.find(c.says) != std::string::npos);
    CHECK((!fs::exists(out) || fs::is_empty(out)));
  }
}

// The L kitchen with a 12 mm half bullnose on its exposed edges, its pieces
// 40 apart (the profile bit, 12 mm with a 12 mm round, reaches 24 mm): the
// edited design's path in `dir`.
std::string profiled_kitchen_l(const fs::path& dir) {
  return edited_example(
      dir, "kitchen_l.yaml", "spacing: 14, grain: along}\nseams: auto",
      "spacing: 40, grain: along}\nseams: auto\nedges: {exposed: half_bullnose, radius: 12}",
      "profiled.yaml");
}

}  // namespace

TEST_CASE("kitchen: the L's pieces partition the top, each a valid slab, written one file each",
          "[pipeline][kitchen]") {
  const fs::path dir = fresh_dir("kitchen_l");
  const Design design = read_design(example("kitchen_l.yaml"));
  const Result r = run_job(design, into(dir));
  const Part* top = product(r);
  REQUIRE(top != nullptr);
  const std::vector<const Part*> parts = parts_of(r, PartRole::Piece);
  REQUIRE(parts.size() == 5);  // two pieces of the top, three backsplash strips
  const auto& pieces = std::get<CountertopProducts>(r.products).kitchen->split.pieces;
  double volume = 0.0;
  long genus = 0;
  for (const Part* p : parts) {
    INFO(p->name);
    CHECK(p->validation.valid());
    const bool strip = p->name.rfind("backsplash-", 0) == 0;
    // A piece keeps its cut-outs: the leg its cooktop, the run its sink and the tap hole behind it.
    const auto piece =
        std::find_if(pieces.begin(), pieces.end(), [&](const KitchenPiece& q) { return q.name == p->name; });
    REQUIRE(piece != pieces.end());
    CHECK(piece->holes.size() == (strip ? 0u : p->name == "piece-1" ? 1u : 2u));
    REQUIRE(p->validation.genus);
    CHECK(*p->validation.genus == static_cast<long>(piece->holes.size()));
    genus += *p->validation.genus;
    if (!strip) volume += p->validation.volume;
    // Its STL, read back, passes the full 3D validation.
    const std::string file = (dir / ("kitchen_l." + p->name + ".stl")).string();
    const ValidationReport full = validate(weld(parse_stl(read_file(file), "stl")).soup);
    CHECK(full.valid());
    CHECK(full.self_intersection == IntersectionCheck::Tested);
  }
  CHECK(std::abs(volume - top->validation.volume) <= 1e-9 * top->validation.volume);
  CHECK(genus == 3);  // the sink, the cooktop and the tap hole, each in one piece
  CHECK(top->validation.genus == std::optional<long>(3));
  const auto& k = *std::get<CountertopProducts>(r.products).kitchen;
  CHECK(k.nesting.slabs == 2);  // the strips do not fit beside the pieces
  CHECK(k.nesting.slabs >= k.nesting.lower_bound);
  CHECK(k.split.seams.size() == 1);
  // The whole top is not written: its pieces are.
  CHECK_FALSE(fs::exists(dir / "kitchen_l.stl"));
  // The cut list: a header and one line per piece; the walls and the seam.
  std::istringstream csv(read_file((dir / "kitchen_l.cutlist.csv").string()));
  std::string line;
  std::getline(csv, line);
  CHECK(line ==
        "piece,slab,x_mm,y_mm,rotation_deg,length_mm,width_mm,area_mm2,exposed_length_mm,wall_length_mm,"
        "seam_length_mm,cutouts");
  std::size_t rows = 0;
  while (std::getline(csv, line)) ++rows;
  REQUIRE(rows == 5);
  // The leg: 2400 of the left wall and 650 of the back wall; its front 2400 exposed; the seam 650.
  // The run: 2950 of the back wall; its front 2950 and its end 650 exposed; the seam 650.
  std::map<std::string, std::array<double, 3>> lengths;
  std::istringstream again(read_file((dir / "kitchen_l.cutlist.csv").string()));
  std::getline(again, line);
  while (std::getline(again, line)) {
    std::vector<std::string> cells;
    std::stringstream cell(line);
    for (std::string c; std::getline(cell, c, ',');) cells.push_back(c);
    REQUIRE(cells.size() >= 11);
    lengths[cells[0]] = {std::stod(cells[8]), std::stod(cells[9]), std::stod(cells[10])};
  }
  CHECK(lengths["piece-1"] == std::array<double, 3>{2400, 3050, 650});
  CHECK(lengths["piece-2"] == std::array<double, 3>{3600, 2950, 650});
  // A strip per straight wall run, as long as the run, standing on its bottom edge.
  CHECK(lengths["backsplash-1"] == std::array<double, 3>{2600, 0, 2400});
  CHECK(lengths["backsplash-2"] == std::array<double, 3>{850, 0, 650});
  CHECK(lengths["backsplash-3"] == std::array<double, 3>{3150, 0, 2950});
}

TEST_CASE("kitchen: each slab's program, run by CNCjs, cuts every piece through and nothing inside one",
          "[pipeline][kitchen]") {
  const fs::path dir = fresh_dir("kitchen_l_nc");
  const Design design = read_design(example("kitchen_l.yaml"));
  const Result r = run_job(design, into(dir));
  const auto& k = *std::get<CountertopProducts>(r.products).kitchen;
  REQUIRE(k.slab_toolpaths.size() == k.nesting.slabs);
  const CountertopDesign& top = std::get<CountertopDesign>(design.body);
  const CncOptions& cnc = top.cnc->options;
  const double radius = 0.5 * cnc.tool_diameter;
  std::size_t drilled = 0;
  for (std::size_t s = 0; s < k.nesting.slabs; ++s) {
    const std::string file = (dir / fmt::format("kitchen_l.slab-{}.nc", s + 1)).string();
    REQUIRE(fs::exists(file));
    const std::string problem = test::gcode_interpreter_problem();
    INFO(problem);
    REQUIRE(problem.empty());
    // The tap holes of the pieces on this slab, at their placed centres, drilled first with T2 (35 mm).
    const std::string program = read_file(file);
    std::vector<test::ExpectedDrill> holes;
    for (const Placement& p : k.nesting.placements) {
      if (p.slab != s) continue;
      for (const std::size_t h : k.split.pieces[p.piece].hole_index) {
        if (!top.holes[h].drill) continue;
        holes.push_back({place_point(top.holes[h].drill->center, p.rotation_deg, p.offset),
                         top.holes[h].drill->diameter, fmt::format("holes[{}]", h)});
      }
    }
    drilled += holes.size();
    test::DrillSpec spec;
    spec.thickness = top.thickness;
    spec.through = cnc.depth + cnc.breakthrough;
    spec.safe_z = cnc.safe_z;
    spec.feed = cnc.plunge;
    spec.rounding = k.slab_toolpaths[s].rounding_allowance;
    spec.tools = {{1, {ToolType::EndMill, 12}}, {2, {ToolType::Drill, 35}}};
    const test::CannedCycles cycles = test::read_canned_cycles(program);
    test::check_drilling(cycles, holes, spec);
    // A slab with no tap hole changes no tool: its program is as it was before tap holes.
    CHECK(cycles.changes.size() == (holes.empty() ? 0u : 2u));
    // The interpreter skips the cycles; the rest of the program is measured on its trace.
    const test::Trace trace =
        test::interpret_around_cycles(program, cycles, fmt::format("kitchen_l.slab-{}.nc", s + 1));
    const std::vector<Placed> pieces = placed_on(k, s);
    double lowest = 0.0;
    for (const test::TraceMotion& m : trace.motions) lowest = std::min({lowest, m.start.z(), m.end.z()});
    CHECK(lowest <= -(cnc.depth + cnc.breakthrough) + 1e-3);
    std::vector<double> through(pieces.size(), 0.0);  // length cut at full depth along each piece
    double closest = INFINITY;
    for (const test::TraceMotion& m : trace.motions) {
      if (std::min(m.start.z(), m.end.z()) >= 0.0) continue;  // above the slab
      const double length = test::motion_length(m);
      const int steps = std::max(1, static_cast<int>(std::ceil(length / 0.25)));
      for (int i = 0; i <= steps; ++i) {
        const Vec3 c = test::motion_point(m, static_cast<double>(i) / steps);
        for (std::size_t p = 0; p < pieces.size(); ++p) {
          // Between samples the centre moves at most 0.125: the margin below allows for it.
          const double d = from_material(pieces[p], c.head<2>());
          closest = std::min(closest, d);
          if (i > 0 && c.z() <= lowest + 1e-6 &&
              std::abs(loop_distance(pieces[p].outer, c.head<2>()) - radius) < 0.1)
            through[p] += length / steps;
        }
      }
    }
    // The tool's edge never enters a piece (the path keeps its proven clearance, less the sampling step).
    CHECK(closest >= radius - cnc.tolerance - 0.125);
    for (std::size_t p = 0; p < pieces.size(); ++p) {
      INFO(pieces[p].name);
      // Cut through all round but the tabs (two of 10 mm, plus the tool's width each).
      CHECK(through[p] >= pieces[p].perimeter - 2.0 * (10.0 + 2.0 * radius) - 1.0);
    }
  }
  CHECK(drilled == 1);  // the tap hole behind the sink, on the slab of its piece, once
  // The report says so per program, with the tools each uses.
  const auto& programs = std::get<std::vector<Facts>>(*r.facts.group("kitchen").find("programs"));
  REQUIRE(programs.size() == k.nesting.slabs);
  double reported = 0.0;
  for (std::size_t s = 0; s < programs.size(); ++s) {
    const double n = programs[s].number("drills");
    reported += n;
    CHECK(std::get<std::vector<Facts>>(*programs[s].find("tools")).size() == (n > 0 ? 2u : 1u));
  }
  CHECK(reported == 1.0);
}

TEST_CASE("kitchen: the U's given seams, a defect on the slabs, the layout and cut list",
          "[pipeline][kitchen]") {
  const fs::path dir = fresh_dir("kitchen_u");
  const Result r = run_job(read_design(example("kitchen_u.yaml")), into(dir));
  const auto& k = *std::get<CountertopProducts>(r.products).kitchen;
  CHECK(k.split.pieces.size() == 3);
  CHECK(k.split.seams.size() == 2);
  // Pieces 2600 x 620, 2960 x 620 and 2600 x 620 go two to a 1570-wide usable area at most.
  CHECK(k.nesting.slabs == 2);
  for (const Placement& p : k.nesting.placements) {
    for (const Vec2& v : p.outer) CHECK((v - Vec2(3100, 1500)).norm() >= 40.0 + 16.0);
  }
  double area = 0.0;
  for (const KitchenPiece& p : k.split.pieces) area += p.area;
  CHECK(std::abs(area - product(r)->validation.volume / 30.0) <= 1e-6 * area);
  const std::string svg = read_file((dir / "kitchen_u.layout.svg").string());
  CHECK(svg.find("id=\"slab-2\"") != std::string::npos);
  CHECK(svg.find("class=\"defect\"") != std::string::npos);
  for (const char* piece : {"piece-1", "piece-2", "piece-3"})
    CHECK(svg.find(fmt::format("id=\"{}\"", piece)) != std::string::npos);
}

TEST_CASE("kitchen: the same design writes the same bytes", "[pipeline][kitchen]") {
  const fs::path a = fresh_dir("kitchen_same_a"), b = fresh_dir("kitchen_same_b");
  const Design design = read_design(example("kitchen_l.yaml"));
  const Result ra = run_job(design, into(a));
  const Result rb = run_job(design, into(b));
  REQUIRE(ra.files.size() == rb.files.size());
  for (const OutputFile& f : ra.files) {
    const std::string name = fs::path(f.path).filename().string();
    INFO(name);
    CHECK(read_file(f.path) == read_file((b / name).string()));
  }
}

TEST_CASE("kitchen bad input: exit 2 naming the key, nothing written", "[pipeline][kitchen]") {
  const fs::path dir = fresh_dir("kitchen_bad");
  const std::vector<BadEdit> cases = {
      {"\nseams: auto", "\nseams: [{at: [1900, 0], direction: [0, 1]}]", "seams[0]", "runs through holes[0]"},
      {"\nseams: auto",
       "\nseams: [{at: [650, 650], direction: [0, -1]}, {at: [650, 300], direction: [0, 1]}]", "seams[1].at",
       "not on the top"},
      {"slab: {length: 3000, width: 1400,", "slab: {length: 700, width: 400,", "holes[0]",
       "cannot fit a slab"},
      {"grain: along}", "grain: along, defects: [{circle: {center: [1500, 700], radius: 2000}}]}", "slab",
       "piece-"},
      {"spacing: 14", "spacing: 8", "slab.spacing", "router bit"},
      {"margin: 10", "margin: 700", "slab.margin", "no usable area"},
      {"backsplash: {height: 100}", "backsplash: {height: 0}", "backsplash.height", "must be > 0"},
      {"slab: {length: 3000, width: 1400, margin: 10, spacing: 14, grain: along}\nseams: auto\nbacksplash: "
       "{height: 100}\n",
       "", "outline.segments[0].edge", "needs a slab"},
      {"\nseams: auto", "\nseams: auto\nedges: {exposed: bullnose, radius: 16}", "edges.radius",
       "at most 15 for a bullnose edge"},
      {"\nseams: auto", "\nseams: auto\nedges: {exposed: ogee}", "edges.exposed", "ogee"},
      {"\nseams: auto", "\nseams: auto\nedges: {exposed: square, radius: 3}", "edges.radius", "no radius"},
      {"\nseams: auto", "\nseams: auto\nedges: {radius: 3}", "edges", "exposed"},
      {"\nseams: auto", "\nseams: auto\nedges: {exposed: eased}\nmax_edge: 50", "max_edge", "not refined"},
      {"\nseams: auto", "\nseams: auto\nedges: {exposed: half_bullnose, radius: 12}", "slab.spacing",
       "space the pieces at least"},
      {"\nseams: auto", "\nseams: auto\nedges: {exposed: half_bullnose, radius: 28}", "edges.radius",
       "through the holding tabs"},
      // A 1500 mm leg brings the cooktop within 80 mm of the inside corner: no butt joint clears it,
      // and the router without dog-bones cannot cut the L-shaped piece any other seams leave.
      {"leg: {value: 2400,", "leg: {value: 1500,", "seams", "set cnc.relief: dogbone"},
  };
  check_bad_edits(dir, "kitchen_l.yaml", "bad", cases);
}

TEST_CASE("kitchen: each piece's exact DXF passes ezdxf's audit and keeps its arcs", "[pipeline][kitchen]") {
  const fs::path dir = fresh_dir("kitchen_u_dxf");
  Design design = read_design(example("kitchen_u.yaml"));
  design.common.outputs = {{"dxf", "test", 0, 0}, {"svg", "test", 0, 0}};
  const Result r = run_job(design, into(dir));
  REQUIRE(r.files.size() == 6);  // three pieces, two drawings each
  const std::string script =
      "import sys, ezdxf\n"
      "doc = ezdxf.readfile(sys.argv[1])\n"
      "a = doc.audit()\n"
      "m = doc.modelspace()\n"
      "print(len(a.errors), len(a.fixes), len(m.query(\"ARC\")), len(m.query(\"LINE\")))\n";
  int arcs_total = 0;
  for (int piece = 1; piece <= 3; ++piece) {
    const std::string path = (dir / fmt::format("kitchen_u.piece-{}.dxf", piece)).string();
    INFO(path);
    const test::ToolRun run = test::run_tool("/usr/bin/python3 -c '" + script + "' " + path);
    REQUIRE(run.code == 0);
    INFO(run.output);
    std::istringstream out(run.output);
    int errors = -1, fixes = -1, arcs = -1, lines = -1;
    out >> errors >> fixes >> arcs >> lines;
    CHECK(errors == 0);
    CHECK(fixes == 0);
    CHECK(lines >= 4);
    arcs_total += arcs;
    CHECK(fs::exists(dir / fmt::format("kitchen_u.piece-{}.svg", piece)));
  }
  // The outline's four 50 mm corner arcs, the sink's and the cooktop's four each, all exact.
  CHECK(arcs_total == 12);
}

TEST_CASE("kitchen: edge: wall belongs to a countertop's outline only", "[pipeline][kitchen]") {
  const std::string curve =
      "name: c\nkind: curve\ncurve:\n  family: tbezier\n  segments:\n"
      "    - line: {from: [0, 0], to: [10, 0]}\n      edge: wall\n";
  try {
    parse_design(curve, "c.yaml");
    FAIL("edge: wall on a curve design was accepted");
  } catch (const InputError& e) {
    INFO(e.what());
    CHECK(e.location().key == "curve.segments[0].edge");
    CHECK(std::string(e.what()).find("countertop's outline") != std::string::npos);
  }
}

namespace {

// What ezdxf reads in a DXF drawing (tests/pipeline/dxf_sheet_dump.py).
nlohmann::json ezdxf_dump(const std::string& path) {
  const std::string script = std::string(FABMESH_SOURCE_DIR) + "/tests/pipeline/dxf_sheet_dump.py";
  const test::ToolRun run = test::run_tool("/usr/bin/python3 " + script + " " + path);
  INFO(run.output);
  REQUIRE(run.code == 0);
  return nlohmann::json::parse(run.output);
}

// The scale (paper mm per model unit, units mm) at which the box lo..hi
// fits A3 less a 10 mm border, upright or turned.
double a3_scale(const nlohmann::json& lo, const nlohmann::json& hi) {
  const double w = hi[0].get<double>() - lo[0].get<double>(), h = hi[1].get<double>() - lo[1].get<double>();
  return std::max(std::min(400.0 / w, 277.0 / h), std::min(277.0 / w, 400.0 / h));
}

// The exact box of a loop.
std::array<double, 2> exact_size(const CutLoop& loop) {
  const auto [lo, hi] = cut_bounds({loop});
  return {hi.x() - lo.x(), hi.y() - lo.y()};
}

// Whether `dims` holds a dimension measuring `value` along x (angle 0) or y (90).
bool measured(const nlohmann::json& dims, double value, double angle) {
  for (const auto& d : dims) {
    if (d["angle"].get<double>() == angle && std::abs(d["measurement"].get<double>() - value) <= 1e-6 * value)
      return true;
  }
  return false;
}

}  // namespace

TEST_CASE("kitchen: the shop drawing's DIMENSION entities measure the exact pieces, readable on A3",
          "[pipeline][kitchen]") {
  for (const char* name : {"kitchen_l", "kitchen_u"}) {
    INFO(name);
    const fs::path dir = fresh_dir(std::string(name) + "_shop");
    Design design = read_design(example(std::string(name) + ".yaml"));
    design.common.outputs = {{"shop_dxf", "test", 0, 0}, {"shop_svg", "test", 0, 0}};
    const Result r = run_job(design, into(dir));
    const auto& k = *std::get<CountertopProducts>(r.products).kitchen;
    const nlohmann::json dxf = ezdxf_dump((dir / (std::string(name) + ".shop.dxf")).string());
    CHECK(dxf["errors"].empty());
    CHECK(dxf["fixes"].empty());
    const nlohmann::json& dims = dxf["dimensions"];
    std::size_t least = 0;  // two per piece and four per cut-out; seams besides
    for (std::size_t i = 0; i < k.split.pieces.size(); ++i) {
      const KitchenPiece& piece = k.split.pieces[i];
      INFO(piece.name);
      REQUIRE(k.exact[i].solid);
      const std::vector<CutLoop>& loops = k.exact[i].drawing;
      REQUIRE(loops.size() == piece.holes.size() + 1);
      const auto size = exact_size(loops.front());
      CHECK(measured(dims, size[0], 0.0));
      CHECK(measured(dims, size[1], 90.0));
      for (std::size_t h = 1; h < loops.size(); ++h) {
        const auto hole = exact_size(loops[h]);
        CHECK(measured(dims, hole[0], 0.0));
        CHECK(measured(dims, hole[1], 90.0));
      }
      least += 2 + 4 * piece.holes.size();
      bool labelled = false;
      for (const auto& t : dxf["texts"])
        labelled = labelled || t["text"].get<std::string>().rfind(piece.name + " (", 0) == 0;
      CHECK(labelled);
    }
    CHECK(dims.size() >= least);
    for (const auto& d : dims) {
      CHECK(d["layer"] == "DIMENSIONS");
      CHECK(d["block"].get<bool>());
      CHECK(d["measurement"].get<double>() > 0.0);
    }
    // Every text, a dimension's too, prints at 2.5 mm or more when the whole
    // drawing is scaled to A3 (the unit is mm).
    const double scale = a3_scale(dxf["lo"], dxf["hi"]);
    CHECK(dxf["dimstyle_text"].get<double>() * scale >= 2.5);
    for (const auto& t : dxf["texts"]) CHECK(t["height"].get<double>() * scale >= 2.5);
    // The SVG draws the same dimensions.
    const std::string svg = read_file((dir / (std::string(name) + ".shop.svg")).string());
    std::size_t drawn = 0;
    for (std::size_t at = svg.find("class=\"dimension\""); at != std::string::npos;
         at = svg.find("class=\"dimension\"", at + 1))
      ++drawn;
    CHECK(drawn == dims.size());
  }
}

TEST_CASE("kitchen: the layout DXF holds every piece, exact, inside its slab's usable area",
          "[pipeline][kitchen]") {
  const fs::path dir = fresh_dir("kitchen_u_layout_dxf");
  Design design = read_design(example("kitchen_u.yaml"));
  design.common.outputs = {{"layout_dxf", "test", 0, 0}};
  const Result r = run_job(design, into(dir));
  const auto& k = *std::get<CountertopProducts>(r.products).kitchen;
  const nlohmann::json dxf = ezdxf_dump((dir / "kitchen_u.layout.dxf").string());
  CHECK(dxf["errors"].empty());
  CHECK(dxf["fixes"].empty());
  const SlabStock& stock = k.stock;
  const double step = 1.1 * stock.width;  // slab s lies (slabs - 1 - s) steps up
  std::map<std::string, int> per_layer;
  for (const auto& b : dxf["boxes"]) {
    const std::string layer = b["layer"];
    ++per_layer[layer];
    if (layer != "PIECES") continue;
    const double lx = b["lo"][0], ly = b["lo"][1], hx = b["hi"][0], hy = b["hi"][1];
    const double s = std::floor(ly / step);  // the slab band it lies in
    const double y0 = s * step;
    CHECK(lx >= stock.margin - 1e-6);
    CHECK(hx <= stock.length - stock.margin + 1e-6);
    CHECK(ly >= y0 + stock.margin - 1e-6);
    CHECK(hy <= y0 + stock.width - stock.margin + 1e-6);
  }
  // The arcs stay arcs: the outline's four corners and each cut-out's four.
  std::size_t arcs = 0;
  for (const auto& b : dxf["boxes"]) arcs += b["layer"] == "PIECES" && b["type"] == "ARC" ? 1 : 0;
  CHECK(arcs == 12);
  CHECK(per_layer["SLABS"] == static_cast<int>(k.nesting.slabs));
  CHECK(per_layer["MARGINS"] == static_cast<int>(k.nesting.slabs));
  CHECK(per_layer["DEFECTS"] == static_cast<int>(k.nesting.slabs * stock.defects.size()));
  for (const KitchenPiece& piece : k.split.pieces) {
    int labels = 0;
    for (const auto& t : dxf["texts"])
      labels += t["text"].get<std::string>().rfind(piece.name + " (", 0) == 0 ? 1 : 0;
    CHECK(labels == 1);
  }
}

TEST_CASE("kitchen: walls from the template's WALLS layer mark the pieces' edges", "[pipeline][kitchen]") {
  // The U's outline comes from kitchen_u_template.dxf, its left, back and right walls as LINEs on WALLS.
  const Result r = run_job(read_design(example("kitchen_u.yaml")), into(fresh_dir("kitchen_u_walls")));
  const auto& k = *std::get<CountertopProducts>(r.products).kitchen;
  REQUIRE(k.split.pieces.size() == 3);
  // Each leg: its wall (2600 less the 50 mm corner arc) and the back wall's 620; the run: 2960 of back wall.
  const std::array<double, 3> walls{2550.0 + 620.0, 2960.0, 2550.0 + 620.0};
  for (std::size_t i = 0; i < 3; ++i) {
    INFO(k.split.pieces[i].name);
    CHECK(edge_lengths(k.split.pieces[i])[1] == Approx(walls[i]).epsilon(1e-12));
  }

  const fs::path dir = fresh_dir("kitchen_walls_bad");
  fs::copy_file(example("kitchen_u_template.dxf"), dir / "kitchen_u_template.dxf");
  // A wall line off the outline: the template with one more line on WALLS.
  std::string dxf = read_file(example("kitchen_u_template.dxf"));
  const std::string entities = "ENTITIES\n";
  dxf.insert(dxf.find(entities) + entities.size(),
             "  0\nLINE\n  5\nFFF0\n  8\nWALLS\n 10\n1000.0\n 20\n1000.0\n 30\n0.0\n 11\n1500.0\n "
             "21\n1000.0\n 31\n0.0\n");
  write_file_atomically((dir / "stray_wall.dxf").string(), dxf);
  const std::vector<BadEdit> cases = {
      {"layer: OUTLINE}", "layer: OUTLINE, walls: NOPE}", "outline.dxf", "layer NOPE: no LINE"},
      {"kitchen_u_template.dxf, layer: OUTLINE}", "stray_wall.dxf, layer: OUTLINE}", "outline.dxf",
       "LINE #FFF0 from (1000, 1000) to (1500, 1000) lies on no line of the outline"},
      {"layer: OUTLINE}", "layer: OUTLINE, walls: OUTLINE}", "outline.dxf", "walls are straight"},
      {"holes:\n", "holes:\n  - outline: {dxf: kitchen_u_template.dxf, layer: OUTLINE, walls: WALLS}\n",
       "holes[0].outline.walls", "not of a cut-out"},
  };
  check_bad_edits(dir, "kitchen_u.yaml", "walls", cases);
  for (std::size_t i = 0; i < cases.size(); ++i) CHECK(!fs::exists(dir / fmt::format("walls{}.yaml-out", i)));
  // `walls` marks a kitchen's edges: not without a slab.
  const std::string top = read_file(example("kitchen_u.yaml"));
  const std::string plain = top.substr(0, top.find("slab:")) + "outputs: [stl]\n";
  std::string text = plain;
  text.replace(text.find("layer: OUTLINE}"), 15, "layer: OUTLINE, walls: WALLS}");
  write_file_atomically((dir / "plain.yaml").string(), text);
  std::string said;
  CHECK(run_cli({"run", (dir / "plain.yaml").string(), "-o", (dir / "plain-out").string() + "/"}, &said) ==
        2);
  INFO(said);
  CHECK(names_place(said, (dir / "plain.yaml").string(), "outline.walls"));
  CHECK(said.find("needs a slab") != std::string::npos);
  // Without a slab the template's WALLS layer is not read: the plain top builds.
  const std::string path = (dir / "plain_ok.yaml").string();
  write_file_atomically(path, plain);
  std::string out;
  CHECK(run_cli({"run", path, "-o", (dir / "plain-ok-out").string() + "/"}, &out) == 0);
}

TEST_CASE("kitchen: profiled front edges on every piece, square on walls and seams", "[pipeline][kitchen]") {
  const fs::path dir = fresh_dir("kitchen_profile");
  const std::string path = profiled_kitchen_l(dir);
  const Design design = read_design(path);
  const Result r = run_job(design, into(dir));
  const Part* top = product(r);
  REQUIRE(top != nullptr);
  CHECK(top->validation.valid());
  const auto& k = *std::get<CountertopProducts>(r.products).kitchen;
  for (const Part* p : parts_of(r, PartRole::Piece)) {
    INFO(p->name);
    const bool strip = p->name.rfind("backsplash-", 0) == 0;
    // Validated in full: a profiled piece has no construction proof.
    CHECK(p->validation.valid());
    CHECK(p->validation.self_intersection ==
          (strip ? IntersectionCheck::ProvenByConstruction : IntersectionCheck::Tested));
    const auto piece = std::find_if(k.split.pieces.begin(), k.split.pieces.end(),
                                    [&](const KitchenPiece& q) { return q.name == p->name; });
    REQUIRE(piece != k.split.pieces.end());
    const std::array<double, 3> lengths = edge_lengths(*piece);
    const double slab_volume = piece->area * 30.0;
    const ProfileMoments m = profile_moments({EdgeProfileKind::HalfBullnose, 12.0}, 30.0);
    if (strip) {
      CHECK(p->validation.volume == Approx(slab_volume).epsilon(1e-12));  // the strips stay square
      continue;
    }
    // Each exposed edge loses about its length times the profile's area (corners aside).
    const double lost = slab_volume - p->validation.volume;
    CHECK(lost > 0.9 * lengths[0] * m.area);
    CHECK(lost < 1.1 * lengths[0] * m.area);
  }
  CHECK(r.facts.contains("edges"));
}

TEST_CASE(
    "kitchen: the profile bit runs along every exposed edge, not along walls or seams, nor into a piece",
    "[pipeline][kitchen]") {
  const fs::path dir = fresh_dir("kitchen_profile_nc");
  const std::string path = profiled_kitchen_l(dir);
  const Design design = read_design(path);
  const Result r = run_job(design, into(dir));
  const auto& k = *std::get<CountertopProducts>(r.products).kitchen;
  const CncOptions& cnc = std::get<CountertopDesign>(design.body).cnc->options;
  const double radius = 0.5 * cnc.tool_diameter;  // the profile bit's tip: the end mill's diameter
  double exposed_total = 0.0, exposed_run = 0.0, other_run = 0.0;
  std::size_t runs = 0, slabs_with_tops = 0;
  for (std::size_t s = 0; s < k.nesting.slabs; ++s) {
    const std::string program = read_file((dir / fmt::format("kitchen_l.slab-{}.nc", s + 1)).string());
    // After the routing: M6 T3 (the end mill is T1, the tap hole's drill T2), then the passes; a
    // slab of backsplash strips only (cut square) has none.
    bool tops = false;
    for (const Placement& p : k.nesting.placements)
      tops = tops || (p.slab == s && !k.split.pieces[p.piece].strip);
    const std::size_t change = program.find("M6 T3");
    CHECK((change != std::string::npos) == tops);
    if (!tops) continue;
    ++slabs_with_tops;
    CHECK(program.find("(profiling: T3, the profile bit 12 mm: half_bullnose, radius 12") !=
          std::string::npos);
    CHECK(program.rfind("M6 T1") < change);
    const test::CannedCycles cycles = test::read_canned_cycles(program);
    const test::Trace trace =
        test::interpret_around_cycles(program, cycles, fmt::format("profiled-{}.nc", s + 1));
    const std::vector<Placed> pieces = placed_on(k, s);
    std::map<std::string, const KitchenPiece*> by_name;
    for (const KitchenPiece& piece : k.split.pieces) by_name[piece.name] = &piece;
    for (const Placed& p : pieces) {
      for (std::size_t e = 0; e < p.outer.size(); ++e) {
        if (by_name.at(p.name)->edges[e] == EdgeKind::Exposed && !by_name.at(p.name)->strip)
          exposed_total += (p.outer[(e + 1) % p.outer.size()] - p.outer[e]).norm();
      }
    }
    const int profiling_from =
        static_cast<int>(std::count(program.begin(), program.begin() + change, '\n')) + 1;
    for (const test::TraceMotion& m : trace.motions) {
      if (m.line <= profiling_from) continue;
      if (std::abs(m.start.z() + 12.0) > 1e-3 || std::abs(m.end.z() + 12.0) > 1e-3) continue;
      if (m.motion != "G1") continue;
      runs += 1;
      const double length = test::motion_length(m);
      const int steps = std::max(1, static_cast<int>(std::ceil(length / 0.5)));
      for (int i = 0; i < steps; ++i) {
        const Vec3 c = test::motion_point(m, (i + 0.5) / steps);
        for (const Placed& p : pieces) {
          // The bit's tip never enters a piece.
          CHECK(from_material(p, c.head<2>()) >= radius - cnc.tolerance - 0.01);
          if (std::abs(loop_distance(p.outer, c.head<2>()) - radius) > 0.05) continue;
          // Which edge it runs along: the nearest.
          std::size_t nearest = 0;
          double best = INFINITY;
          for (std::size_t e = 0; e < p.outer.size(); ++e) {
            const double d = segment_distance(p.outer[e], p.outer[(e + 1) % p.outer.size()], c.head<2>());
            if (d < best) best = d, nearest = e;
          }
          (by_name.at(p.name)->edges[nearest] == EdgeKind::Exposed ? exposed_run : other_run) +=
              length / steps;
        }
      }
    }
  }
  INFO("exposed " << exposed_total << ", profiled along exposed " << exposed_run << ", along walls and seams "
                  << other_run);
  CHECK(runs > 0);
  // Along every exposed edge (the convex corners' arcs add a little), and not along walls or seams.
  CHECK(exposed_run >= exposed_total - 1.0);
  CHECK(other_run <= 1.0);
  // The report lists the profile bit with each program that profiles.
  const auto& programs = std::get<std::vector<Facts>>(*r.facts.group("kitchen").find("programs"));
  std::size_t profiling = 0;
  for (const Facts& p : programs) {
    const auto& tools = std::get<std::vector<Facts>>(*p.find("tools"));
    profiling +=
        std::count_if(tools.begin(), tools.end(), [](const Facts& t) { return t.text("type") == "profile"; });
  }
  CHECK(profiling == slabs_with_tops);
}
