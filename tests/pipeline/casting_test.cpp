// What a potter weighs for a slip-casting mould: plaster and water by weight
// for the mould and each part, the slip to fill it, and shrinkage measured on
// a test bar.

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/core/errors.h"
#include "geometry/mesh/bounding_box.h"
#include "io/design/read_design.h"
#include "io/file.h"
#include "io/mesh/read_mesh.h"
#include "pipeline/summary.h"
#include "tests/io/mesh/external_tool.h"
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

TEST_CASE("casting cases: each half of a box mould gets a case, standing on its floor, valid as written",
          "[pipeline][mould][case]") {
  const fs::path dir = fresh_dir("casting_cases");
  Design design = read_design(example("mould_box_cases.yaml"));  // mm, 5 mm walls
  const Result r = run_job(design, into(dir));
  const std::vector<Facts>& cases = std::get<std::vector<Facts>>(*r.facts.group("mould").find("cases"));
  const std::vector<Facts>& parts = std::get<std::vector<Facts>>(*r.facts.group("mould").find("parts"));
  REQUIRE(cases.size() == 2);
  double x = 0.0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Facts& c = cases[i];
    INFO(c.text("part"));
    CHECK(c.text("name") == "case-" + parts[i].text("name"));
    CHECK(c.find("refused") == nullptr);
    // Side 1 lies on +y of the split plane, side 2 on -y: each pulled out through its back.
    const auto& pull = std::get<std::vector<double>>(*c.find("pull"));
    CHECK(pull == std::vector<double>{0.0, i == 0 ? 1.0 : -1.0, 0.0});
    // The part's ends and top lean by the default 1 degree draft (its
    // bottom too: no base part), each taking a wedge from the part as the
    // case casts it; its split face touches the other part and does not.
    const Facts& draft = c.group("draft");
    CHECK(draft.number("deg") == 1.0);
    CHECK(std::get<std::vector<std::string>>(*draft.find("faces")) ==
          std::vector<std::string>{"its face across -z", "its face across +z", "its face across -x",
                                   "its face across +x"});
    CHECK(std::get<std::vector<std::string>>(*draft.find("not_leaned")).empty());
    CHECK(draft.number("volume") > 0.0);
    CHECK(draft.number("part_volume") == Approx(parts[i].number("volume") - draft.number("volume")));
    // The case is the box around the part less the part as cast: its volume says so.
    const auto& size = std::get<std::vector<double>>(*c.find("size"));
    CHECK(c.number("volume") ==
          Approx(size[0] * size[1] * size[2] - draft.number("part_volume")).epsilon(1e-9));
    // Written standing: from z = 0, side by side along x 10 mm apart.
    const auto& from = std::get<std::vector<double>>(*c.find("written_from"));
    CHECK(from == std::vector<double>{x, 0.0, 0.0});
    x += size[0] + 10.0;
    const std::string stl = (dir / ("mould_box_cases." + c.text("name") + ".stl")).string();
    REQUIRE(fs::exists(stl));
    std::string text;
    CHECK(run_cli({"check", stl}, &text) == 0);
    CHECK(text.find(": valid") != std::string::npos);
    CHECK(c.text("release").find("leaves its case along") != std::string::npos);
  }
  std::ostringstream summary;
  print_summary(r, summary);
  CHECK_THAT(
      summary.str(),
      Catch::Contains("casting cases: 2 of 2 parts (side-1 lifts out along +y, side-2 lifts out along -y)") &&
          Catch::Contains(
              "casting cases' draft: 1 degree on 8 faces (side-1 -z +z -x +x, side-2 -z +z -x +x), "
              "taking 2.474e+05 mm^3 from the parts as cast\n"));
  // Both in one 3MF, apart: checked as an assembly, nothing interpenetrates.
  std::string text;
  CHECK(run_cli({"check", (dir / "mould_box_cases.case.3mf").string()}, &text) == 0);
  CHECK(text.find("2 objects, none interpenetrating") != std::string::npos);
}

