// `fabmesh repair` end to end: the corpus of tests/data/repair-corpus
// repaired into 3MF files that `check`, CGAL PMP and PrusaSlicer accept,
// repaired again into the same bytes; bad input refused (exit 2, nothing
// written); what cannot be mended refused (exit 1, nothing written, saying where).

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "geometry/mesh/weld.h"
#include "io/file.h"
#include "io/mesh/obj.h"
#include "io/mesh/read_mesh.h"
#include "io/mesh/stl.h"
#include "tests/geometry/repair/broken_meshes.h"
#include "tests/geometry/repair/cgal_solid.h"
#include "tests/io/mesh/external_tool.h"
#include "tests/pipeline/cli_harness.h"

using namespace fabmesh;
using namespace fabmesh::testing;
namespace fs = std::filesystem;

namespace {

std::string corpus(const std::string& name) {
  return std::string(FABMESH_SOURCE_DIR) + "/tests/data/repair-corpus/" + name;
}

nlohmann::json manifest() {
  std::ifstream in(corpus("manifest.json"));
  return nlohmann::json::parse(in);
}

/// `repair --json` of `input` into `output`: exit code and the one item.
std::pair<int, nlohmann::json> repair_json(const std::string& input, const std::string& output,
                                           std::vector<std::string> extra = {}) {
  std::vector<std::string> args{"repair", input, "-o", output, "--json"};
  args.insert(args.end(), extra.begin(), extra.end());
  const CliResult r = run_fabmesh(args);
  INFO(r.out << r.err);
  return {r.code, only_item(r.out)};
}

std::set<std::string> steps_of(const nlohmann::json& item) {
  std::set<std::string> steps;
  for (const auto& a : item.at("repairs")) steps.insert(a.at("step").get<std::string>());
  return steps;
}

/// Each object of a file, welded exactly (as check reads it).
std::vector<TriangleSoup> objects_of(const std::string& path) {
  MeshFile file = read_mesh_file(path);
  std::vector<TriangleSoup> objects;
  if (file.objects.empty()) objects.push_back(weld(file.soup).soup);
  for (const MeshObject& o : file.objects) objects.push_back(weld(o.soup).soup);
  return objects;
}

}  // namespace

TEST_CASE("repair: every corpus mesh becomes a valid 3MF that check, CGAL and a second repair accept",
          "[pipeline][repair]") {
  const fs::path dir = fresh_dir("repair_corpus");
  const nlohmann::json cases = manifest().at("cases");
  REQUIRE(cases.size() >= 13);
  for (const auto& c : cases) {
    const std::string name = c.at("file");
    INFO(name << ": " << c.at("about").get<std::string>());
    const std::string out = (dir / (fs::path(name).stem().string() + ".3mf")).string();
    const auto [code, item] = repair_json(corpus(name), out);
    REQUIRE(code == 0);
    CHECK(item.at("status") == "ok");
    CHECK(item.at("valid_as_written") == true);
    for (const auto& step : c.at("steps")) CHECK(steps_of(item).count(step.get<std::string>()) == 1);
    CHECK(item.at("solids") == c.at("components"));
    // Every component is accounted for: kept, united, or dropped with why.
    const std::size_t dropped = item.at("dropped_components").size();
    CHECK(item.at("components").at("dropped").get<std::size_t>() == dropped);
    for (const auto& d : item.at("dropped_components")) CHECK_FALSE(d.at("why").get<std::string>().empty());
    CHECK(item.at("distance").get<double>() >= 0.0);
    // check passes on the output, CGAL agrees on every object.
    std::string text;
    CHECK(run_cli({"check", out}, &text) == 0);
    for (const TriangleSoup& object : objects_of(out)) CHECK(cgal_solid(object).solid());
    // Repairing the output changes nothing and writes the same bytes.
    const std::string again = (dir / (fs::path(name).stem().string() + ".again.3mf")).string();
    const auto [code2, item2] = repair_json(out, again);
    CHECK(code2 == 0);
    CHECK(item2.at("changed") == false);
    CHECK(read_file(again) == read_file(out));
  }
}

TEST_CASE("repair: the JSON item says where each step acted, as indices and coordinates",
          "[pipeline][repair]") {
  const fs::path dir = fresh_dir("repair_places");
  const auto [code, item] = repair_json(corpus("duplicate-faces.obj"), (dir / "d.3mf").string());
  REQUIRE(code == 0);
  const auto& steps = item.at("repairs");
  REQUIRE(steps.size() == 1);
  CHECK(steps[0].at("step") == "duplicate_face");
  CHECK(steps[0].at("count") == 3);
  std::set<std::size_t> faces;
  for (const auto& p : steps[0].at("places")) {
    faces.insert(p.at("face").get<std::size_t>());
    CHECK(p.at("point").size() == 3);
  }
  CHECK(faces == std::set<std::size_t>{512, 513, 514});  // the copies, appended after the 512 faces
}

TEST_CASE("repair: other formats on request, each valid as written", "[pipeline][repair]") {
  const fs::path dir = fresh_dir("repair_formats");
  for (const char* ext : {"stl", "obj", "ply", "off"}) {
    INFO(ext);
    const std::string out = (dir / (std::string("holes.") + ext)).string();
    const auto [code, item] = repair_json(corpus("holes.obj"), out);
    REQUIRE(code == 0);
    std::string upper = ext;
    for (char& ch : upper) ch = static_cast<char>(ch - 'a' + 'A');
    CHECK(item.at("output_format") == upper);
    std::string text;
    CHECK(run_cli({"check", out}, &text) == 0);
    const auto [code2, item2] = repair_json(out, (dir / (std::string("again.") + ext)).string());
    CHECK(code2 == 0);
    CHECK(item2.at("changed") == false);
    CHECK(read_file((dir / (std::string("again.") + ext)).string()) == read_file(out));
  }
}

