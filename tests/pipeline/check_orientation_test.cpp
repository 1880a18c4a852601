// `fabmesh check` on meshes of several components: the real executable
// judges each component's orientation against its nesting (inverted
// components, nested shells of the same orientation, cavities), on files
// written in a temp folder and on the generated corpus of
// tests/data/check-corpus (scripts/make-check-corpus.py).

#include <algorithm>
#include <catch2/catch.hpp>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "io/mesh/obj.h"
#include "io/mesh/stl.h"
#include "tests/geometry/mesh/shapes.h"
#include "tests/io/mesh/temp_dir.h"
#include "tests/pipeline/json_item.h"
#include "tests/pipeline/shell_run.h"

using namespace fabmesh;
using test::TempDir;

using fabmesh::testing::only_item;
using fabmesh::testing::quoted;
using fabmesh::testing::run_in_shell;
using fabmesh::testing::ShellRun;

namespace {

TriangleSoup inverted(TriangleSoup soup) {
  for (auto& t : soup.triangles) std::swap(t[1], t[2]);
  return soup;
}

TriangleSoup cube(double lo, double hi) { return test::box(Vec3(lo, lo, lo), Vec3(hi, hi, hi)); }

TriangleSoup both(TriangleSoup first, const TriangleSoup& second) {
  test::append(first, second);
  return first;
}

/// `check --json` of `soup` written as OBJ (exact coordinates): the exit code and the report.
std::pair<int, nlohmann::json> check_json(const TriangleSoup& soup) {
  const TempDir dir;
  const std::string path = dir.file("mesh.obj");
  write_obj(soup, path);
  const ShellRun run = run_in_shell("check --json " + quoted(path));
  return {run.code, only_item(run.out)};
}

std::set<std::string> kinds(const nlohmann::json& report) {
  std::set<std::string> out;
  for (const auto& k : report.at("defect_kinds")) out.insert(k.get<std::string>());
  return out;
}

}  // namespace

TEST_CASE("check: a cube and a separate inverted cube is invalid, an inverted component",
          "[mesh][check][cli][orientation]") {
  const TriangleSoup soup = both(cube(0, 20), inverted(test::box(Vec3(30, 0, 0), Vec3(35, 5, 5))));
  const auto [code, j] = check_json(soup);
  CHECK(code == 1);
  CHECK(j["valid"] == false);
  CHECK(j["volume"] == 7875.0);
  CHECK(kinds(j) == std::set<std::string>{"inverted_component"});
  REQUIRE(j["component_shells"].size() == 2);
  CHECK(j["component_shells"][1]["orientation"] == "inward");
  CHECK(j["component_shells"][1]["depth"] == 0);
  CHECK(j["component_shells"][1]["faces"] == 12);
  CHECK(j["component_shells"][1]["volume"] == -125.0);

  const TempDir dir;
  write_obj(soup, dir.file("pair.obj"));
  const ShellRun human = run_in_shell("check " + quoted(dir.file("pair.obj")));
  CHECK(human.code == 1);
  CHECK_THAT(human.out, Catch::Contains("INVALID") && Catch::Contains("2 components") &&
                            Catch::Contains("inverted components: component 2 of 2") &&
                            Catch::Contains("faces inward inside no other component"));
}

TEST_CASE("check: two nested cubes facing the same way are invalid", "[mesh][check][cli][orientation]") {
  const auto [code, j] = check_json(both(cube(0, 20), cube(5, 10)));
  CHECK(code == 1);
  CHECK(kinds(j) == std::set<std::string>{"nested_same_orientation"});
  CHECK(j["component_shells"][1]["depth"] == 1);
  CHECK(j["component_shells"][1]["inside"] == 0);
}

TEST_CASE("check: a cube with an inward cavity is valid, volume outer minus inner",
          "[mesh][check][cli][orientation]") {
  const auto [code, j] = check_json(both(cube(0, 20), inverted(cube(5, 10))));
  CHECK(code == 0);
  CHECK(j["valid"] == true);
  CHECK(j["volume"] == 8000.0 - 125.0);
  CHECK(j["defect_kinds"].empty());
  REQUIRE(j["component_shells"].size() == 2);
  CHECK(j["component_shells"][0]["orientation"] == "outward");
  CHECK(j["component_shells"][1]["orientation"] == "inward");
  CHECK(j["component_shells"][1]["depth"] == 1);
}