TEST_CASE("casting cases: a side part over a keyed base gets a plate under it, off first",
          "[pipeline][mould][case]") {
  const fs::path dir = fresh_dir("casting_cases_plate");
  Design design = read_design(example("mould_golden_box_base.yaml"));  // cm, 0.5 cm walls
  design.common.outputs = {{"case_stl", "test", 0, 0}, {"case_3mf", "test", 0, 0}};
  const Result r = run_job(design, into(dir));
  const std::vector<Facts>& cases = std::get<std::vector<Facts>>(*r.facts.group("mould").find("cases"));
  REQUIRE(cases.size() == 3);
  double x = 0.0;
  for (std::size_t i = 0; i < 2; ++i) {
    const Facts& c = cases[i];
    INFO(c.text("part"));
    REQUIRE(c.contains("plate"));
    const Facts& plate = c.group("plate");
    CHECK(plate.text("name") == c.text("name") + "-plate");
    CHECK(std::get<std::vector<double>>(*plate.find("pull")) == std::vector<double>{0.0, 0.0, -1.0});
    CHECK(plate.number("features") == 1);  // the base key's socket in the side's bottom
    // Its two pins, 0.25 cm across and tall (a 0.5 cm wall), in holes 0.2 mm wider and deeper.
    CHECK(c.number("clearance") == Approx(0.02));
    CHECK(std::get<std::vector<Facts>>(*plate.find("pins")).size() == 2);
    const Facts& pin = plate.group("pin");
    CHECK(pin.number("diameter") == Approx(0.25));
    CHECK(pin.number("height") == Approx(0.25));
    CHECK(pin.number("hole_diameter") == Approx(0.29));
    CHECK(pin.number("hole_depth") == Approx(0.27));
    // The plate stands on its outer face: the slab, 0.5 thick, and the socket's
    // dome (the key's radius) on it; written after its case, 1 cm apart.
    const auto& size = std::get<std::vector<double>>(*plate.find("size"));
    CHECK(size[2] > 0.5);
    CHECK(size[2] < 0.5 + 1.0);
    x += std::get<std::vector<double>>(*c.find("size"))[0] + 1.0;
    CHECK(std::get<std::vector<double>>(*plate.find("written_from")) == std::vector<double>{x, 0.0, 0.0});
    x += size[0] + 1.0;
    CHECK_THAT(c.text("release"), Catch::Contains("once the plate across -z is off") &&
                                      Catch::Contains("the plate comes off first along -z"));
    for (const std::string& name : {c.text("name"), plate.text("name")}) {
      const std::string stl = (dir / ("mould_golden_box_base." + name + ".stl")).string();
      REQUIRE(fs::exists(stl));
      std::string text;
      CHECK(run_cli({"check", stl}, &text) == 0);
      CHECK(text.find(": valid") != std::string::npos);
    }
  }
  CHECK_FALSE(cases[2].contains("plate"));  // the base pours through its bottom, its keys up
  std::ostringstream summary;
  print_summary(r, summary);
  CHECK_THAT(summary.str(), Catch::Contains("casting cases: 3 of 3 parts (side-1 lifts out along +y once its "
                                            "plate is off along -z, side-2 lifts out along -y once its plate "
                                            "is off along -z, base lifts out along -z)"));
  std::string text;
  CHECK(run_cli({"check", (dir / "mould_golden_box_base.case.3mf").string()}, &text) == 0);
  CHECK(text.find("5 objects, none interpenetrating") != std::string::npos);
}

namespace {

// The report's casting cases of the golden mould run with `overrides`,
// its case STL and 3MF written to `dir`.
nlohmann::json golden_cases(const fs::path& dir, const std::vector<std::string>& overrides) {
  std::vector<std::string> args{"run", example("mould_golden.yaml"), "-D", "outputs=[case_stl, case_3mf]"};
  args.insert(args.end(), overrides.begin(), overrides.end());
  args.insert(args.end(), {"-o", dir.string() + "/", "--json"});
  std::string text;
  REQUIRE(run_cli_json(args, &text) == 0);
  return nlohmann::json::parse(text).at(0).at("build").at("mould").at("cases");
}

// `check` finds each of the golden mould's case STL `files` in `dir` valid and one body.
void check_golden_stls(const fs::path& dir, std::initializer_list<const char*> files) {
  for (const char* file : files) {
    const std::string stl = (dir / (std::string("mould_golden.") + file + ".stl")).string();
    INFO(stl);
    REQUIRE(fs::exists(stl));
    std::string checked;
    CHECK(run_cli({"check", stl}, &checked) == 0);
    CHECK(checked.find(": valid") != std::string::npos);
    CHECK(checked.find(" 1 component,") != std::string::npos);
  }
}

}  // namespace

