// A vessel's casting master: its outer solid as written (scaled for
// shrinkage) with the mould's spare on its rim, as a proven mesh (STL, 3MF)
// and an exact solid (STEP), the same shape as the mould's cavity.

#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include "io/design/read_design.h"
#include "io/file.h"
#include "io/mesh/read_mesh.h"
#include "io/step/step.h"
#include "tests/io/mesh/external_tool.h"
#include "tests/pipeline/cli_harness.h"

using namespace fabmesh;
using namespace fabmesh::testing;
namespace fs = std::filesystem;

namespace {

const Part& master_of(const Result& r) {
  const std::vector<const Part*> masters = parts_of(r, PartRole::Master);
  REQUIRE(masters.size() == 1);
  return *masters.front();
}

/// The solids of a STEP file as read back (each checked valid and closed): how many, and their volume.
struct StepSolids {
  std::size_t solids = 0;
  double volume = 0.0;
};

StepSolids step_solids(const StepRead& read) {
  StepSolids out;
  for (const StepShapeFacts& f : read.roots) {
    CHECK(f.valid);
    CHECK(f.closed);
    out.solids += static_cast<std::size_t>(f.solids);
    out.volume += f.volume;
  }
  return out;
}

}  // namespace

TEST_CASE("master: the vessel with the mould's spare, the cavity's shape and volume", "[pipeline][master]") {
  Design design = read_design(example("mould_golden.yaml"));  // cm, 12 % shrinkage, a 2.5 cm spare
  design.common.outputs = {{"mould_stl", "test", 0, 0},
                           {"master_stl", "test", 0, 0},
                           {"master_3mf", "test", 0, 0},
                           {"master_step", "test", 0, 0}};
  const fs::path dir = fresh_dir("master_golden");
  const Result r = run_job(design, into(dir));
  const Part& master = master_of(r);
  CHECK(master.name == "master");
  CHECK(master.validation.valid());
  CHECK(master.validation.genus == 0);
  const Facts& m = r.facts.group("master");
  const Facts& mould = r.facts.group("mould");
  CHECK(std::get<bool>(*m.find("spare")));
  // The master is what the slip fills: the cavity, vessel and spare, exactly.
  CHECK(m.number("volume") == Approx(mould.number("slip_volume")).epsilon(1e-12));
  // Its mesh holds that volume within its proven deviation over its area.
  CHECK(std::abs(master.validation.volume - m.number("volume")) <=
        m.number("max_deviation") * master.validation.area);
  // It stands on the vessel's base and reaches the spare's top: the vessel's height plus the spare.
  const auto& size = std::get<std::vector<double>>(*m.find("size"));
  const auto& vessel = std::get<std::vector<double>>(*r.facts.group("shrinkage").find("master_size"));
  CHECK(size[2] == Approx(vessel[2] + 2.5).epsilon(1e-12));
  // Every file written, each proven as stored, and the STL read back is the same closed solid.
  for (const char* file : {"mould_golden.master.stl", "mould_golden.master.3mf", "mould_golden.master.step"})
    CHECK(fs::exists(dir / file));
  for (const OutputFile& f : r.files) {
    if (f.format == "master_stl" || f.format == "master_3mf") {
      CHECK(f.valid_as_written == true);
      CHECK(f.parts == std::vector<std::string>{"master"});
    }
  }
  const TriangleSoup stl = read_mesh((dir / "mould_golden.master.stl").string());
  CHECK(stl.triangles.size() == master.mesh.triangles.size());
}

