// `fabmesh check` says where and what next (issues 43 and 44): defect
// locations in JSON, the marked mesh (GLB checked by the Khronos validator,
// PLY read back), the weld hint, standard input, one error line for an
// unreadable file, measures beyond doubles, and NaN as bad input.

#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <sstream>
#include <string>

#include "io/file.h"
#include "io/mesh/obj.h"
#include "io/mesh/off.h"
#include "io/mesh/read_mesh.h"
#include "io/mesh/stl.h"
#include "tests/geometry/mesh/shapes.h"
#include "tests/io/mesh/external_tool.h"
#include "tests/io/mesh/temp_dir.h"
#include "tests/pipeline/json_item.h"
#include "tests/pipeline/shell_run.h"

using namespace fabmesh;
using fabmesh::testing::only_item;
using fabmesh::testing::quoted;
using fabmesh::testing::run_in_shell;
using fabmesh::testing::ShellRun;
using test::TempDir;

namespace {

/// A cube less one face, and a second cube overlapping it: boundary edges
/// and intersecting faces.
TriangleSoup broken() {
  TriangleSoup s = test::box();
  s.triangles.pop_back();
  test::append(s, test::box(Vec3(5, 0.5, 0.5), Vec3(6, 1.5, 1.5)));
  test::append(s, test::box(Vec3(5.5, 0, 0), Vec3(6.5, 1, 1)));
  return s;
}

/// `fabmesh ARGS` with standard error joined to standard output.
test::ToolRun run_joined(const std::string& args) {
  return test::run_command(std::string("'") + FABMESH_BINARY + "' " + args + " 2>&1");
}

std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

/// The face colours of a binary PLY written by --mark: (red, green, blue) per face.
std::vector<std::array<std::uint8_t, 3>> ply_face_colours(const std::string& bytes) {
  const std::size_t body = bytes.find("end_header\n") + 11;
  REQUIRE(bytes.find("property uchar red\nproperty uchar green\nproperty uchar blue\n") < body);
  const auto count = [&](const std::string& element) {
    const std::size_t at = bytes.find("element " + element + " ");
    return std::stoul(bytes.substr(at + 9 + element.size()));
  };
  const std::size_t vertices = count("vertex");
  const std::size_t faces = count("face");
  std::vector<std::array<std::uint8_t, 3>> colours;
  std::size_t at = body + 12 * vertices;
  for (std::size_t f = 0; f < faces; ++f) {
    REQUIRE(static_cast<unsigned char>(bytes[at]) == 3);
    at += 1 + 12;
    colours.push_back({static_cast<std::uint8_t>(bytes[at]), static_cast<std::uint8_t>(bytes[at + 1]),
                       static_cast<std::uint8_t>(bytes[at + 2])});
    at += 3;
  }
  CHECK(at == bytes.size());
  return colours;
}

}  // namespace

TEST_CASE("check --json lists each defect's faces, vertices and coordinates, the first N with the count",
          "[mesh][check][cli][locations]") {
  const TempDir dir;
  const TriangleSoup mesh = broken();
  write_obj(mesh, dir.file("broken.obj"));
  const ShellRun run = run_in_shell("check --json " + quoted(dir.file("broken.obj")));
  CHECK(run.code == 1);
  const auto j = only_item(run.out);
  const auto& where = j["defect_locations"];
  REQUIRE(where.contains("boundary_edge"));
  REQUIRE(where.contains("self_intersection"));
  CHECK(where["boundary_edge"]["count"] == 3);
  CHECK(where["boundary_edge"]["listed"] == 3);
  for (const auto& at : where["boundary_edge"]["locations"]) {
    REQUIRE(at["faces"].size() == 1);
    REQUIRE(at["vertices"].size() == 2);
    for (std::size_t i = 0; i < 2; ++i) {
      const std::uint32_t v = at["vertices"][i];
      for (int k = 0; k < 3; ++k) CHECK(at["points"][i][k] == mesh.vertices[v][k]);  // the file's numbering
    }
  }
  const std::size_t pairs = where["self_intersection"]["count"];
  CHECK(pairs == j["intersecting_pairs"]);
  CHECK(where["self_intersection"]["listed"] == pairs);
  for (const auto& at : where["self_intersection"]["locations"]) {
    REQUIRE(at["faces"].size() == 2);
    CHECK(at["faces"][0] >= 11);  // the two overlapping cubes'
    CHECK(at["faces"][0] < 23);
    CHECK(at["faces"][1] >= 23);
  }
  // --max-locations bounds the list, never the count.
  const auto two =
      only_item(run_in_shell("check --json --max-locations 2 " + quoted(dir.file("broken.obj"))).out);
  CHECK(two["defect_locations"]["self_intersection"]["count"] == pairs);
  CHECK(two["defect_locations"]["self_intersection"]["listed"] == 2);
  CHECK(two["defect_locations"]["self_intersection"]["locations"].size() == 2);
  CHECK(two["defect_locations"]["boundary_edge"]["locations"].size() == 2);
  // A valid file has none; an STL names its vertices by corner (3 t + k).
  write_stl(test::box(), dir.file("cube.stl"));
  CHECK(only_item(run_in_shell("check --json " + quoted(dir.file("cube.stl"))).out)["defect_locations"]
            .empty());
  TriangleSoup open = test::box();
  open.triangles.pop_back();
  write_stl(open, dir.file("open.stl"));
  const auto stl = only_item(run_in_shell("check --json " + quoted(dir.file("open.stl"))).out);
  for (const auto& at : stl["defect_locations"]["boundary_edge"]["locations"]) {
    const std::uint32_t face = at["faces"][0];
    for (const auto& v : at["vertices"]) CHECK(v.get<std::uint32_t>() / 3 <= face);  // its lowest copy
  }
}