TEST_CASE("casting cases: a cylinder mould's halves are cast upright under lids, its base in one piece",
          "[pipeline][mould][case][lid]") {
  const fs::path dir = fresh_dir("casting_cases_cylinder");
  std::string text;
  const nlohmann::json cases = golden_cases(dir, {"-D", "mould.base_part=true", "-D", "mould.keys=2"});
  REQUIRE(cases.size() == 3);
  for (int side = 0; side < 2; ++side) {
    const nlohmann::json& c = cases.at(side);
    INFO(c.dump());
    const double y = side == 0 ? 1.0 : -1.0;
    CHECK(c.at("pull") == nlohmann::json::array({0.0, y, 0.0}));
    CHECK(c.at("opening") == nlohmann::json::array({0.0, 0.0, 1.0}));
    // The plate under it (the base keys' sockets), then the lid over its back.
    REQUIRE(c.at("pieces").size() == 2);
    CHECK(c.at("pieces").at(0).at("beyond") == "its face across -z");
    CHECK(c.at("pieces").at(1).at("beyond") == "its curved back");
    CHECK(c.at("pieces").at(1).at("pull") == nlohmann::json::array({0.0, y, 0.0}));
    for (const nlohmann::json& piece : c.at("pieces")) CHECK(piece.at("pins").size() == 2);
    CHECK_THAT(c.at("release").get<std::string>(),
               Catch::Contains("its flat face across +z") &&
                   Catch::Contains("comes off next along (0, " + std::string(side == 0 ? "1" : "-1") +
                                   ", 0): it touches side-" + std::to_string(side + 1) + " only on the"));
    CHECK(c.at("draft").at("not_leaned").size() == 1);
  }
  CHECK(cases.at(2).at("pull") == nlohmann::json::array({0.0, 0.0, -1.0}));
  const bool base_pieces = cases.at(2).contains("pieces") && !cases.at(2).at("pieces").empty();
  CHECK_FALSE(base_pieces);
  // The base's wall on the cylinder leans into a cone by the default draft;
  // what it takes is bounded closer than its own size.
  const nlohmann::json& draft = cases.at(2).at("draft");
  CHECK(draft.at("faces") == nlohmann::json::array({"its cylinder"}));
  CHECK(draft.at("not_leaned").empty());
  CHECK(draft.at("volume").get<double>() > 0.0);
  CHECK(draft.at("volume_error").get<double>() < draft.at("volume").get<double>());
  check_golden_stls(dir, {"case-base", "case-side-1", "case-side-1-piece-1", "case-side-1-piece-2",
                          "case-side-2", "case-side-2-piece-2"});
  std::string checked;
  CHECK(run_cli({"check", (dir / "mould_golden.case.3mf").string()}, &checked) == 0);
  CHECK(checked.find("7 objects, none interpenetrating") != std::string::npos);
  // Without a base part: the lid alone, and the summary says so.
  CHECK(run_cli({"run", example("mould_golden.yaml"), "-D", "outputs=[case_stl]", "-o", dir.string() + "/"},
                &text) == 0);
  CHECK(text.find(
            "casting cases: 2 of 2 parts (side-1 lifts out along +y once its lid is off, side-2 lifts out "
            "along -y once its lid is off)") != std::string::npos);
}

TEST_CASE(
    "casting cases: a cylinder mould in three parts: a lid over each back, a piece beyond each slanted face",
    "[pipeline][mould][case][lid]") {
  const fs::path dir = fresh_dir("casting_cases_cylinder_three");
  const nlohmann::json cases = golden_cases(dir, {"-D", "mould.parts=3", "-D", "mould.key_clearance=0.1"});
  REQUIRE(cases.size() == 3);
  // Sides 1 and 3 have a split face on the plane across y: their lids come
  // off across it, then the piece beyond the other split face, and the part
  // leaves the main piece the lid's way. Side 2 has none: its lid comes off
  // along -x, the pieces beyond its split faces (the last with the vessel's
  // slice), and the part lifts off the floor.
  const std::array<nlohmann::json, 3> lids{nlohmann::json::array({0.0, 1.0, 0.0}),
                                           nlohmann::json::array({-1.0, 0.0, 0.0}),
                                           nlohmann::json::array({0.0, -1.0, 0.0})};
  for (std::size_t side = 0; side < 3; ++side) {
    const nlohmann::json& c = cases.at(side);
    INFO(c.dump());
    CHECK(c.at("pull") == (side == 1 ? nlohmann::json::array({0.0, 0.0, 1.0}) : lids.at(side)));
    CHECK(c.at("opening") == nlohmann::json::array({0.0, 0.0, 1.0}));
    REQUIRE(c.at("pieces").size() == (side == 1 ? 3U : 2U));
    CHECK(c.at("pieces").at(0).at("beyond") == "its curved back");
    CHECK(c.at("pieces").at(0).at("pull") == lids.at(side));
    for (std::size_t n = 1; n < c.at("pieces").size(); ++n) {
      CHECK_THAT(c.at("pieces").at(n).at("beyond").get<std::string>(),
                 Catch::StartsWith("its split face at"));
    }
    for (const nlohmann::json& piece : c.at("pieces")) CHECK(piece.at("pins").size() == 2);
  }
  check_golden_stls(dir, {"case-side-1", "case-side-2", "case-side-2-piece-1", "case-side-2-piece-2",
                          "case-side-2-piece-3", "case-side-3-piece-2"});
  std::string checked;
  CHECK(run_cli({"check", (dir / "mould_golden.case.3mf").string()}, &checked) == 0);
  CHECK(checked.find("10 objects, none interpenetrating") != std::string::npos);
}