TEST_CASE("master: without a mould the vessel's outer solid, built only when asked for",
          "[pipeline][master]") {
  // A shell's master is solid: its outer profile closed to the axis, the same solid as the solid vessel.
  Design shell = read_design(example("vessel_golden_shell.yaml"));
  Design solid = read_design(example("vessel_golden_solid.yaml"));
  shell.common.outputs = {{"master_stl", "test", 0, 0}};
  solid.common.outputs = {{"stl", "test", 0, 0}};
  const Result a = run_job(shell, into(fresh_dir("master_shell")));
  const Result b = run_job(solid, into(fresh_dir("master_solid")));
  const Facts& m = a.facts.group("master");
  CHECK_FALSE(std::get<bool>(*m.find("spare")));
  CHECK(m.number("volume") == Approx(46.171424531125).epsilon(1e-10));  // the golden solid's, in cm^3
  CHECK(master_of(a).validation.volume == Approx(product(b)->validation.volume).epsilon(1e-4));
  // Not asked for, not built: no part, no facts.
  CHECK(parts_of(b, PartRole::Master).empty());
  CHECK_FALSE(b.facts.contains("master"));
}

TEST_CASE("master: one wider than the print bed is cut through its axis into halves or quarters that fit it",
          "[pipeline][master]") {
  const std::string path = example("mould_golden.yaml");  // the master is 5.9 cm across, 7.05 cm tall
  // A half stands 5.9 cm along its cut and 2.95 + 0.6 cm (its joint's pin) across it; a quarter 3.55 x 2.95.
  for (const auto& [bed, sectors] : {std::pair<std::string, int>{"[6.5, 4, 10]", 2}, {"[5, 5, 10]", 4}}) {
    INFO("bed " << bed);
    const std::string print = "{bed: " + bed + "}";
    Design design = parse_design(read_file(path), path, {{"print", print, "print=" + print}});
    design.common.outputs = {
        {"master_stl", "test", 0, 0}, {"master_3mf", "test", 0, 0}, {"master_step", "test", 0, 0}};
    const fs::path dir = fresh_dir("master_wide");
    const Result r = run_job(design, into(dir));
    const Facts& m = r.facts.group("master");
    CHECK_FALSE(std::get<bool>(*m.find("fits_bed")));
    CHECK(m.number("sectors") == sectors);
    const std::vector<const Part*> pieces = parts_of(r, PartRole::Master);
    REQUIRE(pieces.size() == static_cast<std::size_t>(sectors));
    const double bed_x = bed == "[5, 5, 10]" ? 50.0 : 65.0, bed_y = bed == "[5, 5, 10]" ? 50.0 : 40.0;
    double volume = 0.0;
    for (std::size_t k = 0; k < pieces.size(); ++k) {
      const Part& piece = *pieces[k];
      INFO(piece.name);
      CHECK(piece.name == fmt::format("{}-{}", sectors == 2 ? "half" : "quarter", k + 1));
      CHECK(piece.validation.valid());
      CHECK(piece.validation.genus == 0);
      CHECK(piece.validation.components == 1);
      CHECK(piece.validation.self_intersection == IntersectionCheck::Tested);  // not proven: tested in full
      // Standing upright as written (mm), turned about z if need be, it fits the bed.
      const TriangleSoup stl = read_mesh((dir / ("mould_golden.master." + piece.name + ".stl")).string());
      CHECK(stl.triangles.size() == piece.mesh.triangles.size());
      Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
      for (const Vec3& v : stl.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
      }
      const Vec3 size = hi - lo;
      CHECK(((size.x() <= bed_x && size.y() <= bed_y) || (size.y() <= bed_x && size.x() <= bed_y)));
      volume += piece.validation.volume;
    }
    // Together the master, plus each joint's pin (0.6 across and long) less its hole (0.64 across, 0.62
    // deep).
    const double joint = M_PI * (0.09 * 0.6 - 0.32 * 0.32 * 0.62);
    CHECK(volume == Approx(m.number("volume") + sectors * joint).epsilon(2e-3));
    // The pieces as assembled in the 3MF: touching at their cut faces, each pin in its hole, none
    // overlapping.
    std::string said;
    CHECK(run_cli({"check", (dir / "mould_golden.master.3mf").string()}, &said) == 0);
    CHECK_THAT(said, Catch::Contains(fmt::format("assembly: {} objects, none interpenetrating", sectors)));
    // The STEP: one exact solid per piece, together the master plus its joints' pins less their holes.
    const StepRead read = read_step(read_file((dir / "mould_golden.master.step").string()));
    REQUIRE(read.error.empty());
    const StepSolids pieces_read = step_solids(read);
    CHECK(pieces_read.solids == static_cast<std::size_t>(sectors));
    CHECK(pieces_read.volume == Approx(m.number("volume") + sectors * joint).epsilon(1e-7));
  }
}

