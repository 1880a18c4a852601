// fabmesh studio: its request handling through real HTTP (the server on a
// free port of 127.0.0.1, in-process, asked with httplib's client), and the
// text edit that saves values into a commented design (docs/studio.md).

#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "geometry/core/errors.h"
#include "geometry/core/units.h"
#include "geometry/mesh/bounding_box.h"
#include "io/design/edit_values.h"
#include "io/mesh/read_mesh.h"
#include "pipeline/failure.h"
#include "pipeline/load_design.h"
#include "pipeline/studio/studio_server.h"
#include "pipeline/studio/studio_session.h"
#include "tests/pipeline/batch/batch_fixture.h"
#include "tests/pipeline/cli_harness.h"
#include "tests/pipeline/studio/studio_fixture.h"  // last: it includes httplib.h

using namespace fabmesh;
using namespace fabmesh::testing;
namespace fs = std::filesystem;
using Json = nlohmann::json;

TEST_CASE("studio: edit_values changes only the values, keeping comments and layout", "[studio]") {
  std::string expected = kCommentedCup;
  auto replace = [&](const std::string& from, const std::string& to) {
    const std::size_t at = expected.find(from);
    REQUIRE(at != std::string::npos);
    expected.replace(at, from.size(), to);
  };
  replace("{value: 4, min: 2", "{value: 5.5, min: 2");
  replace("  wall: 0.3          #", "  wall: 0.25          #");
  replace("lambdas: [0, 0, 0]", "lambdas: [0, -1.5, 0]");
  replace("\"=width / 6\"", "\"=width / 7\"");
  replace("[\"=width / 3\", \"=2 + height / 2\"]", "[2.25, 4.5]");
  const std::string edited = edit_values(
      kCommentedCup, "cup.yaml",
      {parse_override("height=5.5"), parse_override("wall=0.25"), parse_override("profile.lambdas[1]=-1.5"),
       parse_override("profile.points[1][0]=\"=width / 7\""),
       parse_override("profile.points[2]=[2.25, 4.5]")});
  CHECK(edited == expected);
  const Design design = load_design_text(edited, "cup.yaml");
  REQUIRE(design.common.parameters.size() == 3);
  CHECK(design.common.parameters[0].value == 5.5);
  CHECK(design.common.parameters[2].value == 0.25);
}

TEST_CASE("studio: edit_values refuses a value the file does not write", "[studio]") {
  CHECK_THROWS_AS(edit_values(kCommentedCup, "cup.yaml", {parse_override("body.base=1")}), FileError);
  CHECK_THROWS_WITH(
      edit_values(kCommentedCup, "cup.yaml", {parse_override("profile=1")}),
      Catch::Contains(
          "cup.yaml:12:3: profile: the value is not a single number, text or [list] on one line"));
  // A list whose item does not start on its dash's line is not changed item by item.
  const std::string apart = "points:\n  -\n    [1, 2]\n  - [3, 4]\n";
  CHECK_THROWS_WITH(edit_values(apart, "p.yaml", {parse_override("points=[[1, 2]]")}),
                    Catch::Contains("p.yaml:2:3: points: the value is not a single number"));
}

TEST_CASE("studio: edit_values adds and deletes a block list's items, keeping the other lines", "[studio]") {
  // A point added between the second and the third, with its lambda.
  const std::string added = edit_values(
      kCommentedCup, "cup.yaml",
      {parse_override(
           R"(profile.points=[["=width / 4", "=2 + height"], ["=width / 6", "=2 + height * 3 / 4"], )"
           R"([1.75, 4.75], ["=width / 3", "=2 + height / 2"], ["=width / 2", "=2 + height / 4"], )"
           R"(["=width / 4", 2]])"),
       parse_override("profile.lambdas=[0, 0, 0, 0]")});
  std::string expected = kCommentedCup;
  const std::string third = "    - [\"=width / 3\"";
  expected.insert(expected.find(third), "    - [1.75, 4.75]\n");
  expected.replace(expected.find("lambdas: [0, 0, 0]"), 18, "lambdas: [0, 0, 0, 0]");
  CHECK(added == expected);
  const Design six = load_design_text(added, "cup.yaml");
  CHECK(std::get<VesselDesign>(six.body).profile.bspline_points.size() == 6);
  // The first and the fourth deleted, the last moved: their lines go, a new one comes.
  const std::string deleted = edit_values(
      kCommentedCup, "cup.yaml",
      {parse_override(
           R"(profile.points=[["=width / 6", "=2 + height * 3 / 4"], ["=width / 3", "=2 + height / 2"], )"
           R"([1.5, 2]])"),
       parse_override("profile.lambdas=[0]")});
  CHECK(deleted.find("    - [\"=width / 4\", \"=2 + height\"]\n") == std::string::npos);
  CHECK(deleted.find("    - [\"=width / 2\"") == std::string::npos);
  CHECK(
      deleted.find("    - [\"=width / 3\", \"=2 + height / 2\"]\n    - [1.5, 2]\n  lambdas: [0]   # shape") !=
      std::string::npos);
  CHECK(deleted.find("# keep this comment") != std::string::npos);
  CHECK(std::get<VesselDesign>(load_design_text(deleted, "cup.yaml").body).profile.bspline_points.size() ==
        3);
  // Comments between the items stay, and a list that ends the file without a line break still does.
  const std::string tail = "a: 1\nlist:\n  - 1   # one\n  # the second\n  - 2";
  CHECK(edit_values(tail, "t.yaml", {parse_override("list=[0, 1, 2, 3]")}) ==
        "a: 1\nlist:\n  - 0\n  - 1   # one\n  # the second\n  - 2\n  - 3");
  CHECK(edit_values(tail, "t.yaml", {parse_override("list=[2]")}) == "a: 1\nlist:\n  # the second\n  - 2");
  // Items over several lines (a composite's segments): kept whole, with their comments; a new one on a line.
  const std::string segments =
      "outline:\n  segments:\n    - join: {continuity: G1}   # front\n      points: [[1, 0], [2, 0]]\n"
      "    # the corner\n    - join: {continuity: G1}   # right\n      points: [[3, 1], [3, 2]]\n"
      "      lambda: 0.5\n  closed: true\n";
  const std::string split = edit_values(
      segments, "s.yaml",
      {parse_override(
          "outline.segments=[{join: {continuity: G1}, points: [[1, 0], [2, 0]]}, {join: {continuity: "
          "G1}, points: [[2.5, 0.5]]}, {join: {continuity: G1}, points: [[3, 1], [3, 2]], lambda: 0.5}]")});
  std::string inserted = segments;
  inserted.insert(inserted.find("    # the corner"),
                  "    - {join: {continuity: G1}, points: [[2.5, 0.5]]}\n");
  CHECK(split == inserted);
  CHECK(edit_values(segments, "s.yaml",
                    {parse_override("outline.segments=[{join: {continuity: G1}, points: [[3, 1], [3, 2]], "
                                    "lambda: 0.5}]")}) ==
        "outline:\n  segments:\n    # the corner\n    - join: {continuity: G1}   # right\n"
        "      points: [[3, 1], [3, 2]]\n      lambda: 0.5\n  closed: true\n");
}