TEST_CASE("casting cases: a cylinder mould in three parts over a keyed base: every part's case",
          "[pipeline][mould][case][lid]") {
  const fs::path dir = fresh_dir("casting_cases_cylinder_three_base");
  const nlohmann::json cases = golden_cases(dir, {"-D", "mould.parts=3", "-D", "mould.key_clearance=0.1",
                                                  "-D", "mould.base_part=true", "-D", "mould.keys=2"});
  REQUIRE(cases.size() == 4);
  // Sides 1 and 3: the lid, the piece beyond the slanted face, the plate
  // under the part (the base key's socket); the part leaves the lid's way.
  // Side 2: the lid, the pieces beyond its split faces (the last with the
  // vessel's slice, the base key's bump left on the floor); the part lifts
  // off the floor. The base: one piece.
  for (std::size_t side = 0; side < 3; ++side) {
    const nlohmann::json& c = cases.at(side);
    INFO(c.dump());
    REQUIRE(c.at("pieces").size() == 3U);
    CHECK(c.at("pull") == (side == 1 ? nlohmann::json::array({0.0, 0.0, 1.0})
                                     : nlohmann::json::array({0.0, side == 0 ? 1.0 : -1.0, 0.0})));
    CHECK(c.at("pieces").at(0).at("beyond") == "its curved back");
    CHECK_THAT(c.at("pieces").at(1).at("beyond").get<std::string>(), Catch::StartsWith("its split face at"));
    CHECK_THAT(c.at("pieces").at(2).at("beyond").get<std::string>(),
               Catch::StartsWith(side == 1 ? "its split face at" : "its face across -z"));
    for (const nlohmann::json& piece : c.at("pieces")) CHECK(piece.at("pins").size() == 2);
  }
  const bool base_pieces = cases.at(3).contains("pieces") && !cases.at(3).at("pieces").empty();
  CHECK_FALSE(base_pieces);
  check_golden_stls(
      dir, {"case-base", "case-side-2", "case-side-2-piece-1", "case-side-2-piece-2", "case-side-2-piece-3"});
  std::string checked;
  CHECK(run_cli({"check", (dir / "mould_golden.case.3mf").string()}, &checked) == 0);
  CHECK(checked.find("13 objects, none interpenetrating") != std::string::npos);
  // Without keys the middle side's two slanted seams are mirror images: they
  // meet off the edge along its bisector, and its floor is valid as written.
  const std::array<std::array<const char*, 3>, 2> keyless{
      {{"mould.base_part=false", "alone", "8 objects"}, {"mould.base_part=true", "base", "9 objects"}}};
  for (const auto& [base, folder, objects] : keyless) {
    INFO(base);
    const fs::path out = dir / folder;
    std::string text;
    REQUIRE(run_cli({"run", example("mould_golden.yaml"), "-D", "outputs=[case_3mf]", "-D", "mould.parts=3",
                     "-D", "mould.keys=0", "-D", base, "-o", out.string() + "/"},
                    &text) == 0);
    CHECK(run_cli({"check", (out / "mould_golden.case.3mf").string()}, &checked) == 0);
    CHECK(checked.find(std::string(objects) + ", none interpenetrating") != std::string::npos);
  }
}

TEST_CASE("casting cases: a cut a hair from one of the part's vertices leaves no edge float32 folds",
          "[pipeline][mould][case][lid]") {
  // The golden solid's keyless mould in three parts over a base part: the
  // middle side's two slanted seams meet on a line that passes a hair from a
  // vertex of its cavity, crossing two of the cavity's edges 2.6e-7 cm
  // apart. Rounded to float32 (STL, 3MF) the two points were one and their
  // faces folded, and no case file was written; the hair now collapses.
  const fs::path dir = fresh_dir("casting_cases_hair");
  std::string text;
  REQUIRE(run_cli_json(
              {"run", example("vessel_golden_solid.yaml"), "-D", "mould={parts: 3, base_part: true, keys: 0}",
               "-D", "outputs=[case_stl, case_3mf]", "-o", dir.string() + "/", "--json"},
              &text) == 0);
  const nlohmann::json item = nlohmann::json::parse(text).at(0);
  const nlohmann::json& files = item.at("files");
  CHECK(files.size() == 10);  // nine case pieces' STL files and the 3MF
  for (const nlohmann::json& f : files) {
    INFO(f.dump());
    CHECK(f.at("valid_as_written") == true);
    if (f.at("format") == "case_stl") {
      std::string checked;
      CHECK(run_cli({"check", f.at("path").get<std::string>()}, &checked) == 0);
      CHECK(checked.find(" 1 component,") != std::string::npos);
    }
  }
  std::string checked;
  CHECK(run_cli({"check", (dir / "vessel_golden_solid.case.3mf").string()}, &checked) == 0);
  CHECK(checked.find("9 objects, none interpenetrating") != std::string::npos);
}

