// MeshFile::objects: the bodies of a mesh file, format by format.

#include <catch2/catch.hpp>
#include <string>

#include "geometry/core/errors.h"
#include "io/file.h"
#include "io/mesh/obj.h"
#include "io/mesh/read_mesh.h"
#include "io/mesh/stl.h"
#include "io/mesh/threemf.h"
#include "tests/geometry/mesh/shapes.h"

using namespace fabmesh;

namespace {

/// A cube's OBJ vertex records at `x` (8 `v` lines).
std::string cube_vertices(int x) {
  std::string text;
  for (int k = 0; k < 8; ++k) {
    text += "v " + std::to_string(x + (k & 1)) + " " + std::to_string((k >> 1) & 1) + " " +
            std::to_string((k >> 2) & 1) + "\n";
  }
  return text;
}

/// The faces of test::box() as OBJ `f` records over vertices base+1...; faces [from, to).
std::string cube_faces(int base, std::size_t from = 0, std::size_t to = 12) {
  const TriangleSoup cube = test::box();
  std::string text;
  for (std::size_t f = from; f < to; ++f) {
    const auto& t = cube.triangles[f];
    text += "f " + std::to_string(base + t[0] + 1) + " " + std::to_string(base + t[1] + 1) + " " +
            std::to_string(base + t[2] + 1) + "\n";
  }
  return text;
}

std::string corpus(const std::string& name) {
  return std::string(FABMESH_SOURCE_DIR) + "/tests/data/check-corpus/objects/" + name;
}

/// A 3MF model part: a mesh object id 1 ("cube"), a components object id 2
/// placing it twice, an empty mesh id 3, and build items as `items` says.
std::string components_model(const std::string& items) {
  const TriangleSoup cube = test::box();
  std::string xml = R"(<?xml version="1.0" encoding="UTF-8"?><model unit="millimeter" )"
                    R"(xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02"><resources>)"
                    R"(<object id="1" type="model" name="cube"><mesh><vertices>)";
  for (const Vec3& p : cube.vertices)
    xml += "<vertex x=\"" + std::to_string(p.x()) + "\" y=\"" + std::to_string(p.y()) + "\" z=\"" +
           std::to_string(p.z()) + "\"/>";
  xml += "</vertices><triangles>";
  for (const auto& t : cube.triangles)
    xml += "<triangle v1=\"" + std::to_string(t[0]) + "\" v2=\"" + std::to_string(t[1]) + "\" v3=\"" +
           std::to_string(t[2]) + "\"/>";
  xml += "</triangles></mesh></object>";
  xml += R"(<object id="2" type="model"><components><component objectid="1"/>)"
         R"(<component objectid="1" transform="1 0 0 0 1 0 0 0 1 5 0 0"/></components></object>)";
  xml += R"(<object id="3" type="model" name="empty"><mesh><vertices/><triangles/></mesh></object>)";
  return xml + "</resources><build>" + items + "</build></model>";
}

}  // namespace

TEST_CASE("objects: single-object formats and single-object files have none apart", "[mesh][objects]") {
  const MeshFile stl = parse_mesh_file(encode_stl(test::box()), "cube.stl");
  CHECK(stl.objects.empty());
  CHECK(stl.soup.triangles.size() == 12);
  const MeshFile obj = parse_mesh_file(cube_vertices(0) + "o only\n" + cube_faces(0), "cube.obj");
  CHECK(obj.objects.empty());
  const MeshFile threemf = parse_mesh_file(threemf_package(components_model(R"(<item objectid="1"/>)")), "x");
  CHECK(threemf.objects.empty());
}

TEST_CASE("objects: 3MF build items with components expanded and transforms applied", "[mesh][objects]") {
  const std::string bytes = threemf_package(
      components_model(R"(<item objectid="1" transform="1 0 0 0 1 0 0 0 1 0 0 10"/><item objectid="2"/>)"));
  const MeshFile file = parse_mesh_file(bytes, "two.3mf");
  REQUIRE(file.objects.size() == 2);
  CHECK(file.objects[0].name == "cube");
  CHECK(file.objects[1].name == "object 2");  // no name attribute: its id
  CHECK(file.objects[0].soup.triangles.size() == 12);
  CHECK(file.objects[1].soup.triangles.size() == 24);  // the cube twice
  CHECK(file.objects[0].soup.vertices[0].z() == 10);
  CHECK(file.objects[1].soup.vertices[8].x() == 5);
  // The merged soup is parse_mesh's, as before.
  CHECK(file.soup.triangles.size() == 36);
  CHECK(parse_mesh(bytes, "two.3mf").triangles.size() == 36);
}

