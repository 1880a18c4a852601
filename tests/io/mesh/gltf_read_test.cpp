// parse_gltf on hand-built glTF documents: what it must read (transforms,
// strips, fans, sparse and quantized accessors, embedded buffers) and what it
// must refuse with a FileError. The valid documents are checked by the
// Khronos validator too, so the expectations are glTF's, not the reader's.

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <functional>
#include <nlohmann/json.hpp>

#include "geometry/core/errors.h"
#include "geometry/mesh/weld.h"
#include "geometry/validation/validate.h"
#include "io/mesh/gltf.h"
#include "io/mesh/read_mesh.h"
#include "tests/geometry/mesh/shapes.h"
#include "tests/io/mesh/external_tool.h"
#include "tests/io/mesh/temp_dir.h"

using namespace fabmesh;
using Json = nlohmann::json;
using test::TempDir;

namespace {

std::uint32_t u32_at(const std::string& b, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= std::uint32_t{static_cast<unsigned char>(b[at + i])} << (8 * i);
  return v;
}

std::string base64(const std::string& bytes) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const auto n = (std::uint32_t{static_cast<unsigned char>(bytes[i])} << 16) |
                   (std::uint32_t{static_cast<unsigned char>(bytes[i + 1])} << 8) |
                   static_cast<unsigned char>(bytes[i + 2]);
    for (int s = 18; s >= 0; s -= 6) out.push_back(k[(n >> s) & 63]);
  }
  if (i < bytes.size()) {
    std::uint32_t n = std::uint32_t{static_cast<unsigned char>(bytes[i])} << 16;
    if (i + 1 < bytes.size()) n |= std::uint32_t{static_cast<unsigned char>(bytes[i + 1])} << 8;
    out.push_back(k[(n >> 18) & 63]);
    out.push_back(k[(n >> 12) & 63]);
    out.push_back(i + 1 < bytes.size() ? k[(n >> 6) & 63] : '=');
    out.push_back('=');
  }
  return out;
}

/// Builds one buffer of little-endian data and the views and accessors on it.
class DocBuilder {
 public:
  DocBuilder() {
    doc_["asset"] = {{"version", "2.0"}, {"generator", "fabmesh tests"}};
    doc_["accessors"] = Json::array();
    doc_["bufferViews"] = Json::array();
  }
  /// Appends a view of `bytes` (4-aligned); returns its index.
  int view(const std::string& bytes, int target = 0) {
    while (bin_.size() % 4 != 0) bin_.push_back('\0');
    Json v = {{"buffer", 0}, {"byteOffset", bin_.size()}, {"byteLength", bytes.size()}};
    if (target != 0) v["target"] = target;
    bin_ += bytes;
    doc_["bufferViews"].push_back(v);
    return static_cast<int>(doc_["bufferViews"].size() - 1);
  }
  int accessor(Json a) {
    doc_["accessors"].push_back(std::move(a));
    return static_cast<int>(doc_["accessors"].size() - 1);
  }
  /// A float VEC3 accessor (with exact min/max) on a new view.
  int positions(const std::vector<Vec3>& points) {
    std::string bytes;
    std::array<float, 3> lo{}, hi{};
    for (std::size_t i = 0; i < points.size(); ++i) {
      for (int k = 0; k < 3; ++k) {
        const auto f = static_cast<float>(points[i][k]);
        lo[k] = i == 0 ? f : std::min(lo[k], f);
        hi[k] = i == 0 ? f : std::max(hi[k], f);
        bytes.append(reinterpret_cast<const char*>(&f), 4);
      }
    }
    return accessor({{"bufferView", view(bytes, 34962)},
                     {"componentType", 5126},
                     {"count", points.size()},
                     {"type", "VEC3"},
                     {"min", {lo[0], lo[1], lo[2]}},
                     {"max", {hi[0], hi[1], hi[2]}}});
  }
  /// An index accessor of `type` (5121, 5123, 5125) on a new view.
  int indices(const std::vector<std::uint32_t>& values, int type) {
    std::string bytes;
    const int size = type == 5121 ? 1 : type == 5123 ? 2 : 4;
    for (const std::uint32_t v : values) bytes.append(reinterpret_cast<const char*>(&v), size);
    return accessor({{"bufferView", view(bytes, 34963)},
                     {"componentType", type},
                     {"count", values.size()},
                     {"type", "SCALAR"}});
  }
  Json& doc() { return doc_; }
  /// The document as .gltf text, the buffer as a base64 data: URI.
  std::string gltf() {
    while (bin_.size() % 4 != 0) bin_.push_back('\0');
    doc_["buffers"] = Json::array(
        {{{"byteLength", bin_.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin_)}}});
    return doc_.dump();
  }

 private:
  Json doc_;
  std::string bin_;
};

