#include "io/design/manifest.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "geometry/core/errors.h"
#include "io/design/csv_table.h"
#include "io/design/design_source.h"
#include "tests/io/design/cup_design.h"

using namespace fabmesh;
using fabmesh::test::kCup;

namespace {

namespace fs = std::filesystem;

// A folder with cup.yaml and the given extra files.
fs::path folder(const std::string& test, const std::vector<std::pair<std::string, std::string>>& files = {}) {
  const fs::path dir = fs::path(FABMESH_TEST_TMP) / "manifest" / test;
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "cup.yaml") << kCup;
  for (const auto& [name, text] : files) std::ofstream(dir / name, std::ios::binary) << text;
  return dir;
}

BatchManifest manifest(const std::string& test, const std::string& text,
                       const std::vector<std::pair<std::string, std::string>>& files = {}) {
  return parse_manifest(text, (folder(test, files) / "m.yaml").string());
}

std::vector<std::string> names(const BatchManifest& m) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < m.variant_count(); ++i) out.push_back(m.variant(i).name);
  return out;
}

std::string error_of(const std::string& test, const std::string& text,
                     const std::vector<std::pair<std::string, std::string>>& files = {}) {
  try {
    manifest(test, text, files);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// The wall of the design of variant `i`, resolved as a batch resolves it.
double wall_of(const BatchManifest& m, std::size_t i) {
  const Variant v = m.variant(i);
  const Design d = m.bases[v.base].resolve(variant_overrides(m, v));
  return std::get<VesselDesign>(d.body).wall;
}

}  // namespace

TEST_CASE("manifest: a grid is the cartesian product, the first key slowest, with ranges ending exactly",
          "[io][design][manifest][batch]") {
  const BatchManifest m = manifest("grid", R"(design: cup.yaml
name: cup_w{body.wall}_l{profile.lambdas[0]}
grid:
  body.wall: {from: 0.2, to: 0.4, steps: 3}
  profile.lambdas[0]: [-1, 0.5]
)");
  CHECK(names(m) == std::vector<std::string>{"cup_w0.2_l-1", "cup_w0.2_l0.5", "cup_w0.3_l-1", "cup_w0.3_l0.5",
                                             "cup_w0.4_l-1", "cup_w0.4_l0.5"});
  CHECK(m.parameters == std::vector<std::string>{"body.wall", "profile.lambdas[0]"});
  CHECK(wall_of(m, 0) == 0.2);
  CHECK(wall_of(m, 5) == 0.4);
  const Design last = m.bases[0].resolve(variant_overrides(m, m.variant(5)));
  CHECK(last.common.name == "cup_w0.4_l0.5");
  CHECK(std::get<VesselDesign>(last.body).profile.bspline_lambdas[0] == 0.5);
}

TEST_CASE("manifest: a million-variant grid is read as its value lists, each variant made on demand",
          "[io][design][manifest][batch]") {
  const BatchManifest m = manifest("million", R"(design: cup.yaml
name: cup_w{body.wall}_b{body.base}
grid:
  body.wall: {from: 0.2, to: 0.3, steps: 1000}
  body.base: {from: 0.1, to: 0.4, steps: 1000}
)");
  REQUIRE(m.variant_count() == 1000000);
  CHECK(m.variant(0).name == "cup_w0.2_b0.1");
  CHECK(m.variant(999).name == "cup_w0.2_b0.4");  // the last key fastest
  CHECK(m.variant(1000).name == "cup_w0.2001001001_b0.1");
  CHECK(m.variant(999999).name == "cup_w0.3_b0.4");  // ranges end exactly
  CHECK(wall_of(m, 999999) == 0.3);
  CHECK_THROWS_AS(m.variant(1000000), std::out_of_range);
  // Two equal names a million variants apart are still found.
  CHECK_THAT(error_of("million_clash", R"(design: cup.yaml
name: cup_w{body.wall}
grid:
  body.wall: {from: 0.2, to: 0.3, steps: 1000}
  body.base: {from: 0.1, to: 0.4, steps: 1000}
)"),
             Catch::Contains("variants 1 and 2 are both named 'cup_w0.2'"));
}

TEST_CASE("manifest: zip pairs equal-length lists and names the list whose length differs",
          "[io][design][manifest][batch]") {
  const BatchManifest m = manifest("zip", R"(design: cup.yaml
name: z{index}
set: {tolerance: 0.01}
zip:
  body.wall: [0.2, 0.25, 0.3]
  body.base: [0.5, 0.6, 0.7]
)");
  CHECK(names(m) == std::vector<std::string>{"z1", "z2", "z3"});
  const Design d = m.bases[0].resolve(variant_overrides(m, m.variant(1)));
  CHECK(std::get<VesselDesign>(d.body).wall == 0.25);
  CHECK(std::get<VesselDesign>(d.body).base == 0.6);
  CHECK(d.common.tolerance == 0.01);
  const std::string e =
      error_of("zip_bad", "design: cup.yaml\nzip:\n  body.wall: [0.2, 0.3]\n  body.base: [0.5]\n");
  CHECK_THAT(e, Catch::Contains("m.yaml:4:") && Catch::Contains("zip.body.base") &&
                    Catch::Contains("zip.body.wall has 2"));
}

TEST_CASE(
    "manifest: a CSV table gives one variant per row, columns are override paths, an empty cell keeps the "
    "base value",
    "[io][design][manifest][batch]") {
  const BatchManifest m = manifest("table", "design: cup.yaml\ntable: t.csv\n",
                                   {{"t.csv",
                                     "name,body.wall,profile.points[1]\r\n"
                                     "thin,0.2,\"[1.2, 5]\"\r\n"
                                     "\r\n"
                                     "plain,,\n"}});
  CHECK(names(m) == std::vector<std::string>{"thin", "plain"});
  CHECK(wall_of(m, 0) == 0.2);
  CHECK(wall_of(m, 1) == 0.3);
  const Design d = m.bases[0].resolve(variant_overrides(m, m.variant(0)));
  CHECK(std::get<VesselDesign>(d.body).profile.bspline_points[1] == Vec2(1.2, 5));
  // A short row is named by its line in the table.
  const std::string e =
      error_of("table_bad", "design: cup.yaml\ntable: t.csv\n", {{"t.csv", "name,body.wall\na,0.2\nb\n"}});
  CHECK_THAT(e, Catch::Contains("t.csv:3:1") && Catch::Contains("1 cell(s), the header has 2"));
}

TEST_CASE("manifest: CSV cells may hold quoted commas, quotes and line breaks",
          "[io][design][manifest][batch]") {
  const CsvTable t = parse_csv_table("a, b\n\"x,\"\"y\"\"\", \"two\nlines\"\n", "t.csv");
  REQUIRE(t.header.size() == 2);
  CHECK(t.header[1].text == "b");
  REQUIRE(t.rows.size() == 1);
  CHECK(t.rows[0][0].text == "x,\"y\"");
  CHECK(t.rows[0][1].text == "two\nlines");
  CHECK_THROWS_AS(parse_csv_table("a\n\"open\n", "t.csv"), FileError);
  // A spreadsheet's UTF-8 byte order mark is not part of the first column's name.
  const CsvTable bom = parse_csv_table("\xEF\xBB\xBFname,body.wall\nthin,0.2\n", "t.csv");
  REQUIRE(bom.header.size() == 2);
  CHECK(bom.header[0].text == "name");
  CHECK(bom.rows.size() == 1);
}

TEST_CASE("manifest: an explicit variant list, several bases and {design} in names",
          "[io][design][manifest][batch]") {
  const BatchManifest m = manifest("list", R"(design: [cup.yaml, mug.yaml]
name: "{design}-{index}"
variants:
  - {body.wall: 0.2}
  - {body.wall: 0.25, body.base: 0.5}
)",
                                   {{"mug.yaml", kCup + "# the same cup by another name\n"}});
  // The base names come from `name:` in the design files: both are "cup" here, told apart by {index}.
  CHECK(names(m) == std::vector<std::string>{"cup-1", "cup-2", "cup-3", "cup-4"});
  CHECK(m.variant(2).base == 1);
  CHECK(wall_of(m, 3) == 0.25);
}