TEST_CASE("studio: every request without the token, or with a foreign Host, is 403", "[studio]") {
  const fs::path design = cup_file("studio_403");
  RunningStudio studio(design.string(), (design.parent_path() / "out").string());
  httplib::Client c = studio.client();
  const std::string token = studio.server.token();
  REQUIRE(token.size() == 32);
  CHECK(token.find_first_not_of("0123456789abcdef") == std::string::npos);
  CHECK(studio.server.url() ==
        "http://127.0.0.1:" + std::to_string(studio.server.port()) + "/?token=" + token);

  CHECK(c.Get("/")->status == 403);
  CHECK(c.Get("/?token=" + std::string(32, '0'))->status == 403);
  CHECK(c.Get("/api/design")->status == 403);
  CHECK(c.Get("/api/design", {{"X-Fabmesh-Token", token + "0"}})->status == 403);
  CHECK(c.Post("/api/build", "{}", "application/json")->status == 403);
  CHECK(c.Post("/api/save", "{}", "application/json")->status == 403);
  CHECK(c.Get("/t/" + std::string(32, 'a') + "/studio.js")->status == 403);
  CHECK(c.Get("/api/mesh/m1.glb")->status == 403);
  // The page takes its token from the query only; API calls from the header or the query.
  CHECK(c.Get("/", {{"X-Fabmesh-Token", token}})->status == 403);
  const auto page = c.Get("/?token=" + token);
  REQUIRE(page->status == 200);
  CHECK(page->body.find("content=\"" + token + "\"") != std::string::npos);
  CHECK(c.Get("/t/" + token + "/studio.js")->status == 200);
  CHECK(c.Get("/t/" + token + "/three/build/three.module.js")->status == 200);
  CHECK(c.Get("/t/" + token + "/../../etc/passwd")->status == 404);
  CHECK(c.Get("/api/design?token=" + token)->status == 200);
  CHECK(c.Get("/api/design", studio.token())->status == 200);
  // DNS rebinding: a page of another name that resolves to 127.0.0.1 sends its own Host.
  const std::string port = std::to_string(studio.server.port());
  for (const std::string& host : std::vector<std::string>{"evil.example:" + port, "127.0.0.1", "127.0.0.1:1",
                                                          "localhost.evil:" + port}) {
    httplib::Headers h = studio.token();
    h.emplace("Host", host);
    CHECK(c.Get("/api/design", h)->status == 403);
    CHECK(c.Get("/?token=" + token, {{"Host", host}})->status == 403);
  }
  CHECK(c.Get("/api/design", {{"X-Fabmesh-Token", token}, {"Host", "localhost:" + port}})->status == 200);
  // No CORS: another origin's script may not read an answer.
  const auto answer = c.Get("/api/design", {{"X-Fabmesh-Token", token}, {"Origin", "http://evil.example"}});
  CHECK(answer->status == 200);
  CHECK_FALSE(answer->has_header("Access-Control-Allow-Origin"));
  const auto preflight = c.Options("/api/build", {{"Origin", "http://evil.example"}});
  REQUIRE(preflight);
  CHECK(preflight->status == 403);
  CHECK_FALSE(preflight->has_header("Access-Control-Allow-Origin"));
}

