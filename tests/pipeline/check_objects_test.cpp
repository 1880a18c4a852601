// `fabmesh check` of files holding several objects, end to end: the real
// executable on fabmesh's own mould 3MF and on the corpus of
// tests/data/check-corpus/objects/ (scripts/make-check-corpus-objects.py).

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "tests/io/mesh/temp_dir.h"
#include "tests/pipeline/json_item.h"
#include "tests/pipeline/shell_run.h"

using fabmesh::test::TempDir;

using fabmesh::testing::only_item;
using fabmesh::testing::quoted;
using fabmesh::testing::run_in_shell;
using fabmesh::testing::ShellRun;

namespace {

std::string corpus(const std::string& name) {
  return std::string(FABMESH_SOURCE_DIR) + "/tests/data/check-corpus/objects/" + name;
}

nlohmann::json manifest() {
  std::ifstream in(corpus("manifest.json"));
  REQUIRE(in.good());
  std::stringstream text;
  text << in.rdbuf();
  return nlohmann::json::parse(text.str());
}

/// The manifest's case for `file`.
nlohmann::json expected(const std::string& file) {
  const nlohmann::json all = manifest();
  for (const auto& c : all["cases"]) {
    if (c["file"] == file) return c;
  }
  FAIL("no case " << file << " in the manifest");
  return {};
}

/// check --json of the corpus file matches its manifest case: exit code,
/// verdict, and per object name and verdict, and the interpenetrating pairs.
void require_as_expected(const std::string& file) {
  const nlohmann::json want = expected(file);
  const ShellRun run = run_in_shell("check --json " + quoted(corpus(file)));
  INFO(file << ": " << run.out);
  CHECK(run.code == want["exit_code"]);
  const auto j = only_item(run.out);
  CHECK(j["valid"] == want["valid"]);
  CHECK(j["format"] == want["format"]);
  if (want["objects"].empty()) {
    CHECK_FALSE(j.contains("objects"));
    CHECK_FALSE(j.contains("assembly"));
    return;
  }
  REQUIRE(j.contains("objects"));
  REQUIRE(j["objects"].size() == want["objects"].size());
  for (std::size_t i = 0; i < want["objects"].size(); ++i) {
    CHECK(j["objects"][i]["name"] == want["objects"][i]["name"]);
    CHECK(j["objects"][i]["valid"] == want["objects"][i]["valid"]);
  }
  CHECK(j["assembly"]["objects"] == want["objects"].size());
  CHECK(j["assembly"]["interpenetrating"] == want["interpenetrating"]);
}

}  // namespace

TEST_CASE("check objects: fabmesh's own mould 3MF is valid object by object", "[mesh][check][cli][objects]") {
  const TempDir dir;
  const std::string design = std::string(FABMESH_SOURCE_DIR) + "/configs/examples/mould_golden.yaml";
  REQUIRE(run_in_shell("run " + quoted(design) + " --export-format mould_3mf -q -o " + quoted(dir.file("")))
              .code == 0);
  const std::string mould = dir.file("mould_golden.mould.3mf");

  const ShellRun human = run_in_shell("check " + quoted(mould));
  INFO(human.out);
  CHECK(human.code == 0);
  CHECK(human.out.find(mould + ": valid (2 objects, 2 valid)\n") == 0);
  CHECK(human.out.find("  object 1 'mould_golden mould side-1': valid (") != std::string::npos);
  CHECK(human.out.find("  object 2 'mould_golden mould side-2': valid (") != std::string::npos);
  CHECK(human.out.find("  assembly: 2 objects, none interpenetrating\n") != std::string::npos);
  CHECK(human.out.find("non-manifold") == std::string::npos);

  const ShellRun json = run_in_shell("check --json " + quoted(mould));
  CHECK(json.code == 0);
  const auto j = only_item(json.out);
  CHECK(j["valid"] == true);
  CHECK(j["format"] == "3MF");
  CHECK(j["units"] == "mm");
  REQUIRE(j["objects"].size() == 2);
  for (const auto& object : j["objects"]) {
    CHECK(object["valid"] == true);
    CHECK(object["manifold"] == true);
    CHECK(object["self_intersecting"] == false);
    CHECK(object["genus"] == 0);
    CHECK(object["timings_ms"].contains("self_intersection"));
  }
  CHECK(j["assembly"]["interpenetrating"].empty());
  CHECK(j["assembly"]["judged"] == nlohmann::json::array({0, 1}));
  CHECK(j["timings_ms"].contains("assembly"));
}