TEST_CASE("manifest: two variants with one name, or a name that is not a plain file name, are refused",
          "[io][design][manifest][batch]") {
  const std::string same =
      error_of("clash2", "design: cup.yaml\nname: cup\ngrid:\n  body.wall: [0.2, 0.3]\n");
  CHECK_THAT(same, Catch::Contains("m.yaml:2:") && Catch::Contains("variants 1 and 2 are both named 'cup'"));
  const std::string slash =
      error_of("slash", "design: cup.yaml\nname: a/{body.wall}\ngrid:\n  body.wall: [0.2]\n");
  CHECK_THAT(slash, Catch::Contains("not a plain file name"));
  const std::string unknown =
      error_of("unknown", "design: cup.yaml\nname: c{body.wal}\ngrid:\n  body.wall: [0.2]\n");
  CHECK_THAT(unknown, Catch::Contains("{body.wal} is not a parameter"));
}

TEST_CASE("manifest: unknown keys, bad paths and bad ranges are refused with their place",
          "[io][design][manifest][batch]") {
  CHECK_THAT(error_of("key", "design: cup.yaml\ngird: {body.wall: [1]}\n"), Catch::Contains("gird"));
  CHECK_THAT(error_of("path", "design: cup.yaml\ngrid: {'body..wall': [1]}\n"), Catch::Contains("m.yaml:2:"));
  CHECK_THAT(error_of("steps", "design: cup.yaml\ngrid: {body.wall: {from: 0.2, to: 0.3, steps: 2.5}}\n"),
             Catch::Contains("steps"));
  CHECK_THAT(error_of("twice", "design: cup.yaml\nset: {body.wall: 0.2}\ngrid: {body.wall: [0.3]}\n"),
             Catch::Contains("also set by `set`"));
  CHECK_THAT(error_of("kind", "design: cup.yaml\ngrid: {kind: [curve]}\n"), Catch::Contains("kind"));
  // parse_override splits "p=" + "=0" at the first '=': a key with '=' is still no override path
  // (found by fuzz_manifest: `set: {w=: }` was accepted).
  CHECK_THAT(error_of("equals", "design: cup.yaml\nset:\n w=:\n"),
             Catch::Contains("m.yaml:3:2") && Catch::Contains("unexpected '=' in path 'w='"));
  CHECK_THAT(error_of("equals_grid", "design: cup.yaml\ngrid: {'body.wall=0.5': [0.2]}\n"),
             Catch::Contains("unexpected '=' in path 'body.wall=0.5'"));
  CHECK_THAT(error_of("equals_table", "design: cup.yaml\ntable: t.csv\n", {{"t.csv", "body.wall=,x\n1,2\n"}}),
             Catch::Contains("t.csv:1:1") && Catch::Contains("unexpected '=' in path 'body.wall='"));
  CHECK_THAT(error_of("nobase", "design: none.yaml\ngrid: {body.wall: [0.3]}\n"),
             Catch::Contains("none.yaml"));
}