TEST_CASE("studio: the design, a build, its mesh, and bad requests", "[studio]") {
  const fs::path design = cup_file("studio_api");
  RunningStudio studio(design.string(), (design.parent_path() / "out").string());
  httplib::Client c = studio.client();

  const Json d = json_of(c.Get("/api/design", studio.token()));
  CHECK(d["name"] == "studio_cup");
  CHECK(d["kind"] == "vessel");
  REQUIRE(d["parameters"].size() == 3);
  CHECK(d["parameters"][0] == Json({{"name", "height"},
                                    {"kind", "number"},
                                    {"value", 4.0},
                                    {"min", 2.0},
                                    {"max", 10.0},
                                    {"step", 0.1},
                                    {"description", "foot to rim"}}));
  CHECK(d["parameters"][2]["min"].is_null());
  // The same parameters as a JSON Schema, as `fabmesh params --json` prints it.
  CHECK(d["schema"]["$schema"] == "https://json-schema.org/draft/2020-12/schema");
  CHECK(d["schema"]["additionalProperties"] == false);
  CHECK(d["schema"]["properties"]["height"] == Json({{"type", "number"},
                                                     {"default", 4.0},
                                                     {"minimum", 2.0},
                                                     {"maximum", 10.0},
                                                     {"multipleOf", 0.1},
                                                     {"description", "foot to rim"}}));
  CHECK(d["schema"]["properties"].size() == 3);
  REQUIRE(d["shape_parameters"].size() == 3);
  CHECK(d["shape_parameters"][1] ==
        Json({{"key", "profile.lambdas[1]"}, {"value", 0.0}, {"min", -8.0}, {"max", 1.0}, {"step", 0.01}}));
  CHECK(d["text"] == kCommentedCup);
  REQUIRE(d["control_points"].size() == 1);
  CHECK(d["control_points"][0]["curve"] == "profile");
  REQUIRE(d["control_points"][0]["points"].size() == 5);
  CHECK(d["control_points"][0]["points"][2] == Json({{"key", "profile.points[2]"},
                                                     {"x", 2.0},
                                                     {"y", 4.0},
                                                     {"text", R"(["=width / 3", "=2 + height / 2"])"}}));
  CHECK(d["fair_energies"] == Json::array({"strain", "curvature_variation"}));

  const auto built =
      c.Post("/api/build", studio.token(), R"({"overrides": {"height": 5}})", "application/json");
  REQUIRE(built->status == 200);
  const Json b = Json::parse(built->body);
  CHECK(b["report"]["design"] == design.string());
  CHECK(b["report"]["name"] == "studio_cup");
  CHECK(b["report"]["parameters"]["height"] == 5.0);
  CHECK(b["report"]["valid"] == true);
  // The profile's control points' heights follow `height`: one more unit of it, a taller cup.
  const Json plain = json_of(c.Post("/api/build", studio.token(), "{}", "application/json"));
  CHECK(plain["report"]["parameters"]["height"] == 4.0);
  CHECK(b["report"]["bounding_box"]["size"][2].get<double>() >
        plain["report"]["bounding_box"]["size"][2].get<double>() + 0.5);
  CHECK(b["plot_svg"].get<std::string>().find("<svg") != std::string::npos);
  CHECK(b["build_ms"].get<double>() > 0.0);
  const std::string mesh = b["mesh"];
  const auto glb = c.Get(mesh, studio.token());
  REQUIRE(glb->status == 200);
  CHECK(glb->get_header_value("Content-Type") == "model/gltf-binary");
  CHECK(glb->body.compare(0, 4, "glTF") == 0);
  CHECK(c.Get("/api/mesh/m999.glb", studio.token())->status == 404);
  // A shape parameter by its key path, as -D takes it.
  const auto shaped = c.Post("/api/build", studio.token(), R"({"overrides": {"profile.lambdas[1]": -2}})",
                             "application/json");
  CHECK(shaped->status == 200);

  // Malformed requests: 400 naming the request's field.
  const auto bad = [&](const std::string& body) {
    const auto r = c.Post("/api/build", studio.token(), body, "application/json");
    REQUIRE(r);
    CHECK(r->status == 400);
    return Json::parse(r->body)["error"];
  };
  CHECK(bad("{\"overrides\": ")["field"] == "");
  CHECK(bad("[1]")["field"] == "");
  CHECK(bad(R"({"overides": {}})")["field"] == "overides");
  CHECK(bad(R"({"overrides": [1]})")["field"] == "overrides");
  // true and false are values (a switch's): given to a number, the design refuses them at the field.
  const auto for_number =
      c.Post("/api/build", studio.token(), R"({"overrides": {"height": true}})", "application/json");
  REQUIRE(for_number);
  CHECK(for_number->status == 422);
  CHECK(Json::parse(for_number->body)["error"]["request_field"] == "overrides.height");
  CHECK(Json::parse(for_number->body)["error"]["message"].get<std::string>().find(
            "height is a number, not a switch") != std::string::npos);
  CHECK(bad(R"({"overrides": {"height": [1]}})")["field"] == "overrides.height");
  CHECK(bad(R"({"overrides": {"height": "5\n"}})")["field"] == "overrides.height");
  const Json unknown = bad(R"({"overrides": {"heigth": 5}})");
  CHECK(unknown["field"] == "overrides.heigth");
  CHECK(unknown["message"].get<std::string>().find("its parameters are: height, width, wall") !=
        std::string::npos);
  CHECK(bad(R"({"overrides": {"profile..x": 5}})")["field"] == "overrides.profile..x");
  CHECK(bad(R"({"draft": 1})")["field"] == "draft");

  // A build encodes no output: the report leaves out the facts only encoding
  // gives and names the formats export encodes.
  CHECK(b["report"]["pending"]["formats"] == Json::array({"stl", "glb"}));
  CHECK(b["report"]["pending"]["until"] == "export");
  for (const char* key : {"outputs", "files", "skipped_outputs"}) CHECK_FALSE(b["report"].contains(key));
  CHECK(b["stages_ms"]["job"].get<double>() > 0.0);
  // A draft: the same values at a coarser tolerance, with a mesh and a plot but no report (no verdict).
  const Json draft = json_of(c.Post("/api/build", studio.token(),
                                    R"({"overrides": {"height": 5}, "draft": true})", "application/json"));
  CHECK_FALSE(draft.contains("report"));
  CHECK(draft["draft"]["tolerance"].get<double>() > b["report"]["tolerance"].get<double>());
  CHECK(draft["draft"]["triangles"].get<std::size_t>() < b["report"]["triangles"].get<std::size_t>());
  CHECK(draft["plot_svg"].get<std::string>().find("<svg") != std::string::npos);
  CHECK(c.Get(draft["mesh"].get<std::string>(), studio.token())->status == 200);
}