TEST_CASE("repair: bad input exits 2 and writes nothing", "[pipeline][repair]") {
  const fs::path dir = fresh_dir("repair_bad");
  write_text(dir / "empty.stl", "");
  write_text(dir / "nan.obj", "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n");
  write_text(dir / "junk.stl", "this is not a mesh");
  for (const char* bad : {"empty.stl", "nan.obj", "junk.stl", "missing.stl"}) {
    INFO(bad);
    const std::string out = (dir / "out.3mf").string();
    const CliResult r = run_fabmesh({"repair", (dir / bad).string(), "-o", out});
    CHECK(r.code == 2);
    CHECK_FALSE(fs::exists(out));
  }
  // An unknown output format and writing over the input are bad input too.
  CHECK(run_fabmesh({"repair", corpus("holes.obj"), "-o", (dir / "x.gltf").string()}).code == 2);
  write_obj(cube(Vec3::Zero(), 1.0), (dir / "self.obj").string());
  CHECK(run_fabmesh({"repair", (dir / "self.obj").string(), "-o", (dir / "self.obj").string()}).code == 2);
}

TEST_CASE("repair: what cannot be mended exits 1, writes nothing and says where", "[pipeline][repair]") {
  const fs::path dir = fresh_dir("repair_refused");
  const std::string out = (dir / "out.3mf").string();
  SECTION("a hole with --no-fill") {
    const CliResult r = run_fabmesh({"repair", corpus("holes.obj"), "-o", out, "--no-fill"});
    CHECK(r.code == 1);
    CHECK(r.out.find("boundary") != std::string::npos);
    CHECK(r.out.find("--wrap") != std::string::npos);
  }
  SECTION("a change larger than --max-deviation") {
    const CliResult r = run_fabmesh({"repair", corpus("holes.obj"), "-o", out, "--max-deviation", "1e-6"});
    CHECK(r.code == 1);
    CHECK(r.out.find("more than the maximum deviation") != std::string::npos);
  }
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("repair: --wrap makes a closed solid of anything, within the deviation asked",
          "[pipeline][repair][wrap]") {
  const fs::path dir = fresh_dir("repair_wrap");
  const std::string out = (dir / "wrap.3mf").string();
  const auto [code, item] = repair_json(corpus("stray-sheet.obj"), out, {"--wrap", "--max-deviation", "1"});
  REQUIRE(code == 0);
  CHECK(steps_of(item) == std::set<std::string>{"wrap"});
  CHECK(item.at("distance").get<double>() <= 1.0);
  std::string text;
  CHECK(run_cli({"check", out}, &text) == 0);
}

TEST_CASE("repair: PrusaSlicer reads every repaired 3MF as manifold and slices it",
          "[pipeline][repair][prusaslicer]") {
  REQUIRE_PROGRAM("prusa-slicer");
  const fs::path dir = fresh_dir("repair_prusa");
  const nlohmann::json cases = manifest().at("cases");
  REQUIRE(cases.size() >= 13);
  for (const auto& c : cases) {
    const std::string name = c.at("file");
    INFO(name);
    const std::string out = (dir / (fs::path(name).stem().string() + ".3mf")).string();
    REQUIRE(run_fabmesh({"repair", corpus(name), "-o", out}).code == 0);
    test::ToolRun run;
    auto info = test::prusa_info((dir / "home").string(), out, &run);
    INFO(run.output);
    CHECK(run.code == 0);
    CHECK(info["manifold"] == "yes");
  }
  const std::string out = (dir / "overlapping-parts.3mf").string();
  const test::ToolRun slice =
      test::prusa_slicer((dir / "home").string(), "--export-gcode " + test::quoted(out) + " --output " +
                                                      test::quoted((dir / "parts.gcode").string()));
  INFO(slice.output);
  CHECK(slice.code == 0);
}

TEST_CASE("repair: OpenCASCADE's broken sample STLs are mended or refused saying where, never cut down",
          "[pipeline][repair][real]") {
  // Real files from elsewhere, read in place: Debian's occt-misc (a dependency
  // of libocct-foundation-dev, which the build needs), LGPL-2.1 with the OCCT
  // exception. check finds each invalid.
  const fs::path dir = fresh_dir("repair_occt");
  for (const char* name : {"propeller", "bearing", "motor", "video_part", "TR12J_OCC64K"}) {
    INFO(name);
    const std::string input = std::string("/usr/share/opencascade/data/stl/") + name + ".stl";
    REQUIRE(fs::exists(input));
    const std::string out = (dir / (std::string(name) + ".3mf")).string();
    const CliResult r = run_fabmesh({"repair", input, "-o", out, "--json"});
    INFO(r.err);
    CHECK(r.code != 2);  // a readable mesh is never bad input (motor.stl's 1e-15 gaps once were)
    const nlohmann::json item = only_item(r.out);
    if (r.code == 0) {
      // Mended: check accepts it, nothing was lost (bearing.stl once came out as 6 faces).
      std::string text;
      CHECK(run_cli({"check", out}, &text) == 0);
      CHECK(item.at("volume").at("after").get<double>() >=
            0.5 * std::abs(item.at("volume").at("before").get<double>()));
      for (const TriangleSoup& object : objects_of(out)) CHECK(cgal_solid(object).solid());
    } else {
      // Refused: exit 1, nothing written, each line with a place.
      CHECK(r.code == 1);
      CHECK_FALSE(fs::exists(out));
      REQUIRE_FALSE(item.at("unresolved").empty());
      for (const auto& line : item.at("unresolved"))
        CHECK(line.get<std::string>().find(" at (") != std::string::npos);
    }
  }
}
