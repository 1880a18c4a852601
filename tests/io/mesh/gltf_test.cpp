// glTF: fabmesh's GLB (plain and Draco) checked by the Khronos validator and
// draco_decoder, round trips through parse_gltf, and hand-built .gltf files
// exercising what the reader must handle or refuse.

#include "io/mesh/gltf.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>

#include "geometry/core/errors.h"
#include "geometry/mesh/weld.h"
#include "geometry/validation/validate.h"
#include "io/file.h"
#include "io/mesh/draco.h"
#include "io/mesh/obj.h"
#include "io/mesh/read_mesh.h"
#include "tests/geometry/mesh/shapes.h"
#include "tests/io/mesh/external_tool.h"
#include "tests/io/mesh/temp_dir.h"
#include "tests/io/mesh/vessel_fixture.h"

using namespace fabmesh;
using Json = nlohmann::json;
using test::quoted;
using test::run_tool;
using test::TempDir;

namespace {

std::uint32_t u32_at(const std::string& b, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= std::uint32_t{static_cast<unsigned char>(b[at + i])} << (8 * i);
  return v;
}

/// The JSON chunk of a GLB.
Json glb_json(const std::string& glb) {
  REQUIRE(glb.size() >= 20);
  return Json::parse(glb.substr(20, u32_at(glb, 12)));
}

/// The bytes of bufferView `view` of a GLB whose buffer 0 is its BIN chunk.
std::string glb_view(const std::string& glb, int view) {
  const Json doc = glb_json(glb);
  const std::size_t bin = 20 + u32_at(glb, 12) + 8;
  const Json& v = doc["bufferViews"][view];
  return glb.substr(bin + v.value("byteOffset", std::size_t{0}), v["byteLength"].get<std::size_t>());
}

/// Runs the Khronos validator on `glb` written to `dir`; the report must hold
/// no error, no warning and no hint.
void require_validator_passes(const TempDir& dir, const std::string& name, const std::string& bytes) {
  INFO("the Khronos glTF validator: run scripts/install-deps.sh (node, tools/node/node_modules)");
  REQUIRE(test::gltf_validator_installed());
  write_file_atomically(dir.file(name), bytes);
  const test::ToolRun run = run_tool(test::gltf_validator_command(dir.file(name)));
  INFO(name << ": " << run.output);
  REQUIRE(run.code == 0);
  const Json report = Json::parse(run.output.substr(0, run.output.rfind('}') + 1));
  CHECK(report["issues"]["numErrors"] == 0);
  CHECK(report["issues"]["numWarnings"] == 0);
  CHECK(report["issues"]["numHints"] == 0);
}

/// Largest distance from a vertex of `a` to the nearest vertex of `b`.
double max_nearest_distance(const TriangleSoup& a, const TriangleSoup& b) {
  double worst = 0.0;
  for (const Vec3& p : a.vertices) {
    double best = INFINITY;
    for (const Vec3& q : b.vertices) best = std::min(best, (p - q).squaredNorm());
    worst = std::max(worst, std::sqrt(best));
  }
  return worst;
}

/// A torus with more than 65535 vertices (so that indices are 32-bit).
TriangleSoup big_torus() { return test::torus(30.0, 10.0, 400, 200); }

struct Case {
  const char* name;
  TriangleSoup soup;
  double scale;  ///< metres per unit
};

std::vector<Case> glb_cases() {
  return {{"vessel", test::golden_vessel_cm(), 0.01},
          {"big", big_torus(), 0.001},
          {"tiny", test::tetrahedron(Vec3(0, 0, 0), 1.0, 1.0), 0.001}};
}

}  // namespace

TEST_CASE("gltf: a plain GLB passes the Khronos validator with no errors, warnings or hints",
          "[io][gltf][validator]") {
  const TempDir dir;
  for (const Case& c : glb_cases()) {
    INFO(c.name);
    GlbOptions options;
    options.name = c.name;
    options.scale_to_metres = c.scale;
    const std::string glb = encode_glb(c.soup, options);
    require_validator_passes(dir, std::string(c.name) + ".glb", glb);
    const Json doc = glb_json(glb);
    CHECK(doc["asset"]["generator"] == "fabmesh");
    CHECK(doc["accessors"][0]["componentType"] == (c.soup.vertices.size() > 65535 ? 5125 : 5123));
  }
}

TEST_CASE("gltf: a Draco GLB passes the Khronos validator with no errors, warnings or hints",
          "[io][gltf][validator][draco]") {
  const TempDir dir;
  for (const Case& c : glb_cases()) {
    INFO(c.name);
    GlbOptions options;
    options.name = c.name;
    options.scale_to_metres = c.scale;
    options.draco = true;
    const std::string glb = encode_glb(c.soup, options);
    require_validator_passes(dir, std::string(c.name) + "-draco.glb", glb);
    const Json doc = glb_json(glb);
    CHECK(doc["extensionsUsed"] == Json::array({"KHR_draco_mesh_compression"}));
    CHECK(doc["extensionsRequired"] == Json::array({"KHR_draco_mesh_compression"}));
    for (const Json& a : doc["accessors"]) CHECK_FALSE(a.contains("bufferView"));
    CHECK(doc["accessors"][1].contains("min"));
    CHECK(doc["accessors"][1].contains("max"));
  }
}

