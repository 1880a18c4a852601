// What a potter weighs for a slip-casting mould: plaster and water by weight
// for the mould and each part, the slip to fill it, and shrinkage measured on
// a test bar.

#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "geometry/core/errors.h"
#include "io/design/read_design.h"
#include "io/file.h"
#include "pipeline/summary.h"
#include "tests/pipeline/cli_harness.h"

using namespace fabmesh;
using namespace fabmesh::testing;
namespace fs = std::filesystem;

TEST_CASE("casting: plaster, water and slip by weight, for the mould and each part", "[pipeline][mould]") {
  Design design = read_design(example("mould_golden.yaml"));  // cm
  design.common.outputs = {{"mould_stl", "test", 0, 0}};
  const Result r = run_job(design, into(fresh_dir("casting_golden")));
  const Facts& m = r.facts.group("mould");
  CHECK(m.number("plaster_ratio") == 1.4);
  CHECK(m.number("plaster_density") == 2.63);
  CHECK(m.number("slip_density") == 1.75);
  // cm^3 are ml: P = V / (1 / 2.63 + 1 / 1.4), water P / 1.4.
  const double v = m.number("plaster_volume");
  const double plaster = v / (1.0 / 2.63 + 1.0 / 1.4);
  CHECK(m.number("plaster_grams") == Approx(plaster).epsilon(1e-14));
  CHECK(m.number("water_grams") == Approx(plaster / 1.4).epsilon(1e-14));
  // Set plaster weighs plaster and water together: between the water's and the plaster's densities.
  CHECK(m.number("plaster_grams") + m.number("water_grams") > v);
  CHECK(m.number("plaster_grams") + m.number("water_grams") < 2.63 * v);
  CHECK(m.number("slip_millilitres") == m.number("slip_volume"));
  CHECK(m.number("slip_grams") == Approx(1.75 * m.number("slip_volume")).epsilon(1e-14));
  // The parts' plaster adds up to the whole mould's, within their meshes' deviation from the exact parts.
  double parts_plaster = 0.0;
  for (const Facts& part : std::get<std::vector<Facts>>(*m.find("parts"))) {
    CHECK(part.number("water_grams") == Approx(part.number("plaster_grams") / 1.4).epsilon(1e-14));
    parts_plaster += part.number("plaster_grams");
  }
  CHECK(parts_plaster == Approx(plaster).epsilon(1e-3));
  std::ostringstream out;
  print_summary(r, out);
  const std::string summary = out.str();
  CHECK(summary.find(fmt::format("casting: {:.0f} g of plaster into {:.0f} g of water (1.4 : 1 by weight)",
                                 plaster, plaster / 1.4)) != std::string::npos);
}

TEST_CASE("casting: the design's own mix and slip", "[pipeline][mould]") {
  Design cm = read_design(example("mould_golden.yaml"));
  Design dense = parse_design(read_file(example("mould_golden.yaml")), example("mould_golden.yaml"),
                              {{"mould.plaster_ratio", "1.25", "mould.plaster_ratio=1.25"},
                               {"mould.slip_density", "1.8", "mould.slip_density=1.8"}});
  REQUIRE(dense.common.units == "cm");
  cm.common.outputs = dense.common.outputs = {{"mould_stl", "test", 0, 0}};
  const Result a = run_job(cm, into(fresh_dir("casting_cm")));
  const Result b = run_job(dense, into(fresh_dir("casting_dense")));
  const Facts& ma = a.facts.group("mould");
  const Facts& mb = b.facts.group("mould");
  // A thinner mix (more water to each gram of plaster) takes less plaster and more water for the same volume.
  CHECK(mb.number("plaster_volume") == ma.number("plaster_volume"));
  CHECK(mb.number("plaster_grams") ==
        Approx(ma.number("plaster_volume") / (1.0 / 2.63 + 1.0 / 1.25)).epsilon(1e-14));
  CHECK(mb.number("plaster_grams") < ma.number("plaster_grams"));
  CHECK(mb.number("water_grams") > ma.number("water_grams"));
  CHECK(mb.number("water_grams") == Approx(mb.number("plaster_grams") / 1.25).epsilon(1e-14));
  CHECK(mb.number("slip_grams") == Approx(1.8 * ma.number("slip_millilitres")).epsilon(1e-14));
}

TEST_CASE("casting: shrinkage measured on a test bar, and bad materials", "[pipeline][mould]") {
  const std::string yaml = read_file(example("mould_golden.yaml"));
  const auto with = [&](const std::string& find, const std::string& replace) {
    std::string text = yaml;
    const auto at = text.find(find);
    REQUIRE(at != std::string::npos);
    text.replace(at, find.size(), replace);
    return text;
  };
  const Design d = parse_design(with("shrinkage: 0.12", "shrinkage: {wet: 100, fired: 88}"), "bar.yaml");
  const auto& v = std::get<VesselDesign>(d.body);
  CHECK(v.shrinkage == Approx(0.12).epsilon(1e-14));
  CHECK(v.shrinkage_wet == 100.0);
  CHECK(v.shrinkage_fired == 88.0);
  struct Bad {
    std::string find, replace, key, says;
  };
  const Bad bad[] = {
      {"shrinkage: 0.12", "shrinkage: {wet: 100, fired: 120}", "shrinkage.fired",
       "must be in (0, wet = 100]"},
      {"shrinkage: 0.12", "shrinkage: {wet: 0, fired: 0}", "shrinkage.wet", "must be > 0"},
      {"shrinkage: 0.12", "shrinkage: {wet: 100}", "shrinkage", "fired"},
      {"shrinkage: 0.12", "shrinkage: {wet: 100, fired: 90, dry: 95}", "shrinkage", "dry"},
      {"mould:\n", "mould:\n  plaster_ratio: 0\n", "mould.plaster_ratio", "must be > 0"},
      {"mould:\n", "mould:\n  slip_density: -1\n", "mould.slip_density", "must be > 0"},
  };
  for (const Bad& b : bad) {
    INFO(b.replace);
    try {
      parse_design(with(b.find, b.replace), "bad.yaml");
      FAIL("accepted");
    } catch (const InputError& e) {
      const std::string what = e.what();
      INFO(what);
      CHECK(what.find(b.key) != std::string::npos);
      CHECK(what.find(b.says) != std::string::npos);
    }
  }
}
