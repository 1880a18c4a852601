// A vessel's casting master: its outer solid as written (scaled for
// shrinkage) with the mould's spare on its rim, as a proven mesh (STL, 3MF)
// and an exact solid (STEP), the same shape as the mould's cavity.

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>

#include "io/design/read_design.h"
#include "io/file.h"
#include "io/mesh/read_mesh.h"
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

TEST_CASE("master: one larger than the print bed is said so, at print.bed", "[pipeline][master]") {
  const std::string path = example("mould_golden.yaml");  // the master stands 7.05 cm with its spare
  Design design =
      parse_design(read_file(path), path, {{"print", "{bed: [22, 22, 6]}", "print={bed: [22, 22, 6]}"}});
  design.common.outputs = {{"master_stl", "test", 0, 0}};
  const Result r = run_job(design, into(fresh_dir("master_bed")));
  CHECK_FALSE(std::get<bool>(*r.facts.group("master").find("fits_bed")));
  REQUIRE_FALSE(r.warnings.empty());
  CHECK(
      r.warnings.back().find("print.bed: the master (5.89853 cm across, 7.04545 cm tall with its spare) does "
                             "not fit the bed 22 x 22 x 6 cm") != std::string::npos);
  // The vessel alone (4.55 cm) fits: the print checks find nothing.
  CHECK(std::get<bool>(*r.facts.group("print").find("fits_bed")));
}