TEST_CASE("studio: a mould's parts are in the mesh, exploded apart beside the vessel", "[studio]") {
  const fs::path dir = fresh_dir("studio_mould");
  RunningStudio studio(example("mould_golden.yaml"), (dir / "out").string());
  httplib::Client c = studio.client();
  const Json b = json_of(c.Post("/api/build", studio.token(), "{}", "application/json"));
  REQUIRE(b["mesh"].is_string());
  const auto glb = c.Get(b["mesh"].get<std::string>(), studio.token());
  REQUIRE(glb->status == 200);
  write_text(dir / "mould.glb", glb->body);
  const TriangleSoup shown = read_mesh((dir / "mould.glb").string());
  // The vessel's triangles and every part's, as the build's report counts them.
  const Json& report = b["report"];
  std::size_t triangles = report["triangles"].get<std::size_t>();
  REQUIRE(report["build"]["mould"]["parts"].size() >= 2);
  for (const Json& part : report["build"]["mould"]["parts"])
    triangles += part["triangles"].get<std::size_t>();
  CHECK(shown.triangles.size() == triangles);
  // Apart: the scene is wider than the vessel by the parts pushed out.
  const BoundingBox box = bounding_box(shown.vertices);
  const double vessel_width = report["bounding_box"]["size"][0].get<double>() * metres_per_unit("cm");
  CHECK(box.hi.x() - box.lo.x() > 2.0 * vessel_width);
  // Each part is a primitive of its own, named by its material, for the page to hide.
  std::vector<std::string> names{report["name"].get<std::string>()};
  for (const Json& part : report["build"]["mould"]["parts"]) names.push_back(part["name"]);
  CHECK(b["mesh_parts"] == Json(names));
  const std::string& bytes = glb->body;
  const std::uint32_t json_length = static_cast<unsigned char>(bytes[12]) |
                                    (static_cast<unsigned char>(bytes[13]) << 8U) |
                                    (static_cast<unsigned char>(bytes[14]) << 16U);
  const Json gltf = Json::parse(bytes.substr(20, json_length));
  REQUIRE(gltf["meshes"][0]["primitives"].size() == names.size());
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::size_t material = gltf["meshes"][0]["primitives"][i]["material"];
    CHECK(gltf["materials"][material]["name"] == names[i]);
  }
  // A vessel alone is one part: no list.
  RunningStudio cup(example("vessel_golden_solid.yaml"), (dir / "cup").string());
  httplib::Client cc = cup.client();
  CHECK(json_of(cc.Post("/api/build", cup.token(), "{}", "application/json"))["mesh_parts"] == Json::array());
}

TEST_CASE("studio: a value that breaks the design is 422 with the command line's message", "[studio]") {
  const fs::path design = cup_file("studio_422");
  RunningStudio studio(design.string(), (design.parent_path() / "out").string());
  httplib::Client c = studio.client();
  // The message `fabmesh run -D height=15` prints, from the same exception.
  std::string expected;
  try {
    (void)load_design(design.string(), {parse_override("height=15")});
  } catch (...) {
    expected = describe_failure(std::current_exception(), design.string()).message;
  }
  REQUIRE_FALSE(expected.empty());
  CHECK(expected.find("parameters.height: 15 is outside [2, 10]") != std::string::npos);

  const auto r = c.Post("/api/build", studio.token(), R"({"overrides": {"height": 15}})", "application/json");
  REQUIRE(r->status == 422);
  const Json e = Json::parse(r->body)["error"];
  CHECK(e["message"] == expected);
  CHECK(e["field"] == "height");
  CHECK(e["request_field"] == "overrides.height");
  CHECK(e["key"] == "parameters.height");
  CHECK(e["exit_code"] == 2);
  // A value out of a shape parameter's range, at its place in the file.
  const auto lambda =
      c.Post("/api/build", studio.token(), R"({"overrides": {"profile.lambdas[1]": 3}})", "application/json");
  REQUIRE(lambda->status == 422);
  const Json l = Json::parse(lambda->body)["error"];
  CHECK(l["field"] == "profile.lambdas[1]");
  CHECK(l["message"].get<std::string>().find("lambda_2 = 3 is outside [-8, 1]") != std::string::npos);
  // Export and save refuse the same values, and write nothing.
  CHECK(
      c.Post("/api/export", studio.token(), R"({"overrides": {"height": 15}})", "application/json")->status ==
      422);
  CHECK(c.Post("/api/save", studio.token(), R"({"overrides": {"height": 15}})", "application/json")->status ==
        422);
  CHECK(file_text(design) == kCommentedCup);
  CHECK_FALSE(fs::exists(design.parent_path() / "out"));
}