TEST_CASE("manifest: the canonical text ignores layout, comments, key order and file names, not values",
          "[io][design][manifest][batch]") {
  const fs::path dir = folder("canonical", {{"a.yaml", kCup},
                                            {"b.yaml",
                                             "# a comment\nbody: {base: 0.4, wall: 0.3, mode: shell}\n"
                                             "kind: vessel\nname: cup\nunits: cm\ntolerance: 0.005\n"
                                             "profile: {family: quasi_bspline, lambdas: [0, 0, 0],\n"
                                             "  points: [[1.5, 6], [1, 5], [2, 4], [3, 3], [1.5, 2]]}\n"}});
  const DesignSource a = DesignSource::read((dir / "a.yaml").string());
  const DesignSource b = DesignSource::read((dir / "b.yaml").string());
  CHECK(a.canonical({}) == b.canonical({}));
  const Override wall = parse_override("body.wall=0.25");
  CHECK(a.canonical({wall}) == b.canonical({wall}));
  CHECK(a.canonical({wall}) != a.canonical({}));
  // A quoted "0.3" is a string, not the number: it reads differently, so it is another design.
  CHECK(a.canonical({parse_override("body.wall='0.3'")}) != a.canonical({}));
}

TEST_CASE("manifest: the blanked canonical text leaves out only the values of the root keys named",
          "[io][design][manifest][batch]") {
  // The L-shaped kitchen: a countertop with holes, seams, a backsplash and a router program.
  const DesignSource source = DesignSource::read(FABMESH_SOURCE_DIR "/configs/examples/kitchen_l.yaml");
  auto blanked = [&](const std::vector<std::string>& overrides, std::string* canonical = nullptr) {
    std::vector<Override> all;
    for (const std::string& o : overrides) all.push_back(parse_override(o));
    BlankedText text{{"name", "thickness"}, {}};
    std::string whole;
    source.resolve(all, &whole, &text);
    CHECK(whole == source.canonical(all));
    if (canonical != nullptr) *canonical = whole;
    return text.text;
  };
  std::string whole;
  const std::string base = blanked({}, &whole);
  CHECK(base != whole);
  CHECK(base.find("\"thickness\":*") != std::string::npos);
  CHECK(base.find("\"name\":*") != std::string::npos);
  CHECK(base.find("kitchen_l") == std::string::npos);
  CHECK(whole.find("kitchen_l") != std::string::npos);
  CHECK(blanked({"thickness=40", "name=other"}) == base);
  CHECK(blanked({"tolerance=0.02"}) != base);
  CHECK(blanked({"holes[0].rounded_rect.radius=30"}) != base);
  CHECK(blanked({"backsplash.thickness=20"}) != base);  // a `thickness` below the root stays
  BlankedText none{{}, {}};
  std::string canonical;
  source.resolve({}, &canonical, &none);
  CHECK(none.text == canonical);
}

TEST_CASE("manifest: a variant's design keeps the lines and columns of its base design's keys",
          "[io][design][manifest][batch]") {
  const fs::path dir = folder("variant_places", {{"cup.yaml",
                                                  "# a cup\nname: cup\nkind: vessel\nunits: cm\n"
                                                  "tolerance: 0.005\nbody: {mode: solid}\n"
                                                  "profile:\n  family: quasi_bspline\n"
                                                  "  points: [[1.5, 6], [1, 5], [2, 4], [3, 3]]\n"}});
  const DesignSource source = DesignSource::read((dir / "cup.yaml").string());
  for (int round = 0; round < 2; ++round) {  // each resolution, not only the first
    const Design design = source.resolve({parse_override("tolerance=0.01")});
    REQUIRE(design.common.where.count("profile") == 1);
    CHECK(design.common.where.at("profile").line == 8);  // where its value starts, not 1:1
    CHECK(design.common.where.at("profile.points").line == 9);
    CHECK(design.common.where.at("tolerance").override_text == "tolerance=0.01");
  }
}