TEST_CASE("objects: 3MF build items without a triangle are left out", "[mesh][objects]") {
  const std::string one = threemf_package(components_model(R"(<item objectid="1"/><item objectid="3"/>)"));
  CHECK(parse_mesh_file(one, "one.3mf").objects.empty());
  const std::string two =
      threemf_package(components_model(R"(<item objectid="3"/><item objectid="1"/><item objectid="2"/>)"));
  const MeshFile file = parse_mesh_file(two, "two.3mf");
  REQUIRE(file.objects.size() == 2);
  CHECK(file.objects[0].name == "cube");
}

TEST_CASE("objects: OBJ o objects are apart, named", "[mesh][objects]") {
  const std::string text =
      cube_vertices(0) + cube_vertices(1) + "o left\n" + cube_faces(0) + "o right\n" + cube_faces(8);
  const MeshFile file = parse_mesh_file(text, "two.obj");
  REQUIRE(file.objects.size() == 2);
  CHECK(file.objects[0].name == "left");
  CHECK(file.objects[1].name == "right");
  CHECK(file.objects[1].soup.vertices.size() == 8);
  CHECK(file.objects[1].soup.triangles.size() == 12);
  CHECK(file.objects[1].soup.vertices[file.objects[1].soup.triangles[0][0]].x() >= 1);
  CHECK(file.soup.triangles.size() == 24);
  CHECK(parse_obj(text, "two.obj").triangles.size() == 24);
}

TEST_CASE("objects: OBJ g groups are apart only as separate shells", "[mesh][objects]") {
  SECTION("groups sharing vertices are one object") {
    const MeshFile file = parse_mesh_file(
        cube_vertices(0) + "g red\n" + cube_faces(0, 0, 6) + "g blue\n" + cube_faces(0, 6), "x.obj");
    CHECK(file.objects.empty());
    CHECK(file.soup.triangles.size() == 12);
  }
  SECTION("groups whose vertices are distinct but coincide are one object") {
    const MeshFile file = parse_mesh_file(
        cube_vertices(0) + cube_vertices(0) + "g red\n" + cube_faces(0, 0, 6) + "g blue\n" + cube_faces(8, 6),
        "x.obj");
    CHECK(file.objects.empty());
  }
  SECTION("groups sharing nothing are apart, a group again later joins its own") {
    const std::string text = cube_vertices(0) + cube_vertices(3) + "g a\n" + cube_faces(0, 0, 6) + "g b\n" +
                             cube_faces(8) + "g a\n" + cube_faces(0, 6);
    const ObjContent content = parse_obj_objects(text, "x.obj");
    CHECK(content.object_names == std::vector<std::string>{"a", "b"});
    const MeshFile file = parse_mesh_file(text, "x.obj");
    REQUIRE(file.objects.size() == 2);
    CHECK(file.objects[0].soup.triangles.size() == 12);
    CHECK(file.objects[1].soup.triangles.size() == 12);
  }
  SECTION("shells of a named o are named o/g, and o objects never join") {
    const std::string text = cube_vertices(0) + cube_vertices(3) + cube_vertices(1) + "o pair\ng first\n" +
                             cube_faces(0) + "g second\n" + cube_faces(8) + "o touching\n" + cube_faces(16);
    const MeshFile file = parse_mesh_file(text, "x.obj");
    REQUIRE(file.objects.size() == 3);
    CHECK(file.objects[0].name == "pair/first");
    CHECK(file.objects[1].name == "pair/second");
    CHECK(file.objects[2].name == "touching");
  }
}

TEST_CASE("objects: glTF node instances of a mesh, placed by their nodes", "[mesh][objects]") {
  const MeshFile file = read_mesh_file(corpus("two-nodes.gltf"));
  REQUIRE(file.objects.size() == 2);
  CHECK(file.objects[0].name == "left");
  CHECK(file.objects[1].name == "cube (node 1)");
  for (std::size_t k = 0; k < 8; ++k) {
    CHECK(file.objects[1].soup.vertices[k] == file.objects[0].soup.vertices[k] + Vec3(0.5, 0.5, 0.5));
  }
  CHECK(file.objects[1].soup.triangles == file.objects[0].soup.triangles);
  CHECK(file.soup.triangles.size() == 24);
}