TEST_CASE("casting cases: a part no case releases is named", "[pipeline][mould][case]") {
  const fs::path dir = fresh_dir("casting_cases_refused");
  std::string text;
  // Three parts keyed on planes 120 degrees apart, on a base: the base pours
  // through its bottom; each side's keys on its slanted split faces catch on
  // any case pulled along an axis, so its case is carved in pieces taken off
  // first: one under the part (the base keys' sockets) and one beyond each
  // split face whose keys would catch.
  const fs::path carved = fresh_dir("casting_cases_carved");
  REQUIRE(
      run_cli_json({"run", example("mould_golden_box_base.yaml"), "-D", "outputs=[case_stl, case_3mf]", "-D",
                    "mould.parts=3", "-D", "mould.key_clearance=0.1", "-o", carved.string() + "/", "--json"},
                   &text) == 0);
  for (const char* file : {"case-base", "case-side-1", "case-side-1-piece-1", "case-side-1-piece-2",
                           "case-side-2", "case-side-2-piece-3", "case-side-3-piece-2"}) {
    CHECK(fs::exists(carved / (std::string("mould_golden_box_base.") + file + ".stl")));
  }
  CHECK_FALSE(fs::exists(carved / "mould_golden_box_base.case-side-1-piece-3.stl"));
  const nlohmann::json report = nlohmann::json::parse(text);
  const nlohmann::json& cases = report.at(0).at("build").at("mould").at("cases");
  REQUIRE(cases.size() == 4);
  const nlohmann::json& side2 = cases.at(1);
  CHECK(side2.at("pull") == nlohmann::json::array({-1.0, 0.0, 0.0}));
  REQUIRE(side2.at("pieces").size() == 3);
  CHECK(side2.at("pieces").at(0).at("beyond") == "its face across -z");
  CHECK(side2.at("pieces").at(1).at("beyond") == "its split face at 120 degrees");
  CHECK(side2.at("pieces").at(2).at("beyond") == "its split face at 240 degrees");
  for (const nlohmann::json& piece : side2.at("pieces")) CHECK(piece.at("pins").size() == 2);
  CHECK_THAT(
      side2.at("release").get<std::string>(),
      Catch::Contains("side-2 leaves its case along -x once the case's 3 other pieces are off") &&
          Catch::Contains("piece 3 (beyond its split face at 240 degrees) comes off next along (0.866, "
                          "-0.5, 0)"));
  std::string checked;
  CHECK(run_cli({"check", (carved / "mould_golden_box_base.case.3mf").string()}, &checked) == 0);
  CHECK(checked.find("11 objects, none interpenetrating") != std::string::npos);
  // Without a base: one piece beyond each slanted split face.
  CHECK(run_cli({"run", example("mould_golden.yaml"), "-D", "outputs=[case_stl]", "-D", "mould.block=box",
                 "-D", "mould.parts=3", "-D", "mould.key_clearance=0.1", "-o", carved.string() + "/"},
                &text) == 0);
  CHECK(text.find(
            "casting cases: 3 of 3 parts (side-1 lifts out along +y once its 1 other piece is off, side-2 "
            "lifts out along -x once its 2 other pieces are off, side-3 lifts out along -y once its 1 "
            "other piece is off)") != std::string::npos);
  // case_step writes a carved case's pieces assembled, cut from the exact case.
  const fs::path step = fresh_dir("casting_cases_carved_step");
  CHECK(run_cli({"run", example("mould_golden.yaml"), "-D", "outputs=[case_step]", "-D", "mould.block=box",
                 "-D", "mould.parts=3", "-D", "mould.key_clearance=0.1", "-o", step.string() + "/"},
                &text) == 0);
  for (const char* part : {"side-1", "side-2", "side-3"}) {
    const std::string file =
        read_file((step / (std::string("mould_golden.case-") + part + ".step")).string());
    std::size_t solids = 0;
    for (std::size_t at = file.find("MANIFOLD_SOLID_BREP"); at != std::string::npos;
         at = file.find("MANIFOLD_SOLID_BREP", at + 1))
      ++solids;
    CHECK(solids == (std::string(part) == "side-2" ? 3U : 2U));
  }
  // A case that does not fit the printer is cut into sections that do; a
  // bed no longer than a section's pin is bad input at print.bed, nothing
  // written.
  const fs::path bed = fresh_dir("casting_cases_bed");
  CHECK(run_cli({"run", example("mould_box_cases.yaml"), "-D", "print={bed: [250, 250, 250]}", "-D",
                 "outputs=[case_stl]", "-o", bed.string() + "/"},
                &text) == 0);
  CHECK_FALSE(fs::exists(bed / "mould_box_cases.case-side-1.stl"));
  CHECK(fs::exists(bed / "mould_box_cases.case-side-1-section-1.stl"));
  CHECK(fs::exists(bed / "mould_box_cases.case-side-1-section-2.stl"));
  CHECK(text.find("written whole") == std::string::npos);
  const fs::path small = fresh_dir("casting_cases_bed_small");
  CHECK(run_cli({"run", example("mould_box_cases.yaml"), "-D", "print={bed: [2, 2, 250]}", "-D",
                 "outputs=[case_stl]", "-o", small.string() + "/"},
                &text) == 2);
  CHECK_FALSE(fs::exists(small / "mould_box_cases.case-side-1.stl"));
  CHECK(fs::is_empty(small));
  CHECK_THAT(text, Catch::Contains("-D print={bed: [2, 2, 250]}: print.bed: case-side-1 (383.227 x 235.976 x "
                                   "123.988 standing) cannot be cut into sections that fit the bed 2 x 2 x "
                                   "250: the bed is no longer than a section's pin (2.5 tall: half of "
                                   "case.wall) along an axis the piece exceeds it"));
  // A wall of no thickness is bad input at its key, and so is a clearance
  // that would leave the pins' holes no wall: nothing written.
  CHECK(run_cli({"run", example("mould_box_cases.yaml"), "-D", "case.wall=0", "-o", dir.string() + "/"},
                &text) == 2);
  CHECK(text.find("case.wall") != std::string::npos);
  const fs::path refused = fresh_dir("casting_cases_clearance");
  CHECK(run_cli({"run", example("mould_box_cases.yaml"), "-D", "case.clearance=1.25", "-o",
                 refused.string() + "/"},
                &text) == 2);
  CHECK_THAT(
      text, Catch::Contains("case.clearance") && Catch::Contains("clearance = 1.25 mm must be at least 0 and "
                                                                 "below a quarter of case.wall (1.25 mm)"));
  CHECK(fs::is_empty(refused));
  // A draft beyond 10 degrees, or negative, likewise.
  for (const char* draft : {"case.draft_deg=12", "case.draft_deg=-1"}) {
    INFO(draft);
    CHECK(run_cli({"run", example("mould_box_cases.yaml"), "-D", draft, "-o", refused.string() + "/"},
                  &text) == 2);
    CHECK_THAT(text, Catch::Contains("-D " + std::string(draft)) && Catch::Contains("case.draft_deg") &&
                         Catch::Contains("must be an angle from 0 to 10 degrees"));
    CHECK(fs::is_empty(refused));
  }
  // No draft: the case is the box less the part exactly, and says no face leans.
  const fs::path plain = fresh_dir("casting_cases_no_draft");
  std::string json;
  REQUIRE(run_cli_json({"run", example("mould_box_cases.yaml"), "-D", "case.draft_deg=0", "-D",
                        "outputs=[case_stl]", "-o", plain.string() + "/", "--json"},
                       &json) == 0);
  const nlohmann::json mould = nlohmann::json::parse(json)[0]["build"]["mould"];
  for (std::size_t i = 0; i < 2; ++i) {
    const nlohmann::json& c = mould["cases"][i];
    CHECK(c["draft"]["faces"].empty());
    CHECK(c["draft"]["volume"] == 0.0);
    const auto size = c["size"].get<std::vector<double>>();
    CHECK(c["volume"].get<double>() ==
          Approx(size[0] * size[1] * size[2] - mould["parts"][i]["volume"].get<double>()).epsilon(1e-9));
  }
}