TEST_CASE("gltf: the validator script fails on a GLB with an error", "[io][gltf][validator]") {
  const TempDir dir;
  std::string glb = encode_glb(test::box(), {});
  // Corrupt the POSITION accessor's declared max: the data no longer matches it.
  const std::size_t at = glb.find("\"max\":[");
  REQUIRE(at != std::string::npos);
  glb[at + 7] = glb[at + 7] == '9' ? '8' : '9';
  REQUIRE(test::gltf_validator_installed());
  dir.write("bad.glb", glb);
  const test::ToolRun run = run_tool(test::gltf_validator_command(dir.file("bad.glb")));
  INFO(run.output);
  CHECK(run.code == 1);
  CHECK(run.output.find("ACCESSOR_MAX_MISMATCH") != std::string::npos);
}

TEST_CASE("gltf: a plain GLB round-trips the soup within float32, in metres and Y-up", "[io][gltf]") {
  for (const Case& c : glb_cases()) {
    INFO(c.name);
    GlbOptions options;
    options.scale_to_metres = c.scale;
    const std::string glb = encode_glb(c.soup, options);
    CHECK(encode_glb(c.soup, options) == glb);  // deterministic
    CHECK(detect_format(glb, "x") == MeshFormat::Glb);
    const GltfContent back = parse_gltf(glb, "x.glb");
    CHECK(back.primitives == 1);
    CHECK(back.draco_primitives == 0);
    CHECK(back.transformed_instances == 0);
    const TriangleSoup expected = to_gltf_frame(c.soup, c.scale);
    CHECK(back.soup.triangles == expected.triangles);
    REQUIRE(back.soup.vertices.size() == expected.vertices.size());
    std::size_t beyond_float32 =
        0;  // coordinates farther than float32 rounding (half an ulp) from the model's
    for (std::size_t i = 0; i < expected.vertices.size(); ++i) {
      const Vec3 d = back.soup.vertices[i] - expected.vertices[i];
      for (int k = 0; k < 3; ++k)
        beyond_float32 += std::abs(d[k]) > std::ldexp(std::abs(expected.vertices[i][k]), -24);
    }
    CHECK(beyond_float32 == 0);
    // Y-up: the model's height (z) is glTF's y.
    const auto [lo, hi] = test::bounds(back.soup);
    const auto [mlo, mhi] = test::bounds(c.soup);
    CHECK(hi.y() - lo.y() == Approx(c.scale * (mhi.z() - mlo.z())).epsilon(1e-6));
    const TriangleSoup model = from_gltf_frame(back.soup, 1.0 / c.scale);
    const ValidationReport original = validate(c.soup);
    const ValidationReport r = validate(weld(model).soup);
    CHECK(r.valid() == original.valid());
    CHECK(r.volume == Approx(original.volume).epsilon(1e-5));
  }
}

TEST_CASE("gltf: a Draco GLB round-trips within the quantization bound", "[io][gltf][draco]") {
  for (int bits : {11, 14, 20}) {
    INFO("bits " << bits);
    const TriangleSoup vessel = test::golden_vessel_cm(0.02);
    GlbOptions options;
    options.scale_to_metres = 0.01;
    options.draco = true;
    options.draco_position_bits = bits;
    const std::string glb = encode_glb(vessel, options);
    CHECK(encode_glb(vessel, options) == glb);
    const GltfContent back = parse_gltf(glb, "x.glb");
    CHECK(back.draco_primitives == 1);
    CHECK(back.soup.triangles.size() == vessel.triangles.size());
    const TriangleSoup expected = to_gltf_frame(vessel, 0.01);
    const auto [lo, hi] = test::bounds(expected);
    const double bound = draco_max_error(lo, hi, bits);
    CHECK(max_nearest_distance(back.soup, expected) <= bound);
    CHECK(max_nearest_distance(expected, back.soup) <= bound);
    if (bits >= 14) {
      const ValidationReport r = validate(weld(back.soup).soup);
      CHECK(r.valid());
      CHECK(r.volume == Approx(validate(expected).volume).epsilon(1e-3));
    }
  }
}

TEST_CASE("gltf: Draco's own decoder reads the Draco payload of a GLB", "[io][gltf][draco]") {
  REQUIRE_PROGRAM("draco_decoder");
  const TempDir dir;
  GlbOptions options;
  options.draco = true;
  const TriangleSoup torus = test::torus(30.0, 10.0, 48, 24);
  const std::string glb = encode_glb(torus, options);
  dir.write("payload.drc", glb_view(glb, 0));
  const test::ToolRun run = run_tool("draco_decoder -i " + quoted(dir.file("payload.drc")) + " -o " +
                                     quoted(dir.file("payload.obj")));
  INFO(run.output);
  REQUIRE(run.code == 0);
  const TriangleSoup decoded = read_mesh(dir.file("payload.obj"));
  CHECK(decoded.triangles.size() == torus.triangles.size());
  const ValidationReport r = validate(weld(decoded).soup);
  CHECK(r.valid());
  CHECK(r.genus == 1);
  const Json doc = glb_json(glb);
  CHECK(doc["accessors"][1]["count"] == parse_gltf(glb, "t.glb").soup.vertices.size());
}

TEST_CASE("gltf: the writer refuses what glTF cannot hold", "[io][gltf]") {
  GlbOptions options;
  CHECK_THROWS_AS(encode_glb(TriangleSoup{}, options), InputError);
  TriangleSoup bad = test::box();
  bad.triangles[0][1] = 8;
  CHECK_THROWS_AS(encode_glb(bad, options), InputError);
  TriangleSoup huge = test::box();
  huge.vertices[0].x() = 1e300;
  CHECK_THROWS_AS(encode_glb(huge, options), InputError);
  options.scale_to_metres = 0.0;
  CHECK_THROWS_AS(encode_glb(test::box(), options), RangeError);
  options.scale_to_metres = 1.0;
  options.draco = true;
  options.draco_position_bits = 31;
  CHECK_THROWS_AS(encode_glb(test::box(), options), RangeError);
}