TEST_CASE("studio: save keeps the comments, and the saved file runs to the export's bytes", "[studio]") {
  const fs::path design = cup_file("studio_save");
  const fs::path out = design.parent_path() / "out";
  RunningStudio studio(design.string(), out.string());
  httplib::Client c = studio.client();
  const std::string body = R"({"overrides": {"height": 5.5, "wall": 0.25}})";
  const Json exported = json_of(c.Post("/api/export", studio.token(), body, "application/json"));
  CHECK(exported["files"].size() == 2);
  CHECK(exported["report"]["files"].size() == 2);  // export's report is complete
  CHECK_FALSE(exported["report"].contains("pending"));
  const Json saved = json_of(c.Post("/api/save", studio.token(), body, "application/json"));
  CHECK(saved["saved"] == design.string());
  std::string expected = kCommentedCup;
  expected.replace(expected.find("value: 4,"), 9, "value: 5.5,");
  expected.replace(expected.find("wall: 0.3 "), 9, "wall: 0.25");
  CHECK(file_text(design) == expected);
  // The file as saved gives the files the studio exported, byte for byte.
  const fs::path again = design.parent_path() / "again";
  REQUIRE(run_cli({"run", "-q", design.string(), "-o", again.string()}) == 0);
  const auto studio_files = output_tree(out);
  CHECK(studio_files.size() == 2);
  CHECK(output_tree(again) == studio_files);
  // The design as saved is what the API now shows.
  const Json d = json_of(c.Get("/api/design", studio.token()));
  CHECK(d["parameters"][0]["value"] == 5.5);
  CHECK(d["parameters"][2]["value"] == 0.25);
}

TEST_CASE("studio: a design that does not read stops the command with exit code 2", "[studio]") {
  const fs::path dir = fresh_dir("studio_bad_design");
  write_text(dir / "bad.yaml", "name: bad\nkind: vessel\nprofile: 3\n");
  std::string output;
  CHECK(run_cli({"studio", "--no-open", (dir / "bad.yaml").string()}, &output) == 2);
  CHECK(output.find("bad.yaml:3:") != std::string::npos);
  CHECK(run_cli({"studio", "--no-open", (dir / "missing.yaml").string()}, &output) == 2);
}

TEST_CASE("studio: fairest gives the shape parameters optimize gives, as overrides", "[studio]") {
  const fs::path design = cup_file("studio_fairest");
  RunningStudio studio(design.string(), (design.parent_path() / "out").string());
  httplib::Client c = studio.client();
  for (const std::string energy : {"strain", "curvature_variation"}) {
    const Json f =
        json_of(c.Post("/api/fairest", studio.token(),
                       R"({"overrides": {"height": 5}, "energy": ")" + energy + "\"}", "application/json"));
    CHECK(f["energy"] == energy);
    CHECK(f["skipped"].empty());
    REQUIRE(f["overrides"].size() == 3);
    for (const auto& [key, value] : f["overrides"].items()) {
      CHECK(key.rfind("profile.lambdas[", 0) == 0);
      CHECK(value.get<double>() >= -8.0);
      CHECK(value.get<double>() <= 1.0);
    }
    // The same numbers `fabmesh optimize` finds for the curve with `fair: ENERGY`.
    std::string optimize_json;
    const std::string faired = file_text(design);
    const fs::path copy = design.parent_path() / (energy + ".yaml");
    write_text(copy, std::string(faired).replace(faired.find("fair: none"), 10, "fair: " + energy));
    REQUIRE(run_cli_json({"optimize", "--json", copy.string(), "-D", "height=5"}, &optimize_json) == 0);
    const Json optimized = Json::parse(optimize_json);
    for (std::size_t i = 0; i < 3; ++i) {
      CHECK(f["overrides"][fmt::format("profile.lambdas[{}]", i)].get<double>() ==
            Approx(optimized[0]["lambdas"][i].get<double>()).margin(1e-12));
    }
    // They build.
    Json build = {{"overrides", f["overrides"]}};
    CHECK(c.Post("/api/build", studio.token(), build.dump(), "application/json")->status == 200);
  }
  const auto bad = c.Post("/api/fairest", studio.token(), R"({"energy": "bending"})", "application/json");
  REQUIRE(bad->status == 400);
  CHECK(Json::parse(bad->body)["error"]["field"] == "energy");
  CHECK(c.Post("/api/build", studio.token(), R"({"energy": "strain"})", "application/json")->status == 400);
}

TEST_CASE("studio: a T-Bezier curve's given points are draggable, found on the plot by position",
          "[studio]") {
  const fs::path dir = fresh_dir("studio_tbezier");
  RunningStudio studio(example("tbezier_outline_g2.yaml"), (dir / "out").string());
  httplib::Client c = studio.client();
  const Json d = json_of(c.Get("/api/design", studio.token()));
  REQUIRE(d["control_points"].size() == 1);
  const Json& curve = d["control_points"][0];
  CHECK(curve["curve"] == "curve");
  CHECK(curve["by"] == "position");
  CHECK(d["fair_energies"] == Json::array({"curvature_variation"}));  // T-Bezier: not strain
  // Each segment gives its end point only (G2 joins all round): four points, each where the text writes it.
  REQUIRE(curve["points"].size() == 4);
  CHECK(curve["points"][1] ==
        Json({{"key", "curve.segments[1].points[0]"}, {"x", 100.0}, {"y", 60.0}, {"text", "[100, 60]"}}));
  // Moved up by its -D path, the curve is built again through it: a new plot, a higher top.
  const Json before = json_of(c.Post("/api/build", studio.token(), "{}", "application/json"));
  const Json after =
      json_of(c.Post("/api/build", studio.token(),
                     R"({"overrides": {"curve.segments[1].points[0]": "[100, 70]"}})", "application/json"));
  CHECK(after["plot_svg"] != before["plot_svg"]);
  CHECK(after["report"]["bounding_box"]["max"][1].get<double>() >
        before["report"]["bounding_box"]["max"][1].get<double>());
}