TEST_CASE("check --mark writes the mesh with defective faces coloured: a GLB the Khronos validator passes",
          "[mesh][check][cli][mark][validator]") {
  const TempDir dir;
  write_obj(broken(), dir.file("broken.obj"));
  const ShellRun run =
      run_in_shell("check " + quoted(dir.file("broken.obj")) + " --mark " + quoted(dir.file("marked.glb")));
  CHECK(run.code == 1);  // the verdict is unchanged
  INFO(run.out);
  CHECK(run.out.find("marked: " + dir.file("marked.glb")) != std::string::npos);
  CHECK(run.out.find("orange: 3 faces on a boundary edge") != std::string::npos);
  CHECK(run.out.find("red: ") != std::string::npos);
  CHECK(run.out.find("light grey: ") != std::string::npos);

  INFO("the Khronos glTF validator: run scripts/install-deps.sh (node, tools/node/node_modules)");
  REQUIRE(test::gltf_validator_installed());
  const test::ToolRun validated = test::run_tool(test::gltf_validator_command(dir.file("marked.glb")));
  INFO(validated.output);
  REQUIRE(validated.code == 0);
  const auto report = nlohmann::json::parse(validated.output.substr(0, validated.output.rfind('}') + 1));
  CHECK(report["issues"]["numErrors"] == 0);
  CHECK(report["issues"]["numWarnings"] == 0);
  CHECK(report["issues"]["numHints"] == 0);
  // Read back: every face is there, once (the primitives together are the mesh).
  const MeshFile back = read_mesh_file(dir.file("marked.glb"));
  CHECK(back.soup.triangles.size() == broken().triangles.size());
}

TEST_CASE("check --mark OUT.ply colours each face by its defect kind, read back",
          "[mesh][check][cli][mark]") {
  const TempDir dir;
  const TriangleSoup mesh = broken();
  write_obj(mesh, dir.file("broken.obj"));
  const ShellRun json = run_in_shell("check --json " + quoted(dir.file("broken.obj")) + " --mark " +
                                     quoted(dir.file("marked.ply")));
  CHECK(json.code == 1);
  const auto j = only_item(json.out);  // the JSON stays one document: no legend in it
  const std::string bytes = read_file(dir.file("marked.ply"));
  const TriangleSoup back = read_mesh(dir.file("marked.ply"));
  CHECK(back.triangles.size() == mesh.triangles.size());
  const auto colours = ply_face_colours(bytes);
  REQUIRE(colours.size() == mesh.triangles.size());
  const std::array<std::uint8_t, 3> orange{255, 140, 0}, red{230, 0, 0}, grey{200, 200, 200};
  std::set<std::uint32_t> on_boundary, crossing;
  for (const auto& at : j["defect_locations"]["boundary_edge"]["locations"])
    on_boundary.insert(at["faces"][0].get<std::uint32_t>());
  for (const auto& at : j["defect_locations"]["self_intersection"]["locations"]) {
    crossing.insert(at["faces"][0].get<std::uint32_t>());
    crossing.insert(at["faces"][1].get<std::uint32_t>());
  }
  for (std::uint32_t f = 0; f < colours.size(); ++f) {
    INFO("face " << f);
    if (on_boundary.count(f)) {
      CHECK(colours[f] == orange);
    } else if (crossing.count(f)) {
      CHECK(colours[f] == red);
    } else {
      CHECK(colours[f] == grey);
    }
  }
  CHECK(
      run_in_shell("check " + quoted(dir.file("broken.obj")) + " --mark " + quoted(dir.file("m.png"))).code ==
      2);
  CHECK(run_in_shell("check " + quoted(dir.file("broken.obj")) + " " + quoted(dir.file("broken.obj")) +
                     " --mark " + quoted(dir.file("m.ply")))
            .code == 2);  // one file only
}