std::vector<std::uint32_t> flat(const TriangleSoup& soup) {
  std::vector<std::uint32_t> out;
  for (const auto& t : soup.triangles) out.insert(out.end(), t.begin(), t.end());
  return out;
}

void require_valid_gltf(const std::string& name, const std::string& text) {
  const TempDir dir;
  INFO("the Khronos glTF validator: run scripts/install-deps.sh (node, tools/node/node_modules)");
  REQUIRE(test::gltf_validator_installed());
  dir.write(name, text);
  const test::ToolRun run = test::run_tool(test::gltf_validator_command(dir.file(name)));
  INFO(run.output);
  REQUIRE(run.code == 0);
}

}  // namespace

TEST_CASE("gltf: node transforms (TRS, matrix, hierarchy) place every instance and a mirror stays outward",
          "[io][gltf]") {
  DocBuilder b;
  const TriangleSoup cube = test::box();
  const int pos = b.positions(cube.vertices);
  const int idx = b.indices(flat(cube), 5121);
  b.doc()["meshes"] = {{{"primitives", {{{"attributes", {{"POSITION", pos}}}, {"indices", idx}}}}}};
  const double h = std::sqrt(0.5);
  b.doc()["nodes"] = {
      // scale 2, a quarter turn about y, then a move: an 8-volume cube at x in [10, 12]
      {{"mesh", 0}, {"translation", {10, 0, 0}}, {"rotation", {0, h, 0, h}}, {"scale", {2, 2, 2}}},
      // mirrored in x by a column-major matrix, moved to x in [-4, -3]
      {{"mesh", 0}, {"matrix", {-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -3, 0, 0, 1}}},
      // a parent moving its child up by 5
      {{"translation", {0, 5, 0}}, {"children", {3}}},
      {{"mesh", 0}}};
  b.doc()["scenes"] = {{{"nodes", {0, 1, 2}}}};
  b.doc()["scene"] = 0;
  const std::string text = b.gltf();
  require_valid_gltf("transforms.gltf", text);
  CHECK(detect_format(text, "t.json") == MeshFormat::Gltf);
  const GltfContent c = parse_gltf(text, "transforms.gltf");
  CHECK(c.primitives == 3);
  CHECK(c.transformed_instances == 3);
  CHECK(c.mirrored_instances == 1);
  const ValidationReport r = validate(weld(c.soup).soup);
  CHECK(r.valid());
  CHECK(r.components == 3);
  CHECK(r.volume == Approx(8.0 + 1.0 + 1.0));
  CHECK(c.soup.vertices[16] == Vec3(0, 5, 0));  // the child's first vertex, moved by its parent
}