TEST_CASE("studio: a point added is a list override, and the answer offers the new list", "[studio]") {
  const fs::path design = cup_file("studio_add_point");
  RunningStudio studio(design.string(), (design.parent_path() / "out").string());
  httplib::Client c = studio.client();
  const Json d = json_of(c.Get("/api/design", studio.token()));
  REQUIRE(d["control_points"].size() == 1);
  const Json& cup = d["control_points"][0];
  CHECK(cup["list"] == "profile.points");
  CHECK(cup["min_points"] == 3);
  CHECK(cup["points"][1]["text"] == R"(["=width / 6", "=2 + height * 3 / 4"])");
  CHECK(cup["lambdas"] == Json({{"key", "profile.lambdas"}, {"texts", {"0", "0", "0"}}}));
  // A sixth point between the second and the third, and its lambda; the third then moved by its own key.
  const Json body = {
      {"overrides",
       {{"profile.points",
         R"([["=width / 4", "=2 + height"], ["=width / 6", "=2 + height * 3 / 4"], [1.8, 4.6], )"
         R"(["=width / 3", "=2 + height / 2"], ["=width / 2", "=2 + height / 4"], ["=width / 4", 2]])"},
        {"profile.lambdas", "[0, 0, 0, 0]"},
        {"profile.points[2]", "[1.7, 4.6]"}}}};
  const Json built = json_of(c.Post("/api/build", studio.token(), body.dump(), "application/json"));
  REQUIRE(built.contains("report"));
  const Json& after = built["control_points"][0];
  REQUIRE(after["points"].size() == 6);
  CHECK(after["points"][2] ==
        Json({{"key", "profile.points[2]"}, {"x", 1.7}, {"y", 4.6}, {"text", "[1.7, 4.6]"}}));
  CHECK(after["points"][5]["text"] == R"(["=width / 4", 2])");  // the expressions stay as written
  CHECK(after["lambdas"]["texts"].size() == 4);
  // The new lambda has its slider.
  std::vector<std::string> keys;
  for (const Json& s : built["shape_parameters"]) keys.push_back(s["key"]);
  CHECK(keys == std::vector<std::string>{"profile.lambdas[0]", "profile.lambdas[1]", "profile.lambdas[2]",
                                         "profile.lambdas[3]"});
  // Saved, the file has the new line and keeps every comment; it builds as the studio did.
  REQUIRE(c.Post("/api/save", studio.token(), body.dump(), "application/json")->status == 200);
  const std::string saved = file_text(design);
  CHECK(saved.find(
            "    - [\"=width / 6\", \"=2 + height * 3 / 4\"]\n    - [1.7, 4.6]\n    - [\"=width / 3\"") !=
        std::string::npos);
  CHECK(saved.find("lambdas: [0, 0, 0, 0]   # shape parameters, in [-8, 1]") != std::string::npos);
  const Json reread = json_of(c.Get("/api/design", studio.token()));
  CHECK(reread["control_points"][0]["points"] == after["points"]);
  // Two points are too few: 422 with the reader's words, nothing saved.
  const Json two = {{"overrides", {{"profile.points", "[[1, 6], [1, 2]]"}, {"profile.lambdas", "[]"}}}};
  const auto refused = c.Post("/api/build", studio.token(), two.dump(), "application/json");
  REQUIRE(refused->status == 422);
  CHECK_THAT(Json::parse(refused->body)["error"]["message"].get<std::string>(),
             Catch::Contains("needs at least 3 points"));
  CHECK(c.Post("/api/save", studio.token(), two.dump(), "application/json")->status == 422);
  CHECK(file_text(design) == saved);
}