TEST_CASE("casting cases: PrusaSlicer finds each case manifold and slices it standing on its floor",
          "[pipeline][mould][case][prusaslicer]") {
  REQUIRE_PROGRAM("prusa-slicer");
  const fs::path dir = fresh_dir("casting_cases_prusa");
  REQUIRE(run_cli({"run", example("mould_box_cases.yaml"), "-D", "outputs=[case_stl]", "-o",
                   dir.string() + "/"}) == 0);
  REQUIRE(run_cli({"run", example("mould_golden_box_base.yaml"), "-D", "outputs=[case_stl]", "-o",
                   dir.string() + "/"}) == 0);  // in cm, written in mm
  REQUIRE(run_cli({"run", example("mould_golden.yaml"), "-D", "outputs=[case_stl]", "-o",
                   dir.string() + "/"}) == 0);  // a cylinder mould, in cm
  struct Piece {
    const char* name;
    double height;  // mm, as it stands
  };
  // PrusaSlicer finds the STL manifold, `height` tall, and slices it on a 400 mm bed.
  const auto sliced = [&dir](const fs::path& stl, double height) {
    const std::map<std::string, std::string> info = test::prusa_info((dir / "home").string(), stl.string());
    REQUIRE(info.count("manifold") == 1);
    CHECK(info.at("manifold") == "yes");
    CHECK(std::stod(info.at("size_z")) == Approx(height).margin(0.01));
    fs::path gcode = stl;
    gcode.replace_extension(".gcode");
    const test::ToolRun slice =
        test::prusa_slicer((dir / "home").string(),
                           "--export-gcode --bed-shape 0x0,400x0,400x400,0x400 --center 200,200 " +
                               test::quoted(stl.string()) + " --output " + test::quoted(gcode.string()));
    INFO(slice.output);
    CHECK(slice.code == 0);
    CHECK(fs::file_size(gcode) > 0);
  };
  // A case stands on its floor, its opening up: 124 mm tall for the big half
  // (its 113 mm depth, a key, the floor); the golden half's over its base
  // 70.5. The plate stands on its outer face: 5 mm and the socket's 6.2 mm dome.
  // A cylinder mould's half stands on its board, 75.5 mm (its 59.5 mm radius,
  // a key's 6 mm bump and two 5 mm walls); its lid on its back, 67.0 mm.
  for (const Piece& piece : {Piece{"mould_box_cases.case-side-1", 123.988},
                             {"mould_box_cases.case-side-2", 123.988},
                             {"mould_golden_box_base.case-side-1", 70.520},
                             {"mould_golden_box_base.case-side-1-plate", 11.2},
                             {"mould_golden.case-side-1", 75.520},
                             {"mould_golden.case-side-1-piece-1", 67.020}}) {
    INFO(piece.name);
    sliced(dir / (std::string(piece.name) + ".stl"), piece.height);
  }
  // The middle side of the golden mould in 3 parts: its floor (the main
  // piece, one 5 mm wall), its lid, and the pieces beyond its split faces
  // (the last with the vessel's slice), each as tall as fabmesh reads it.
  const fs::path three = dir / "three";
  REQUIRE(run_cli({"run", example("mould_golden.yaml"), "-D", "outputs=[case_stl]", "-D", "mould.parts=3",
                   "-D", "mould.key_clearance=0.1", "-o", three.string() + "/"}) == 0);
  for (const char* name : {"mould_golden.case-side-2", "mould_golden.case-side-2-piece-1",
                           "mould_golden.case-side-2-piece-2", "mould_golden.case-side-2-piece-3"}) {
    INFO(name);
    const fs::path stl = three / (std::string(name) + ".stl");
    const BoundingBox box = bounding_box(read_mesh(stl.string()).vertices);
    if (std::string(name) == "mould_golden.case-side-2") CHECK(box.hi.z() - box.lo.z() == Approx(5.0));
    sliced(stl, box.hi.z() - box.lo.z());
  }
}