TEST_CASE("gltf: strips, fans, non-indexed, sparse and quantized accessors are read, points skipped",
          "[io][gltf]") {
  DocBuilder b;
  // A unit square at z = 0 as a strip (0 1 2 3 zig-zag) and at z = 1 as a fan.
  const int strip_pos = b.positions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}});
  const int fan_pos = b.positions({{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}});
  // A non-indexed tetrahedron.
  const TriangleSoup tet = test::tetrahedron(Vec3(0, 0, 5), 1.0, 1.0);
  std::vector<Vec3> soup_points;
  for (const auto& t : tet.triangles)
    for (const std::uint32_t i : t) soup_points.push_back(tet.vertices[i]);
  const int tet_pos = b.positions(soup_points);
  // A cube as a sparse accessor: zeros, then 7 replaced vertices, indices uint16.
  const TriangleSoup cube = test::box(Vec3(0, 0, 10), Vec3(1, 1, 11));
  std::string sparse_idx;
  std::string sparse_val;
  for (std::uint8_t i = 0; i < 8; ++i) {
    sparse_idx.push_back(static_cast<char>(i));
    for (int k = 0; k < 3; ++k) {
      const auto f = static_cast<float>(cube.vertices[i][k]);
      sparse_val.append(reinterpret_cast<const char*>(&f), 4);
    }
  }
  const int sparse_pos =
      b.accessor({{"componentType", 5126},
                  {"count", 8},
                  {"type", "VEC3"},
                  {"min", {0, 0, 10}},
                  {"max", {1, 1, 11}},
                  {"sparse",
                   {{"count", 8},
                    {"indices", {{"bufferView", b.view(sparse_idx)}, {"componentType", 5121}}},
                    {"values", {{"bufferView", b.view(sparse_val)}}}}}});
  const int cube_idx = b.indices(flat(cube), 5123);
  // KHR_mesh_quantization: a unit cube as normalized unsigned shorts (65535 = 1).
  std::string q;
  for (const Vec3& p : test::box().vertices) {
    for (int k = 0; k < 3; ++k) {
      const std::uint16_t v = p[k] > 0 ? 65535 : 0;
      q.append(reinterpret_cast<const char*>(&v), 2);
    }
    q.append(2, '\0');  // a vertex attribute element is 4-byte aligned: stride 8
  }
  const int q_view = b.view(q, 34962);
  b.doc()["bufferViews"][q_view]["byteStride"] = 8;
  const int q_pos = b.accessor({{"bufferView", q_view},
                                {"componentType", 5123},
                                {"normalized", true},
                                {"count", 8},
                                {"type", "VEC3"},
                                {"min", {0, 0, 0}},
                                {"max", {65535, 65535, 65535}}});
  const int q_idx = b.indices(flat(test::box()), 5125);
  b.doc()["extensionsUsed"] = {"KHR_mesh_quantization"};
  b.doc()["extensionsRequired"] = {"KHR_mesh_quantization"};
  b.doc()["meshes"] = {{{"primitives",
                         {{{"attributes", {{"POSITION", strip_pos}}}, {"mode", 5}},
                          {{"attributes", {{"POSITION", fan_pos}}}, {"mode", 6}},
                          {{"attributes", {{"POSITION", tet_pos}}}},
                          {{"attributes", {{"POSITION", sparse_pos}}}, {"indices", cube_idx}},
                          {{"attributes", {{"POSITION", strip_pos}}}, {"mode", 0}}}}},
                       {{"primitives", {{{"attributes", {{"POSITION", q_pos}}}, {"indices", q_idx}}}}}};
  b.doc()["nodes"] = {{{"mesh", 0}}, {{"mesh", 1}, {"translation", {0, 0, 20}}}};
  b.doc()["scenes"] = {{{"nodes", {0, 1}}}};
  const std::string text = b.gltf();
  require_valid_gltf("kinds.gltf", text);
  const GltfContent c = parse_gltf(text, "kinds.gltf");
  CHECK(c.primitives == 5);
  CHECK(c.skipped_primitives == 1);
  REQUIRE(c.soup.triangles.size() == 2 + 2 + 4 + 12 + 12);
  // Strip: (0 1 2), (1 3 2); fan: (1 2 0), (2 3 0): all counter-clockwise seen from +z.
  for (int t = 0; t < 4; ++t) {
    const auto& f = c.soup.triangles[t];
    const Vec3 n =
        (c.soup.vertices[f[1]] - c.soup.vertices[f[0]]).cross(c.soup.vertices[f[2]] - c.soup.vertices[f[0]]);
    CHECK(n.z() == Approx(1.0));
  }
  // The closed parts (tetrahedron, sparse cube, quantized cube) are valid solids.
  TriangleSoup solids = c.soup;
  solids.triangles.erase(solids.triangles.begin(), solids.triangles.begin() + 4);
  const ValidationReport r = validate(weld(solids).soup);
  CHECK(r.valid());
  CHECK(r.components == 3);
  CHECK(r.volume == Approx(validate(tet).volume + 1.0 + 1.0));
  CHECK(c.soup.vertices.back() == Vec3(1, 1, 21));
}

TEST_CASE("gltf: a buffer in an external file is refused and no file is opened", "[io][gltf]") {
  const TempDir dir;
  dir.write("mesh.bin", std::string(36, '\0'));
  Json doc = {{"asset", {{"version", "2.0"}}},
              {"buffers", {{{"byteLength", 36}, {"uri", "mesh.bin"}}}},
              {"bufferViews", {{{"buffer", 0}, {"byteLength", 36}}}},
              {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}}}},
              {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}}}}}}},
              {"nodes", {{{"mesh", 0}}}}};
  try {
    read_mesh(dir.write("mesh.gltf", doc.dump()));
    FAIL("no exception");
  } catch (const FileError& e) {
    CHECK(std::string(e.what()).find("external file 'mesh.bin'") != std::string::npos);
  }
}