TEST_CASE("master: one too wide even in quarters is said so, at print.bed", "[pipeline][master]") {
  const std::string path = example("mould_golden.yaml");  // a quarter is 3.55 x 2.95 cm with its pin
  Design design =
      parse_design(read_file(path), path, {{"print", "{bed: [3, 3, 10]}", "print={bed: [3, 3, 10]}"}});
  design.common.outputs = {{"master_stl", "test", 0, 0}};
  const Result r = run_job(design, into(fresh_dir("master_too_wide")));
  CHECK_FALSE(std::get<bool>(*r.facts.group("master").find("fits_bed")));
  REQUIRE_FALSE(r.warnings.empty());
  CHECK_THAT(r.warnings.back(), Catch::Contains("print.bed: the master (5.8997 cm across) is wider than the "
                                                "bed 3 x 3 cm even in quarters (each 3.54985 x 2.94985 cm"));
  CHECK(parts_of(r, PartRole::Master).size() == 1);
}

TEST_CASE("master: one taller than the print bed is cut into sections that fit it, joined by pins",
          "[pipeline][master]") {
  const std::string path = example("mould_golden.yaml");  // the master stands 7.05 cm with its spare
  Design design =
      parse_design(read_file(path), path, {{"print", "{bed: [22, 22, 6]}", "print={bed: [22, 22, 6]}"}});
  design.common.outputs = {{"master_stl", "test", 0, 0}, {"master_3mf", "test", 0, 0}};
  const fs::path dir = fresh_dir("master_bed");
  const Result r = run_job(design, into(dir));
  const Facts& m = r.facts.group("master");
  CHECK_FALSE(std::get<bool>(*m.find("fits_bed")));
  // The default pin, 6 mm (0.6 cm), rises 0.6 cm: sections of at most 5.4 cm, so two of 3.52 cm.
  const std::vector<const Part*> sections = parts_of(r, PartRole::Master);
  REQUIRE(sections.size() == 2);
  CHECK(sections[0]->name == "section-1");
  CHECK(sections[1]->name == "section-2");
  double volume = 0.0;
  for (const Part* s : sections) {
    INFO(s->name);
    CHECK(s->validation.valid());
    CHECK(s->validation.genus == 0);
    CHECK(s->validation.components == 1);
    const TriangleSoup stl = read_mesh((dir / ("mould_golden.master." + s->name + ".stl")).string());
    CHECK(stl.triangles.size() == s->mesh.triangles.size());
    double lo = 1e300, hi = -1e300;
    for (const Vec3& v : stl.vertices) {
      lo = std::min(lo, v.z());
      hi = std::max(hi, v.z());
    }
    CHECK(hi - lo <= 60.0 + 1e-4);  // mm: standing on its bottom, pin and all, within the bed's 6 cm
    volume += s->validation.volume;
  }
  // Together the master's volume, plus a pin and minus its hole (0.64 across, 0.62 deep) at the joint.
  const double pin = M_PI * 0.09 * 0.6, hole = M_PI * 0.32 * 0.32 * 0.62;
  CHECK(volume == Approx(m.number("volume") + pin - hole).epsilon(2e-3));
  CHECK_FALSE(fs::exists(dir / "mould_golden.master.stl"));
  CHECK(fs::exists(dir / "mould_golden.master.3mf"));
  // The report names the sections and their heights.
  const auto* listed = m.find("sections");
  REQUIRE(listed != nullptr);
  const Facts& pin_facts = m.group("pin");
  CHECK(pin_facts.number("diameter") == Approx(0.6));
  CHECK(pin_facts.number("hole_diameter") == Approx(0.64));
  CHECK(pin_facts.number("hole_depth") == Approx(0.62));
}