TEST_CASE("check: an STL whose corners are jittered by 1e-5 gets the weld tolerance that makes it valid",
          "[mesh][check][cli][weld]") {
  const TempDir dir;
  TriangleSoup noisy = test::unwelded(test::torus(30.0, 10.0, 64, 32));
  std::mt19937 random(43);
  std::uniform_real_distribution<double> offset(-1e-5, 1e-5);
  for (Vec3& p : noisy.vertices) p += Vec3(offset(random), offset(random), offset(random));
  write_obj(noisy, dir.file("noisy.obj"));  // OBJ keeps the jitter (an STL's float32 would round most of it)
  const ShellRun human = run_in_shell("check " + quoted(dir.file("noisy.obj")));
  INFO(human.out);
  CHECK(human.code == 1);
  CHECK(human.out.find("hint: --weld-tolerance ") != std::string::npos);
  CHECK(human.out.find("makes the mesh valid") != std::string::npos);
  const auto j = only_item(run_in_shell("check --json " + quoted(dir.file("noisy.obj"))).out);
  REQUIRE(j["weld_hint"].is_object());
  const double tolerance = j["weld_hint"]["tolerance"];
  CHECK(tolerance < 2 * std::sqrt(3.0) * 1.1e-5);
  CHECK(tolerance < j["weld_hint"]["mean_edge"].get<double>() / 20);
  CHECK(j["weld_hint"]["valid_after"] == true);
  // The hint is right: welding with it makes the file valid.
  std::ostringstream value;
  value.precision(17);
  value << tolerance;
  CHECK(run_in_shell("check --weld-tolerance " + value.str() + " " + quoted(dir.file("noisy.obj"))).code ==
        0);
  // No hint for a real hole, nor for a valid file.
  TriangleSoup open = test::box();
  open.triangles.pop_back();
  write_obj(open, dir.file("open.obj"));
  CHECK(only_item(run_in_shell("check --json " + quoted(dir.file("open.obj"))).out)["weld_hint"].is_null());
  CHECK(run_in_shell("check " + quoted(dir.file("open.obj"))).out.find("hint:") == std::string::npos);
}

TEST_CASE("check - reads the mesh from standard input, any format by content", "[mesh][check][cli]") {
  const TempDir dir;
  write_stl(test::torus(3.0, 1.0, 32, 16), dir.file("torus.stl"));
  write_off(test::box(), dir.file("cube.off"));
  const ShellRun stl = run_in_shell("check - < " + quoted(dir.file("torus.stl")));
  CHECK(stl.code == 0);
  CHECK(stl.out.find("-: valid") != std::string::npos);
  CHECK(stl.out.find("genus 1") != std::string::npos);
  const ShellRun off = run_in_shell("check --json - < " + quoted(dir.file("cube.off")));
  CHECK(off.code == 0);
  CHECK(only_item(off.out)["format"] == "OFF");
  CHECK(only_item(off.out)["file"] == "-");
  CHECK(run_in_shell("check - < /dev/null").code == 2);  // empty: not a mesh
  CHECK(run_in_shell("check - - < " + quoted(dir.file("cube.off"))).code == 2);
}

TEST_CASE("check: an unreadable file's error is printed once", "[mesh][check][cli]") {
  const TempDir dir;
  dir.write("junk.stl", "this is not a mesh at all");
  const test::ToolRun run = run_joined("check " + quoted(dir.file("junk.stl")));
  INFO(run.output);
  CHECK(run.code == 2);
  CHECK(occurrences(run.output, "junk.stl") == 1);
}

TEST_CASE("check: a cube of coordinates near 1e300 is valid, its volume and area never NaN",
          "[mesh][check][cli]") {
  const TempDir dir;
  write_off(test::box(Vec3(0, 0, 0), Vec3(1e300, 1e300, 1e300)), dir.file("huge.off"));
  const ShellRun run = run_in_shell("check " + quoted(dir.file("huge.off")));
  INFO(run.out);
  CHECK(run.code == 0);
  CHECK(run.out.find("nan") == std::string::npos);
  CHECK(run.out.find("inf") == std::string::npos);
  CHECK(run.out.find("volume beyond 1.79769e+308 (not representable)") != std::string::npos);
}
