// `fabmesh check` end to end: the real executable on files written in a temp folder.

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "io/mesh/obj.h"
#include "io/mesh/off.h"
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

TEST_CASE("check: a valid STL exits 0 and reports what the weld merged", "[mesh][check][cli]") {
  const TempDir dir;
  const std::string path = dir.file("torus.stl");
  write_stl(test::torus(3.0, 1.0, 32, 16), path);
  const ShellRun human = run_in_shell("check " + quoted(path));
  CHECK(human.code == 0);
  CHECK(human.out.find("valid") != std::string::npos);
  CHECK(human.out.find("genus 1") != std::string::npos);
  CHECK(human.out.find("welded 2560 coincident vertices (normal for STL") !=
        std::string::npos);  // 3 * 1024 - 512

  const ShellRun json = run_in_shell("check --json " + quoted(path));
  CHECK(json.code == 0);
  const auto j = only_item(json.out);
  for (const char* key :
       {"file", "vertices", "triangles", "components", "boundary_edges", "non_manifold_edges",
        "non_manifold_vertices", "degenerate_faces", "duplicate_faces", "self_intersecting",
        "oriented_outward", "volume", "area", "genus", "valid", "welded_vertices", "timings_ms"}) {
    CHECK(j.contains(key));
  }
  CHECK(j["file"] == path);
  CHECK(j["vertices"] == 512);
  CHECK(j["triangles"] == 1024);
  CHECK(j["genus"] == 1);
  CHECK(j["valid"] == true);
  CHECK(j["welded_vertices"] == 2560);
  CHECK(j["timings_ms"].contains("self_intersection"));
}

TEST_CASE("check: an invalid mesh exits 1 and names its defects", "[mesh][check][cli]") {
  const TempDir dir;
  TriangleSoup open = test::box();
  open.triangles.pop_back();
  write_off(open, dir.file("open.off"));
  const ShellRun human = run_in_shell("check " + quoted(dir.file("open.off")));
  CHECK(human.code == 1);
  CHECK(human.out.find("INVALID") != std::string::npos);
  CHECK(human.out.find("3 boundary edges") != std::string::npos);
  const auto j = only_item(run_in_shell("check --json " + quoted(dir.file("open.off"))).out);
  CHECK(j["boundary_edges"] == 3);
  CHECK(j["valid"] == false);
  CHECK(j["genus"].is_null());
}

TEST_CASE("check: several files give a JSON array, and any invalid exits 1, any unreadable exits 2",
          "[mesh][check][cli]") {
  const TempDir dir;
  write_obj(test::box(), dir.file("cube.obj"));
  TriangleSoup inside_out = test::box();
  for (auto& t : inside_out.triangles) std::swap(t[1], t[2]);
  write_obj(inside_out, dir.file("inside_out.obj"));
  std::string lying = encode_stl(test::box());
  lying[80] = 13;  // claims 13 triangles, holds 12
  dir.write("lying.stl", lying);

  const ShellRun both =
      run_in_shell("check --json " + quoted(dir.file("cube.obj")) + " " + quoted(dir.file("inside_out.obj")));
  CHECK(both.code == 1);
  const auto j = nlohmann::json::parse(both.out);
  REQUIRE(j.is_array());
  REQUIRE(j.size() == 2);
  CHECK(j[0]["valid"] == true);
  CHECK(j[1]["valid"] == false);
  CHECK(j[1]["oriented_outward"] == false);

  CHECK(run_in_shell("check " + quoted(dir.file("cube.obj"))).code == 0);
  CHECK(run_in_shell("check " + quoted(dir.file("lying.stl"))).code == 2);
  CHECK(run_in_shell("check " + quoted(dir.file("cube.obj")) + " " + quoted(dir.file("lying.stl"))).code ==
        2);
  CHECK(run_in_shell("check " + quoted(dir.file("missing.stl"))).code == 2);
  CHECK(run_in_shell("check --weld-tolerance -1 " + quoted(dir.file("cube.obj"))).code == 2);
  CHECK(run_in_shell("check").code == 2);  // MESH is required
}

TEST_CASE("check: --weld-tolerance closes cracks that exact welding leaves open", "[mesh][check][cli]") {
  const TempDir dir;
  TriangleSoup cracked = test::unwelded(test::box());
  cracked.vertices[0].x() += 1e-9;  // one corner copy is a hair off
  write_obj(cracked, dir.file("cracked.obj"));
  CHECK(run_in_shell("check " + quoted(dir.file("cracked.obj"))).code == 1);
  CHECK(run_in_shell("check --weld-tolerance 1e-6 " + quoted(dir.file("cracked.obj"))).code == 0);
}