TEST_CASE("master sections: PrusaSlicer slices each to a top within the bed's height, unlike the whole",
          "[pipeline][master][prusaslicer]") {
  REQUIRE_PROGRAM("prusa-slicer");
  const fs::path dir = fresh_dir("master_sections_prusa");
  const std::string design = example("mould_golden.yaml");
  REQUIRE(run_cli({"run", design, "-D", "print={bed: [22, 22, 6]}", "-D", "outputs=[master_stl]", "-o",
                   (dir / "sections").string()}) == 0);
  REQUIRE(run_cli({"run", design, "-D", "outputs=[master_stl]", "-o", (dir / "whole").string()}) == 0);
  // The G-code's highest layer (its ";Z:" marks), in mm.
  const auto sliced_top = [&](const fs::path& stl, const std::string& name) {
    const fs::path gcode = dir / (name + ".gcode");
    const test::ToolRun slice =
        test::prusa_slicer((dir / "home").string(), "--export-gcode --bed-shape 0x0,220x0,220x220,0x220 " +
                                                        test::quoted(stl.string()) + " --output " +
                                                        test::quoted(gcode.string()));
    INFO(slice.output);
    REQUIRE(slice.code == 0);
    double top = 0.0;
    std::istringstream in(read_file(gcode.string()));
    for (std::string line; std::getline(in, line);) {
      if (line.rfind(";Z:", 0) == 0) top = std::max(top, std::stod(line.substr(3)));
    }
    return top;
  };
  for (const char* section : {"section-1", "section-2"}) {
    INFO(section);
    const fs::path stl = dir / "sections" / (std::string("mould_golden.master.") + section + ".stl");
    REQUIRE(fs::exists(stl));
    const double top = sliced_top(stl, section);
    CHECK(top > 35.0);   // half the master, 35.2 mm, the pin on the first
    CHECK(top <= 60.0);  // within the bed's 6 cm
  }
  CHECK(sliced_top(dir / "whole" / "mould_golden.master.stl", "whole") > 70.0);  // the master, 70.5 mm
  // Wider than a 50 x 50 mm bed: each quarter manifold, and sliced standing upright on that bed.
  REQUIRE(run_cli({"run", design, "-D", "print={bed: [5, 5, 10]}", "-D", "outputs=[master_stl]", "-o",
                   (dir / "quarters").string()}) == 0);
  for (int k = 1; k <= 4; ++k) {
    const fs::path stl = dir / "quarters" / fmt::format("mould_golden.master.quarter-{}.stl", k);
    INFO(stl);
    REQUIRE(fs::exists(stl));
    const std::map<std::string, std::string> info = test::prusa_info((dir / "home").string(), stl.string());
    REQUIRE(info.count("manifold") == 1);
    CHECK(info.at("manifold") == "yes");
    const fs::path gcode = dir / fmt::format("quarter-{}.gcode", k);
    const test::ToolRun slice =
        test::prusa_slicer((dir / "home").string(), "--export-gcode --bed-shape 0x0,50x0,50x50,0x50 " +
                                                        test::quoted(stl.string()) + " --output " +
                                                        test::quoted(gcode.string()));
    INFO(slice.output);
    CHECK(slice.code == 0);
    CHECK(fs::exists(gcode));
  }
}