namespace {

// The production vase in a box mould, its cases cut for its 220 mm bed (mm).
const char* const kVaseBox[] = {"-D", "mould.block=box", "-D", "outputs=[case_stl]"};

}  // namespace

TEST_CASE("casting cases: cases too big for the bed are written in pinned sections that fit it",
          "[pipeline][mould][case][sections]") {
  const fs::path dir = fresh_dir("casting_case_sections");
  const std::vector<std::string> args{"run",
                                      example("mould_vase_production.yaml"),
                                      kVaseBox[0],
                                      kVaseBox[1],
                                      kVaseBox[2],
                                      kVaseBox[3],
                                      "--json",
                                      "-o",
                                      dir.string() + "/"};
  std::string text;
  REQUIRE(run_cli_json(args, &text) == 0);
  const nlohmann::json report = nlohmann::json::parse(text);
  for (const std::string warning : report[0]["warnings"]) {
    CHECK(warning.find("case-") == std::string::npos);  // no case left whole for want of a bed
  }
  const nlohmann::json& cases = report[0]["build"]["mould"]["cases"];
  REQUIRE(cases.size() == 4);
  std::size_t sections = 0;
  for (const nlohmann::json& c : cases) {
    std::vector<nlohmann::json> pieces{c};
    for (const nlohmann::json& p : c.value("pieces", nlohmann::json::array())) pieces.push_back(p);
    for (const nlohmann::json& p : pieces) {
      const std::string name = p["name"];
      INFO(name);
      const std::vector<double> size = p["size"];
      if (p["fits_bed"].get<bool>()) {
        CHECK(fs::exists(dir / ("mould_vase_production." + name + ".stl")));
        CHECK_FALSE(p.contains("sections"));
        continue;
      }
      // Cut: not written whole; every section written, fitting the bed, the
      // volumes adding up to the piece's with the pins and their holes.
      CHECK_FALSE(fs::exists(dir / ("mould_vase_production." + name + ".stl")));
      REQUIRE(p.contains("sections"));
      const nlohmann::json& pin = p["section_pin"];
      CHECK(pin["diameter"] == 2.5);  // a quarter of the 5 mm wall in radius
      CHECK(pin["hole_diameter"].get<double>() == Approx(2.5 + 2 * 0.2));
      const double stud = M_PI * 1.25 * 1.25 * pin["height"].get<double>();
      const double hole = M_PI * 1.45 * 1.45 * pin["hole_depth"].get<double>();
      double volume = 0.0, pins = 0.0, holes = 0.0;
      for (const nlohmann::json& s : p["sections"]) {
        const std::vector<double> part = s["size"];
        CHECK(part[2] <= 220.0);
        CHECK(std::min(part[0], part[1]) <= 220.0);
        CHECK(std::max(part[0], part[1]) <= 220.0);
        CHECK(s["pins"].get<double>() + s["holes"].get<double>() >= 2.0);
        volume += s["volume"].get<double>();
        pins += s["pins"].get<double>();
        holes += s["holes"].get<double>();
        CHECK(fs::exists(dir / ("mould_vase_production." + s["name"].get<std::string>() + ".stl")));
        ++sections;
      }
      CHECK(pins == holes);
      // The pins' polygons are within the tolerance of their circles: their
      // volumes within a few percent of the circles'.
      CHECK(volume == Approx(p["volume"].get<double>() + pins * (stud - hole)).margin(0.05 * pins * hole));
      CHECK(p["sections_volume_error"].get<double>() <= 1e-9 * p["volume"].get<double>());
    }
  }
  CHECK(sections >= 20);
  // fabmesh's own check of every file written: each valid.
  for (const auto& entry : fs::directory_iterator(dir)) {
    INFO(entry.path().string());
    std::string checked;
    CHECK(run_cli({"check", entry.path().string()}, &checked) == 0);
    CHECK(checked.find(": valid") != std::string::npos);
  }
}