TEST_CASE(
    "check objects: a 3-part mould with keys touches on its 120-degree split planes, none interpenetrating",
    "[mesh][check][cli][objects]") {
  // The parts touch on planes that hold no float32 point: as written (3MF,
  // float32) a socket's rim crosses the neighbouring part by a fraction of a
  // float's unit in the last place. That is contact, not overlap.
  const TempDir dir;
  const std::string design = std::string(FABMESH_SOURCE_DIR) + "/configs/examples/mould_golden.yaml";
  REQUIRE(run_in_shell("run " + quoted(design) +
                       " -D mould.parts=3 -D mould.key_clearance=0.1 --export-format mould_3mf -q -o " +
                       quoted(dir.file("")))
              .code == 0);
  const ShellRun human = run_in_shell("check " + quoted(dir.file("mould_golden.mould.3mf")));
  INFO(human.out);
  CHECK(human.code == 0);
  CHECK(human.out.find("(3 objects, 3 valid)") != std::string::npos);
  CHECK(human.out.find("  assembly: 3 objects, none interpenetrating\n") != std::string::npos);
}

TEST_CASE("check objects: a 3MF of two cubes touching on a face is valid, none interpenetrating",
          "[mesh][check][cli][objects]") {
  require_as_expected("touching-cubes.3mf");
  const ShellRun human = run_in_shell("check " + quoted(corpus("touching-cubes.3mf")));
  CHECK(human.out.find("  object 1 'left': valid (8 vertices, 12 triangles, 1 component, genus 0, volume 1 "
                       "mm^3, area 6 mm^2)\n") != std::string::npos);
  CHECK(human.out.find("  assembly: 2 objects, none interpenetrating\n") != std::string::npos);
}

TEST_CASE("check objects: a 3MF of interpenetrating cubes has each valid and names the pair",
          "[mesh][check][cli][objects]") {
  require_as_expected("interpenetrating-cubes.3mf");
  const ShellRun human = run_in_shell("check " + quoted(corpus("interpenetrating-cubes.3mf")));
  CHECK(human.code == 0);
  CHECK(human.out.find("  assembly: 2 objects, interpenetrating: 1 'a' and 2 'b'\n") != std::string::npos);
}

TEST_CASE("check objects: bars crossing with no corner inside each other interpenetrate",
          "[mesh][check][cli][objects]") {
  require_as_expected("crossing-bars.3mf");
}

TEST_CASE("check objects: one cube placed twice interpenetrates, unnamed objects named by id",
          "[mesh][check][cli][objects]") {
  require_as_expected("copies.3mf");
}

TEST_CASE("check objects: one invalid object makes the file invalid, the other still judged",
          "[mesh][check][cli][objects]") {
  require_as_expected("open-and-closed.3mf");
  const ShellRun human = run_in_shell("check " + quoted(corpus("open-and-closed.3mf")));
  CHECK(human.out.find("  object 2 'open': INVALID (") != std::string::npos);
  CHECK(human.out.find("    - 3 boundary edges") != std::string::npos);
  const auto j = only_item(run_in_shell("check --json " + quoted(corpus("open-and-closed.3mf"))).out);
  CHECK(j["assembly"]["judged"] == nlohmann::json::array({0}));
}

TEST_CASE("check objects: an OBJ of two o objects touching is two valid objects",
          "[mesh][check][cli][objects]") {
  require_as_expected("two-objects.obj");
}

TEST_CASE("check objects: an OBJ of one shell split in two g groups stays one object",
          "[mesh][check][cli][objects]") {
  require_as_expected("groups-in-objects.obj");
  require_as_expected("one-shell-two-groups.obj");
  const ShellRun human = run_in_shell("check " + quoted(corpus("one-shell-two-groups.obj")));
  CHECK(human.out == corpus("one-shell-two-groups.obj") +
                         ": valid (8 vertices, 12 triangles, 1 component, genus 0, volume 1, area 6)\n"
                         "  OBJ file (no unit in the file)\n");
}

TEST_CASE("check objects: an OBJ of two g groups sharing no vertex is two objects",
          "[mesh][check][cli][objects]") {
  require_as_expected("two-shells-groups.obj");
}

TEST_CASE("check objects: a glTF of one mesh on two nodes is two objects, placed",
          "[mesh][check][cli][objects]") {
  require_as_expected("two-nodes.gltf");
}

TEST_CASE("check objects: the corpus manifest covers every file of the corpus", "[mesh][check][objects]") {
  const nlohmann::json m = manifest();
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(corpus(""))) {
    if (entry.path().filename() == "manifest.json") continue;
    ++files;
    bool listed = false;
    for (const auto& c : m["cases"]) listed = listed || c["file"] == entry.path().filename().string();
    CHECK(listed);
  }
  CHECK(files == m["cases"].size());
}

TEST_CASE("check objects: several files, one of several objects, give one entry per file",
          "[mesh][check][cli][objects]") {
  const ShellRun run = run_in_shell("check --json " + quoted(corpus("touching-cubes.3mf")) + " " +
                                    quoted(corpus("one-shell-two-groups.obj")));
  CHECK(run.code == 0);
  const auto j = nlohmann::json::parse(run.out);
  REQUIRE(j.is_array());
  REQUIRE(j.size() == 2);
  CHECK(j[0]["objects"].size() == 2);
  CHECK(j[1]["triangles"] == 12);
}