TEST_CASE("studio: a composite offers its segments whole, and one added is a list override save writes",
          "[studio]") {
  const fs::path dir = fresh_dir("studio_segments");
  write_text(dir / "top.yaml", file_text(example("countertop_g1.yaml")));
  const fs::path design = dir / "top.yaml";
  RunningStudio studio(design.string(), (dir / "out").string());
  httplib::Client c = studio.client();
  const Json d = json_of(c.Get("/api/design", studio.token()));
  REQUIRE(d["control_points"].size() == 1);
  const Json& segments = d["control_points"][0]["segments"];
  CHECK(segments["key"] == "outline.segments");
  CHECK(segments["closed"] == true);
  REQUIRE(segments["items"].size() == 8);
  CHECK(segments["items"][1] ==
        Json({{"key", "outline.segments[1]"},
              {"entries", Json::array({Json::array({"join", R"({continuity: "G1", alpha: 1})"}),
                                       Json::array({"points", "[[2400, 50], [2400, 150]]"}),
                                       Json::array({"lambda", "0.5"}), Json::array({"mu", "0.5"})})},
              {"points", {"outline.segments[1].points[0]", "outline.segments[1].points[1]"}},
              {"joined", true}}));
  // A segment ending at (1000, 0) before the front edge's, as the page writes it.
  std::string list = "[{join: {continuity: G1, alpha: 1}, points: [[900, 0], [1000, 0]]}";
  for (const Json& item : segments["items"]) {
    std::string entries;
    for (const Json& e : item["entries"])
      entries += (entries.empty() ? "" : ", ") + e[0].get<std::string>() + ": " + e[1].get<std::string>();
    list += ", {" + entries + "}";
  }
  list += "]";
  const Json body = {{"overrides", {{"outline.segments", list}}}};
  const Json built = json_of(c.Post("/api/build", studio.token(), body.dump(), "application/json"));
  REQUIRE(built.contains("report"));
  CHECK(built["report"]["valid"] == true);
  CHECK(built["control_points"][0]["segments"]["items"].size() == 9);
  CHECK(built["control_points"][0]["points"][1] ==
        Json({{"key", "outline.segments[0].points[1]"}, {"x", 1000.0}, {"y", 0.0}, {"text", "[1000, 0]"}}));
  // Saved: one new line, every comment kept.
  const std::string before = file_text(design);
  REQUIRE(c.Post("/api/save", studio.token(), body.dump(), "application/json")->status == 200);
  std::string expected = before;
  expected.insert(expected.find("    - join: {continuity: G1, alpha: 1}      # front edge"),
                  "    - {join: {continuity: G1, alpha: 1}, points: [[900, 0], [1000, 0]]}\n");
  CHECK(file_text(design) == expected);
  // A curve with a line or an arc among its segments offers its points, not its segments.
  RunningStudio cnc(example("countertop_asymmetric_line.yaml"), (dir / "cnc").string());
  httplib::Client cc = cnc.client();
  const Json mixed = json_of(cc.Get("/api/design", cnc.token()));
  REQUIRE(mixed["control_points"].size() == 1);
  CHECK(mixed["control_points"][0]["points"].size() > 0);
  CHECK_FALSE(mixed["control_points"][0].contains("segments"));
}

TEST_CASE("studio: a profile through points drags the points it passes through", "[studio]") {
  const fs::path dir = fresh_dir("studio_through");
  RunningStudio studio(example("vessel_through_shell.yaml"), (dir / "out").string());
  httplib::Client c = studio.client();
  const Json d = json_of(c.Get("/api/design", studio.token()));
  REQUIRE(d["control_points"].size() == 1);
  const Json& curve = d["control_points"][0];
  CHECK(curve["curve"] == "profile");
  CHECK(curve["group"] == "through-points");   // the plot's dots on the curve, not its control polygon
  CHECK(d["fair_energies"] == Json::array());  // fairing would move the curve off its points
  REQUIRE(curve["points"].size() == 5);
  CHECK(curve["points"][2] ==
        Json({{"key", "profile.through[2]"}, {"x", 4.6}, {"y", 13.0}, {"text", "[4.6, 13]"}}));
  const Json before = json_of(c.Post("/api/build", studio.token(), "{}", "application/json"));
  CHECK_THAT(before["plot_svg"].get<std::string>(),
             Catch::Contains("<g class=\"through-points\" data-name=\"profile\" data-points=\"5\""));
  // Moved out, the belly point takes the curve with it: a wider vase.
  const Json after =
      json_of(c.Post("/api/build", studio.token(), R"({"overrides": {"profile.through[3]": "[6.5, 7]"}})",
                     "application/json"));
  CHECK(after["report"]["bounding_box"]["size"][0].get<double>() >
        before["report"]["bounding_box"]["size"][0].get<double>());
}

TEST_CASE("studio: a kitchen shows its pieces apart and its slab layout", "[studio]") {
  const fs::path dir = fresh_dir("studio_kitchen");
  RunningStudio studio(example("kitchen_l.yaml"), (dir / "out").string());
  httplib::Client c = studio.client();
  const Json b = json_of(c.Post("/api/build", studio.token(), "{}", "application/json"));
  REQUIRE(b["layout_svg"].is_string());
  const std::string layout = b["layout_svg"];
  const Json& kitchen = b["report"]["build"]["kitchen"];
  for (std::size_t s = 1; s <= kitchen["slabs"].get<std::size_t>(); ++s)
    CHECK(layout.find(fmt::format("id=\"slab-{}\"", s)) != std::string::npos);
  REQUIRE(b["mesh"].is_string());
  const auto glb = c.Get(b["mesh"].get<std::string>(), studio.token());
  REQUIRE(glb->status == 200);
  write_text(dir / "kitchen.glb", glb->body);
  const TriangleSoup shown = read_mesh((dir / "kitchen.glb").string());
  // Every piece's triangles (the top's pieces and the backsplash strips), not the whole top's.
  std::size_t triangles = 0, pieces = 0;
  for (const Json& part : b["report"]["parts"]) {
    if (part["role"] != "piece") continue;
    triangles += part["triangles"].get<std::size_t>();
    ++pieces;
  }
  CHECK(pieces == kitchen["pieces"].size());
  CHECK(shown.triangles.size() == triangles);
  // Apart: wider than the top by the opened seams.
  const BoundingBox box = bounding_box(shown.vertices);
  const double top_width = b["report"]["bounding_box"]["size"][0].get<double>() * metres_per_unit("mm");
  CHECK(box.hi.x() - box.lo.x() > 1.04 * top_width);
  // One router path per slab, named as its program file, with the pieces on it.
  REQUIRE(b["router_paths"].size() == kitchen["slabs"].get<std::size_t>());
  std::size_t placed = 0;
  for (std::size_t s = 0; s < b["router_paths"].size(); ++s) {
    const Json& program = b["router_paths"][s];
    CHECK(program["program"] == fmt::format("kitchen_l.slab-{}", s + 1));
    placed += program["parts"].size();
    CHECK_THAT(program["svg"].get<std::string>(), Catch::Contains("id=\"path-0\""));
  }
  CHECK(placed == kitchen["pieces"].size());
  // Any other design has no layout, and one without `cnc` no router path.
  RunningStudio cup(example("vessel_golden_solid.yaml"), (dir / "cup").string());
  httplib::Client cc = cup.client();
  const Json v = json_of(cc.Post("/api/build", cup.token(), "{}", "application/json"));
  CHECK(v["layout_svg"].is_null());
  CHECK(v["router_paths"] == Json::array());
}

