// Issue 43, the DXF templates of countertops through the real program, under
// the time and memory bounds the test enforces (tests/pipeline/limited_run.h):
// a line of any length reads (one of 1024 characters hung `run` forever), a
// template cut short is bad input naming the file and line (it built without
// its last entities), an LWPOLYLINE without its vertex count is its own
// outline, and thousands of holes take memory near-linear in their number.

#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/pipeline/cli_harness.h"
#include "tests/pipeline/limited_run.h"

using namespace fabmesh;
using namespace fabmesh::testing;
namespace fs = std::filesystem;

namespace {

constexpr double kSeconds = 60.0;
constexpr std::size_t kMemory = 2048 * kMiB;

const char* const kDesign = R"(name: top
kind: countertop
units: mm
tolerance: 0.05
thickness: 30
outline: {dxf: t.dxf, layer: OUTLINE}
holes:
  - {dxf: t.dxf, layer: HOLES}
outputs: [stl]
)";

// A 1000 x 600 worktop with three round holes; `extra` goes first into the
// ENTITIES section, `outline_count` is the LWPOLYLINE's group 90 ("" for none).
std::string worktop(const std::string& extra, const std::string& outline_count = "90\n4\n") {
  std::string text =
      "999\nwritten for fabmesh's tests\n0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n"
      "0\nSECTION\n2\nENTITIES\n" +
      extra;
  text += "0\nLWPOLYLINE\n5\n10\n8\nOUTLINE\n" + outline_count +
          "70\n1\n10\n0\n20\n0\n10\n1000\n20\n0\n10\n1000\n20\n600\n10\n0\n20\n600\n";
  for (int i = 1; i <= 3; ++i)
    text += fmt::format("0\nCIRCLE\n5\nA{}\n8\nHOLES\n10\n{}\n20\n300\n30\n0\n40\n40\n", i, 250 * i);
  return text + "0\nENDSEC\n0\nEOF\n";
}

LimitedRun run_template(const fs::path& dir, const std::string& dxf) {
  write_text(dir / "t.dxf", dxf);
  write_text(dir / "top.yaml", kDesign);
  return run_limited({"run", (dir / "top.yaml").string(), "-o", (dir / "out").string(), "--json"}, kSeconds,
                     kMemory);
}

}  // namespace

TEST_CASE("run: a DXF template with lines of 1023, 1024 and a million characters builds",
          "[io][design][dxf][run]") {
  for (const std::size_t length : {1023u, 1024u, 4096u, 1u << 20}) {
    INFO(length);
    const fs::path dir = fresh_dir(fmt::format("dxf_long_line_{}", length));
    const std::string long_text = std::string(length, 'x');
    // A comment, a text on the outline's layer, an entity on a layer of that long a name.
    const std::string extra = "999\n" + long_text + "\n0\nTEXT\n8\nOUTLINE\n10\n0\n20\n0\n40\n5\n1\n" +
                              long_text + "\n0\nPOINT\n8\n" + long_text + "\n10\n0\n20\n0\n";
    const LimitedRun r = run_template(dir, worktop(extra));
    INFO(r.describe());
    REQUIRE(r.code == 0);
    const nlohmann::json item = nlohmann::json::parse(r.out).at(0);
    CHECK(item["genus"] == 3);
    CHECK(item["valid"] == true);
  }
}

TEST_CASE("run: a DXF template cut short is bad input naming the file and line, nothing written",
          "[io][design][dxf][run]") {
  const std::string whole = worktop("");
  // Cut after the third hole's last group, before ENDSEC; and inside the third hole.
  for (const std::size_t size :
       {whole.find("0\nENDSEC", whole.find("A3")), whole.find("40\n40", whole.find("A3"))}) {
    INFO(size);
    const fs::path dir = fresh_dir(fmt::format("dxf_cut_{}", size));
    const LimitedRun r = run_template(dir, whole.substr(0, size));
    INFO(r.describe());
    CHECK(r.code == 2);
    CHECK_THAT(r.err,
               Catch::Matches("(.|\n)*t\\.dxf:[0-9]+: the drawing ends inside its ENTITIES section, before "
                              "ENDSEC: the file is cut short(.|\n)*"));
    CHECK_FALSE(fs::exists(dir / "out" / "top.stl"));
  }
}

TEST_CASE("run: an LWPOLYLINE without its vertex count is its own outline", "[io][design][dxf][run]") {
  // A larger polyline on another layer before it: its vertices were taken.
  const std::string before =
      "0\nLWPOLYLINE\n5\nF\n8\nFRAME\n90\n4\n70\n1\n10\n-50\n20\n-50\n10\n2050\n20\n-"
      "50\n10\n2050\n20\n1050\n10\n-50\n"
      "20\n1050\n";
  const fs::path dir = fresh_dir("dxf_no_count");
  const LimitedRun r = run_template(dir, worktop(before, ""));
  INFO(r.describe());
  REQUIRE(r.code == 0);
  const nlohmann::json item = nlohmann::json::parse(r.out).at(0);
  CHECK(item["bounding_box"]["min"] == nlohmann::json::array({0.0, 0.0, 0.0}));
  CHECK(item["bounding_box"]["max"] == nlohmann::json::array({1000.0, 600.0, 30.0}));
}

TEST_CASE("run: 6400 holes from a DXF template build within 1 GiB of address space",
          "[io][design][dxf][run]") {
  // Issue 43: 4,900 holes took 534 MB and 10,000 1.75 GB: the clearance
  // search between the loops began with every pair of loops (20 million
  // pairs here, 0.8 GB). Now from one pair of the tree over them: 0.27 GB.
  std::string entities =
      "0\nLWPOLYLINE\n5\n10\n8\nOUTLINE\n90\n4\n70\n1\n10\n0\n20\n0\n10\n1620\n20\n0\n10\n1620\n20\n1620\n10"
      "\n"
      "0\n20\n1620\n";
  for (int i = 0; i < 80; ++i) {
    for (int j = 0; j < 80; ++j)
      entities +=
          fmt::format("0\nCIRCLE\n8\nHOLES\n10\n{}\n20\n{}\n30\n0\n40\n5\n", 20 + 20 * i, 20 + 20 * j);
  }
  const fs::path dir = fresh_dir("dxf_many_holes");
  write_text(dir / "t.dxf", "0\nSECTION\n2\nENTITIES\n" + entities + "0\nENDSEC\n0\nEOF\n");
  std::string design = kDesign;
  design.replace(design.find("outputs: [stl]"), 14, "outputs: [dxf]");
  write_text(dir / "top.yaml", design);
  const LimitedRun r = run_limited(
      {"run", (dir / "top.yaml").string(), "-o", (dir / "out").string(), "--json"}, 600.0, 1024 * kMiB);
  INFO(r.describe());
  REQUIRE(r.code == 0);
  CHECK(nlohmann::json::parse(r.out).at(0)["genus"] == 6400);
}