TEST_CASE("casting cases: for a small bed, cuts a hair from a pin or another cut leave no piece whole",
          "[pipeline][mould][case][sections]") {
  // The production vase's round mould for a 100 mm bed: its cuts, 2 to 4
  // along a piece, meet pins and each other a hair apart (edges 2e-5 mm to
  // 3e-4 mm long), which float32 could fold; those edges collapse, and every
  // piece is cut into sections that fit the bed.
  const fs::path dir = fresh_dir("casting_case_sections_small_bed");
  std::string text;
  REQUIRE(run_cli_json({"run", example("mould_vase_production.yaml"), "-D", "print.bed=[100,100,100]", "-D",
                        "outputs=[case_3mf]", "--json", "-o", dir.string() + "/"},
                       &text) == 0);
  const nlohmann::json report = nlohmann::json::parse(text);
  for (const std::string warning : report[0]["warnings"]) {
    CHECK(warning.find("case-") == std::string::npos);  // no piece left whole
  }
  std::size_t sections = 0, whole = 0;
  for (const nlohmann::json& c : report[0]["build"]["mould"]["cases"]) {
    std::vector<nlohmann::json> pieces{c};
    for (const nlohmann::json& p : c.value("pieces", nlohmann::json::array())) pieces.push_back(p);
    for (const nlohmann::json& p : pieces) {
      INFO(p["name"]);
      if (p["fits_bed"].get<bool>()) {
        ++whole;
        continue;
      }
      REQUIRE(p.contains("sections"));
      CHECK(p["sections_volume_error"].get<double>() <= 1e-9 * p["volume"].get<double>());
      for (const nlohmann::json& s : p["sections"]) {
        const std::vector<double> size = s["size"];
        CHECK(std::max({size[0], size[1], size[2]}) <= 100.0);
        CHECK(s["pins"].get<double>() + s["holes"].get<double>() >= 2.0);
        ++sections;
      }
    }
  }
  CHECK(sections >= 90);
  std::string checked;
  CHECK(run_cli({"check", (dir / "mould_vase_production.case.3mf").string()}, &checked) == 0);
  CHECK(checked.find(std::to_string(sections + whole) + " objects, none interpenetrating") !=
        std::string::npos);
}

TEST_CASE(
    "casting cases: PrusaSlicer finds every case file of the production vase manifold, within its bed, and "
    "slices it",
    "[pipeline][mould][case][sections][prusaslicer]") {
  REQUIRE_PROGRAM("prusa-slicer");
  const fs::path dir = fresh_dir("casting_case_sections_prusa");
  std::string text;
  REQUIRE(run_cli({"run", example("mould_vase_production.yaml"), kVaseBox[0], kVaseBox[1], kVaseBox[2],
                   kVaseBox[3], "-o", dir.string() + "/"},
                  &text) == 0);
  CHECK_THAT(text,
             Catch::Contains("casting cases cut for the bed: 9 pieces in 24 sections (case-side-1 in 2, "
                             "case-side-1-piece-2 in 2, case-side-2 in 6, ") &&
                 Catch::Contains("case-base in 4), two 2.5 mm pins into 2.9 mm holes across every joint"));
  // Every file: the 24 sections (the side part pulled along -x has its main
  // piece in six, two cells holding a wall apart from the rest) and the two
  // plates that fit the bed whole.
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() == ".stl") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  std::size_t sliced = 0;
  for (const fs::path& path : files) {
    const std::string file = path.filename().string();
    INFO(file);
    const std::map<std::string, std::string> info = test::prusa_info((dir / "home").string(), path.string());
    REQUIRE(info.count("manifold") == 1);
    CHECK(info.at("manifold") == "yes");
    const double x = std::stod(info.at("size_x")), y = std::stod(info.at("size_y"));
    CHECK(std::max(x, y) <= 220.0);
    CHECK(std::stod(info.at("size_z")) <= 220.0);
    // Placed from the bed's corner (PrusaSlicer's --center refuses some
    // objects written far along x); it refuses one that does not fit.
    const fs::path gcode = dir / (file + ".gcode");
    const test::ToolRun slice =
        test::prusa_slicer((dir / "home").string(),
                           "--export-gcode --bed-shape 0x0,220x0,220x220,0x220 "
                           "--align-xy 0,0 " +
                               test::quoted(path.string()) + " --output " + test::quoted(gcode.string()));
    INFO(slice.output);
    CHECK(slice.code == 0);
    CHECK(fs::file_size(gcode) > 0);
    ++sliced;
  }
  CHECK(sliced == 26);
}