TEST_CASE("studio: a countertop with cnc shows its router path, drawn as its toolpath_svg output",
          "[studio]") {
  const fs::path dir = fresh_dir("studio_router");
  RunningStudio studio(example("countertop_cnc.yaml"), (dir / "out").string());
  httplib::Client c = studio.client();
  const Json b = json_of(c.Post("/api/build", studio.token(), "{}", "application/json"));
  REQUIRE(b["router_paths"].size() == 1);
  const Json& program = b["router_paths"][0];
  CHECK(program["program"] == "countertop_cnc");
  CHECK(program["parts"] == Json::array());
  // The same drawing export writes as the toolpath_svg output.
  const Json exported = json_of(c.Post("/api/export", studio.token(), "{}", "application/json"));
  CHECK(program["svg"] == file_text(dir / "out" / "countertop_cnc.toolpath.svg"));
  // A wider tool moves the path: drawn anew with the override.
  const Json wider = json_of(c.Post("/api/build", studio.token(),
                                    R"({"overrides": {"cnc.tool_diameter": 16}})", "application/json"));
  REQUIRE(wider["router_paths"].size() == 1);
  CHECK(wider["router_paths"][0]["svg"] != program["svg"]);
}

TEST_CASE("studio: parameter sets are listed, picked by override, and saved as a new set", "[studio]") {
  const fs::path design = cup_file("studio_sets");
  const std::string text = kCommentedCup + "parameter_sets:\n  tall: {height: 8}   # a preset\n";
  write_text(design, text);
  RunningStudio studio(design.string(), (design.parent_path() / "out").string());
  httplib::Client c = studio.client();
  const auto post = [&](const char* path, const std::string& body) {
    return c.Post(path, studio.token(), body, "application/json");
  };

  const Json d = json_of(c.Get("/api/design", studio.token()));
  CHECK(d["parameter_sets"] == Json::array({"tall"}));
  CHECK(d["parameter_set"] == "");
  CHECK(d["schema"]["properties"]["parameter_set"]["enum"] == Json::array({"tall"}));
  CHECK(d["schema"]["examples"] == Json::array({{{"parameter_set", "tall"}, {"height", 8.0}}}));

  // Picked: the set's values, and the report names the set.
  const Json tall = json_of(post("/api/build", R"({"overrides": {"parameter_set": "tall"}})"));
  CHECK(tall["report"]["parameter_set"] == "tall");
  CHECK(tall["report"]["parameters"]["height"] == 8.0);
  // A field moved on top of the set wins.
  const Json moved = json_of(post("/api/build", R"({"overrides": {"parameter_set": "tall", "height": 7}})"));
  CHECK(moved["report"]["parameters"]["height"] == 7.0);
  const auto huge = post("/api/build", R"({"overrides": {"parameter_set": "huge"}})");
  REQUIRE(huge);
  CHECK(huge->status == 422);
  CHECK(Json::parse(huge->body)["error"]["message"].get<std::string>().find(
            "no parameter set 'huge' (the sets are: tall)") != std::string::npos);

  // Save as set: every parameter's value, a new line of the block map.
  const Json saved = json_of(post("/api/save_set", R"({"name": "mine", "overrides": {"height": 5.5}})"));
  CHECK(saved["parameter_set"] == "mine");
  const std::string with_mine = text + "  mine: {height: 5.5, width: 6, wall: 0.3}\n";
  CHECK(file_text(design) == with_mine);
  const auto again = post("/api/save_set", R"({"name": "mine", "overrides": {}})");
  REQUIRE(again);
  CHECK(again->status == 422);
  const auto bad = post("/api/save_set", R"({"name": "my set"})");
  REQUIRE(bad);
  CHECK(bad->status == 400);
  CHECK(Json::parse(bad->body)["error"]["field"] == "name");
  CHECK(file_text(design) == with_mine);

  // Save with a set picked: the file's parameter_set, as its new last line.
  (void)json_of(post("/api/save", R"({"overrides": {"parameter_set": "mine"}})"));
  CHECK(file_text(design) == with_mine + "parameter_set: mine\n");
  const Design read_back = load_design(design.string());
  CHECK(read_back.common.parameter_set == "mine");
  CHECK(read_back.common.parameters[0].value == 5.5);
  // No set: null, in place of the name.
  (void)json_of(post("/api/save", R"({"overrides": {"parameter_set": null}})"));
  CHECK(file_text(design) == with_mine + "parameter_set: null\n");
  CHECK(load_design(design.string()).common.parameters[0].value == 4.0);
}