TEST_CASE("check: two separate outward cubes are valid, each at depth 0", "[mesh][check][cli][orientation]") {
  const auto [code, j] = check_json(both(cube(0, 20), test::box(Vec3(30, 0, 0), Vec3(35, 5, 5))));
  CHECK(code == 0);
  CHECK(j["valid"] == true);
  REQUIRE(j["component_shells"].size() == 2);
  for (const auto& shell : j["component_shells"]) {
    CHECK(shell["depth"] == 0);
    CHECK(shell["orientation"] == "outward");
    CHECK(shell["inside"].is_null());
  }
}

TEST_CASE("check: a torus and a single inside-out cube keep their verdicts",
          "[mesh][check][cli][orientation]") {
  const TempDir dir;
  write_stl(test::torus(3.0, 1.0, 32, 16), dir.file("torus.stl"));
  const ShellRun torus = run_in_shell("check --json " + quoted(dir.file("torus.stl")));
  CHECK(torus.code == 0);
  const auto t = only_item(torus.out);
  REQUIRE(t["component_shells"].size() == 1);
  CHECK(t["component_shells"][0]["faces"] == 1024);
  CHECK(t["component_shells"][0]["depth"] == 0);

  const auto [code, j] = check_json(inverted(cube(0, 1)));
  CHECK(code == 1);
  CHECK(kinds(j) == std::set<std::string>{"inside_out"});  // not also an inverted component
  REQUIRE(j["component_shells"].size() == 1);
  CHECK(j["component_shells"][0]["orientation"] == "inward");
  write_obj(inverted(cube(0, 1)), dir.file("inside-out.obj"));
  const ShellRun human = run_in_shell("check " + quoted(dir.file("inside-out.obj")));
  CHECK_THAT(human.out, Catch::Contains("inside-out (non-positive volume) (volume -1)") &&
                            !Catch::Contains("inverted components"));
}

TEST_CASE("check: shells on shared planes nest by exact parity", "[mesh][check][cli][orientation]") {
  // An octahedron whose four equator vertices lie in the plane of the inner box's top face.
  TriangleSoup octahedron;
  octahedron.vertices = {{10, 10, -5}, {25, 10, 10}, {10, 25, 10}, {-5, 10, 10}, {10, -5, 10}, {10, 10, 25}};
  octahedron.triangles = {{0, 2, 1}, {0, 3, 2}, {0, 4, 3}, {0, 1, 4},
                          {5, 1, 2}, {5, 2, 3}, {5, 3, 4}, {5, 4, 1}};
  const TriangleSoup inner = test::box(Vec3(8, 8, 8), Vec3(12, 12, 10));
  const auto [cavity_code, cavity] = check_json(both(octahedron, inverted(inner)));
  CHECK(cavity_code == 0);
  CHECK(cavity["component_shells"][1]["depth"] == 1);
  const auto [nested_code, nested] = check_json(both(octahedron, inner));
  CHECK(nested_code == 1);
  CHECK(kinds(nested) == std::set<std::string>{"nested_same_orientation"});
  // A box within the octahedron's bounding box but outside it, its corner on the diagonal plane x = y.
  const auto [apart_code, apart] = check_json(both(octahedron, test::box(Vec3(20, 20, 0), Vec3(22, 22, 2))));
  CHECK(apart_code == 0);
  CHECK(apart["component_shells"][1]["depth"] == 0);
}

TEST_CASE("check: the corpus of tests/data/check-corpus gets its expected verdicts",
          "[mesh][check][cli][orientation]") {
  const std::string folder = std::string(FABMESH_SOURCE_DIR) + "/tests/data/check-corpus/";
  std::ifstream in(folder + "manifest.json");
  REQUIRE(in);
  const auto manifest = nlohmann::json::parse(in);
  REQUIRE(manifest["cases"].size() >= 3);
  for (const auto& entry : manifest["cases"]) {
    const std::string file = entry["file"];
    INFO(file);
    const ShellRun run = run_in_shell("check --json " + quoted(folder + file));
    const bool valid = entry["valid"];
    CHECK(run.code == (valid ? 0 : 1));
    const auto j = only_item(run.out);
    CHECK(j["valid"] == valid);
    std::set<std::string> expected;
    for (const auto& k : entry["defect_kinds"]) expected.insert(k.get<std::string>());
    CHECK(kinds(j) == expected);
  }
}