TEST_CASE("master sections: a bed no taller than the pin is bad input at print.bed, nothing written",
          "[pipeline][master]") {
  const fs::path dir = fresh_dir("master_bed_pin");
  std::string said;
  CHECK(run_cli({"run", example("mould_golden.yaml"), "-D", "print={bed: [22, 22, 0.5]}", "-D",
                 "outputs=[master_stl]", "-o", (dir / "out").string()},
                &said) == 2);
  CHECK_THAT(said,
             Catch::Contains("-D print={bed: [22, 22, 0.5]}: print.bed: the bed's height 0.5 leaves no room "
                             "for a section under its registration pin (0.6 tall: pin_diameter)"));
  CHECK_FALSE(fs::exists(dir / "out"));
  // As narrow as the pin: no section could hold one beside it, however the
  // master is cut.
  CHECK(run_cli({"run", example("mould_golden.yaml"), "-D", "print={bed: [0.6, 0.6, 0.6]}", "-D",
                 "outputs=[master_stl]", "-o", (dir / "out").string()},
                &said) == 2);
  CHECK_THAT(said,
             Catch::Contains("-D print={bed: [0.6, 0.6, 0.6]}: print.bed: the bed's width 0.6 leaves no "
                             "room for a section beside its registration pin (0.6 across: "
                             "pin_diameter)"));
  CHECK_FALSE(fs::exists(dir / "out"));
}

TEST_CASE("master sections: the STEP holds each section as an exact solid, the master plus pins less holes",
          "[pipeline][master][step]") {
  const std::string path = example("mould_golden.yaml");
  Design design =
      parse_design(read_file(path), path, {{"print", "{bed: [22, 22, 6]}", "print={bed: [22, 22, 6]}"}});
  design.common.outputs = {{"master_step", "test", 0, 0}};
  const fs::path dir = fresh_dir("master_sections_step");
  const Result r = run_job(design, into(dir));
  const StepRead read = read_step(read_file((dir / "mould_golden.master.step").string()));
  REQUIRE(read.error.empty());
  CHECK(read.length_unit == "centimetre");
  const StepSolids sections = step_solids(read);
  CHECK(sections.solids == 2);
  // The pin 0.6 cm across and tall, its hole 0.64 across and 0.62 deep.
  const double joint = M_PI * (0.09 * 0.6 - 0.32 * 0.32 * 0.62);
  CHECK(sections.volume == Approx(r.facts.group("master").number("volume") + joint).epsilon(1e-7));
}

TEST_CASE("master sections: the vase example's set, its bed warning saying the master is cut to fit",
          "[pipeline][master]") {
  const fs::path dir = fresh_dir("master_vase_example");
  std::string said;
  REQUIRE(run_cli({"run", example("mould_vase_production.yaml"), "-o", dir.string()}, &said) == 0);
  // The vase itself (318 mm) is taller than the 220 mm bed; its master (343 mm with the spare) is cut.
  CHECK_THAT(said,
             Catch::Contains("does not fit the bed 220 x 220 x 220 mm; its casting master is cut into 2 "
                             "sections that fit it"));
  CHECK_THAT(said, Catch::Contains("master: cut for the bed into 2 sections (section-1 177.6 mm, section-2 "
                                   "171.6 mm tall as printed), a 6 mm pin on the axis at each joint into a "
                                   "6.4 mm hole"));
  // On a 150 mm bed each section is also cut through its axis, and the summary says how to glue them.
  REQUIRE(run_cli({"run", example("mould_vase_production.yaml"), "-D", "print.bed=[150, 150, 220]", "-D",
                   "outputs=[master_3mf]", "-o", (dir / "quarters").string()},
                  &said) == 0);
  CHECK_THAT(said, Catch::Contains("its casting master is cut into 8 pieces (2 sections, each in quarters) "
                                   "that fit it"));
  CHECK_THAT(said, Catch::Contains("master: cut for the bed into 8 pieces, 2 sections each in quarters "
                                   "(section-1 177.6 mm, section-2 171.6 mm tall as printed), a 6 mm pin "
                                   "across every joint into a 6.4 mm hole; glue each section's pieces "
                                   "together first, then stack the sections"));
  for (const char* f :
       {"mould_vase_production.master.section-1.stl", "mould_vase_production.master.section-2.stl",
        "mould_vase_production.master.3mf", "mould_vase_production.mould.3mf",
        "mould_vase_production.mould.step", "mould_vase_production.mould-base.stl"}) {
    CHECK(fs::exists(dir / f));
  }
}