TEST_CASE("gltf: malformed GLB and glTF are FileErrors naming the file", "[io][gltf]") {
  const std::string glb = encode_glb(test::box(), {});
  const auto put_u32 = [](std::string& s, std::size_t at, std::uint32_t v) { std::memcpy(&s[at], &v, 4); };
  std::vector<std::pair<std::string, std::string>> bad = {
      {"empty", ""},
      {"magic only", "glTF"},
      {"truncated", glb.substr(0, glb.size() - 4)},
      {"trailing bytes", glb + "abcd"},
      {"not json", "{ this is not json"},
      {"json without asset", "{\"meshes\": []}"},
      {"glTF 1", "{\"asset\": {\"version\": \"1.0\"}}"},
  };
  {
    // The BIN chunk claims 8 more bytes than the file holds (tinygltf 2.7 reads them).
    std::string b = glb;
    const std::size_t bin_header = 20 + u32_at(glb, 12);
    put_u32(b, bin_header, u32_at(glb, bin_header) + 8);
    bad.emplace_back("BIN chunk overrun", b);
  }
  const auto with = [&](const std::string& what, const std::function<void(Json&)>& edit) {
    Json doc = Json::parse(glb.substr(20, u32_at(glb, 12)));
    edit(doc);
    std::string json = doc.dump();
    while (json.size() % 4 != 0) json.push_back(' ');
    const std::string bin = glb.substr(20 + u32_at(glb, 12));
    std::string out = glb.substr(0, 20) + json + bin;
    put_u32(out, 8, static_cast<std::uint32_t>(out.size()));
    put_u32(out, 12, static_cast<std::uint32_t>(json.size()));
    bad.emplace_back(what, out);
  };
  with("accessor out of range", [](Json& d) { d["meshes"][0]["primitives"][0]["indices"] = 7; });
  with("negative index", [](Json& d) { d["meshes"][0]["primitives"][0]["indices"] = -1; });
  with("count too large", [](Json& d) { d["accessors"][1]["count"] = 1000000; });
  with("offset past the view", [](Json& d) { d["accessors"][0]["byteOffset"] = 1u << 31; });
  with("view past the buffer", [](Json& d) { d["bufferViews"][1]["byteLength"] = 1u << 30; });
  with("index past the vertices", [](Json& d) {
    d["accessors"][1]["count"] = 2;
    d["bufferViews"][1]["byteLength"] = 24;
  });
  with("node cycle", [](Json& d) {
    d["nodes"][0]["children"] = {1};
    d["nodes"].push_back({{"children", {0}}});
  });
  with("unknown required extension", [](Json& d) {
    d["extensionsUsed"] = {"EXT_meshopt_compression"};
    d["extensionsRequired"] = {"EXT_meshopt_compression"};
  });
  with("bad mode", [](Json& d) { d["meshes"][0]["primitives"][0]["mode"] = 9; });
  with("no scene node", [](Json& d) { d["scenes"][0]["nodes"] = {5}; });
  with("huge zero accessor", [](Json& d) {
    d["accessors"][1].erase("bufferView");
    d["accessors"][1]["count"] = 4000000000u;
  });
  with("matrix and TRS", [](Json& d) {
    d["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    d["nodes"][0]["scale"] = {1, 1, 1};
  });
  with("Draco garbage", [](Json& d) {
    d["meshes"][0]["primitives"][0]["extensions"] = {
        {"KHR_draco_mesh_compression", {{"bufferView", 0}, {"attributes", {{"POSITION", 0}}}}}};
  });
  for (const auto& [what, bytes] : bad) {
    INFO(what);
    try {
      parse_gltf(bytes, "bad.glb");
      FAIL("no exception");
    } catch (const FileError& e) {
      CHECK(e.path() == "bad.glb");
      CHECK(std::string(e.what()).rfind("bad.glb: ", 0) == 0);
    }
  }
  GltfReadOptions tight;
  tight.max_triangles = 11;
  CHECK_THROWS_AS(parse_gltf(glb, "box.glb", tight), FileError);
  tight.max_triangles = 12;
  CHECK(parse_gltf(glb, "box.glb", tight).soup.triangles.size() == 12);
}
