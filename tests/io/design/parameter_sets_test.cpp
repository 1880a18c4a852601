// Parameter sets (docs/design-files.md, "Parameter sets"): a set's values in
// place of its parameters', -D on top, every error at its place; sets in a
// batch manifest (`sets`); a set added to a design's text (the studio's save
// as set).

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "geometry/core/errors.h"
#include "io/design/design_source.h"
#include "io/design/edit_values.h"
#include "io/design/manifest.h"
#include "io/design/read_design.h"
#include "tests/io/design/design_text.h"

using namespace fabmesh;
using fabmesh::test::read_error;
using fabmesh::test::read_text;
using fabmesh::test::replaced;

namespace {

// A cup with two parameters and three sets. Line 8 is `tall`, its height at
// column 17; `wide`'s width is an expression over the set's parameters.
const std::string kSetCup = R"(name: cup
kind: vessel
units: cm
parameters:
  height: {value: 4, min: 2, max: 10}
  width: 6
parameter_sets:
  tall: {height: 8}
  small: {height: 3, width: 5}
  wide: {width: "=height * 2.5"}
profile:
  family: quasi_bspline
  points: [["=width / 4", "=2 + height"], [1, 4], [2, 3], ["=width / 2", 2.5], [1.5, 2]]
  lambdas: [0, 0, 0]
body: {mode: solid}
)";

double value_of(const Design& d, const std::string& name) {
  for (const DesignParameter& p : d.common.parameters) {
    if (p.name == name) return p.value;
  }
  FAIL("no parameter " << name);
  return 0.0;
}

}  // namespace

TEST_CASE("parameter sets: a set's values replace its parameters', the others keep theirs",
          "[io][design][sets]") {
  const Design plain = read_text(kSetCup);
  CHECK(plain.common.parameter_set.empty());
  REQUIRE(plain.common.parameter_sets.size() == 3);
  CHECK(plain.common.parameter_sets[0].name == "tall");
  CHECK(plain.common.parameter_sets[2].values ==
        std::vector<std::pair<std::string, std::string>>{{"width", "=height * 2.5"}});
  CHECK(value_of(plain, "height") == 4);

  const Design tall = read_text(kSetCup, {"parameter_set=tall"});
  CHECK(tall.common.parameter_set == "tall");
  CHECK(value_of(tall, "height") == 8);
  CHECK(value_of(tall, "width") == 6);
  // The set's values reach the geometry: the rim is at 2 + height.
  const Design small = read_text(kSetCup, {"parameter_set=small"});
  CHECK(value_of(small, "height") == 3);
  CHECK(value_of(small, "width") == 5);
  // An expression in a set is evaluated over the design's parameters.
  CHECK(value_of(read_text(kSetCup, {"parameter_set=wide"}), "width") == 10);
  CHECK(value_of(read_text(kSetCup, {"parameter_set=wide", "height=3"}), "width") == 7.5);
}

TEST_CASE("parameter sets: -D wins over the set's value, in any order", "[io][design][sets]") {
  for (const auto& defines : {std::vector<std::string>{"parameter_set=tall", "height=9"},
                              std::vector<std::string>{"height=9", "parameter_set=tall"}}) {
    const Design d = read_text(kSetCup, defines);
    CHECK(d.common.parameter_set == "tall");
    CHECK(value_of(d, "height") == 9);
  }
  // The last set named is the one used.
  CHECK(read_text(kSetCup, {"parameter_set=tall", "parameter_set=small"}).common.parameter_set == "small");
  // An edit of a set applies before the set does.
  CHECK(value_of(read_text(kSetCup, {"parameter_set=tall", "parameter_sets.tall.height=7"}), "height") == 7);
}

TEST_CASE("parameter sets: the file's own parameter_set, and null for none", "[io][design][sets]") {
  const std::string chosen = kSetCup + "parameter_set: small\n";
  CHECK(value_of(read_text(chosen), "height") == 3);
  CHECK(read_text(chosen).common.parameter_set == "small");
  CHECK(value_of(read_text(chosen, {"parameter_set=tall"}), "height") == 8);
  // The set a -P picks replaces the file's whole: small's width does not stay.
  CHECK(value_of(read_text(chosen, {"parameter_set=tall"}), "width") == 6);
  const Design none = read_text(chosen, {"parameter_set=null"});
  CHECK(none.common.parameter_set.empty());
  CHECK(value_of(none, "height") == 4);
}

TEST_CASE("parameter sets: bad sets and bad choices are bad input at their place", "[io][design][sets]") {
  CHECK(read_error(kSetCup, {"parameter_set=huge"}) ==
        "-D parameter_set=huge: parameter_set: no parameter set 'huge' (the sets are: tall, small, wide)");
  // A set's value out of its parameter's range: at the set's line and column.
  CHECK(read_error(replaced(kSetCup, "tall: {height: 8}", "tall: {height: 12}"), {"parameter_set=tall"}) ==
        "cup.yaml:8:18: parameter_sets.tall.height: 12 is outside [2, 10]");
  // Checked whether the set is used or not.
  CHECK(read_error(replaced(kSetCup, "tall: {height: 8}", "tall: {heigth: 8}")) ==
        "cup.yaml:8:10: parameter_sets.tall.heigth: \"heigth\" is not a parameter of the design (the "
        "parameters are: height, width)");
  CHECK(read_error(replaced(kSetCup, "tall: {height: 8}", "tall: {height: [8]}")) ==
        "cup.yaml:8:18: parameter_sets.tall.height: expected a number or an expression \"=...\", the "
        "parameter's value");
  CHECK(
      read_error(replaced(kSetCup, "tall: {height: 8}", "\"tall one\": {height: 8}")) ==
      "cup.yaml:8:3: parameter_sets: \"tall one\" is not a parameter set's name: 1 to 64 letters, digits, _ "
      "and -, not starting with -");
  CHECK(read_error(replaced(kSetCup, "tall: {height: 8}", "tall: {}")) ==
        "cup.yaml:8:9: parameter_sets.tall: expected a map of parameters to values, e.g. {height: 14, wall: "
        "0.4} (at least one)");
  CHECK(read_error(replaced(kSetCup, "tall: {height: 8}", "tall: 8"))
            .find("parameter_sets.tall: expected a map") != std::string::npos);
  const std::string no_parameters = R"(kind: vessel
parameter_sets: {tall: {height: 8}}
profile: {family: quasi_bspline, points: [[1.5, 6], [1, 4], [2, 3], [3, 2.5], [1.5, 2]]}
body: {mode: solid}
)";
  CHECK(read_error(no_parameters).find("cup.yaml:2:17: parameter_sets: the design declares no parameters") ==
        0);
  CHECK(read_error(no_parameters, {"parameter_set=tall"}).find("parameter_sets: the design declares no") !=
        std::string::npos);
  const std::string no_sets = replaced(kSetCup, "parameter_sets:", "other_sets:");
  CHECK(
      read_error(replaced(no_sets,
                          "other_sets:\n  tall: {height: 8}\n  small: {height: 3, width: 5}\n  wide: "
                          "{width: \"=height * 2.5\"}\n",
                          ""),
                 {"parameter_set=tall"}) ==
      "-D parameter_set=tall: parameter_set: no parameter set 'tall': the design declares no parameter_sets");
}

TEST_CASE("parameter sets: a design source lists its sets, a manifest builds them", "[io][design][sets]") {
  const std::filesystem::path dir = std::filesystem::path(FABMESH_TEST_TMP) / "parameter_sets";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "cup.yaml") << kSetCup;
  CHECK(DesignSource::read((dir / "cup.yaml").string()).parameter_set_names() ==
        std::vector<std::string>{"tall", "small", "wide"});
  const auto manifest = [&](const std::string& text) {
    return parse_manifest(text, (dir / "m.yaml").string());
  };
  const BatchManifest all = manifest("design: cup.yaml\nsets: all\n");
  REQUIRE(all.variant_count() == 3);
  CHECK(all.variant(0).name == "cup_tall");
  CHECK(all.variant(2).name == "cup_wide");
  CHECK(all.parameters == std::vector<std::string>{"parameter_set"});
  // Each variant is the design with -P NAME.
  const Design wide = all.bases[0].resolve(variant_overrides(all, all.variant(2)));
  CHECK(wide.common.parameter_set == "wide");
  CHECK(value_of(wide, "width") == 10);
  // The sets vary slowest; {set} names them.
  const BatchManifest listed = manifest(
      "design: cup.yaml\nsets: [small, tall]\nname: c_{set}_{height}\n"
      "grid: {height: [4, 5]}\n");
  REQUIRE(listed.variant_count() == 4);
  CHECK(listed.variant(0).name == "c_small_4");
  CHECK(listed.variant(1).name == "c_small_5");
  CHECK(listed.variant(2).name == "c_tall_4");
  // The grid's height wins over the set's.
  CHECK(value_of(listed.bases[0].resolve(variant_overrides(listed, listed.variant(2))), "height") == 4);
  const auto error = [&](const std::string& text) {
    try {
      manifest(text);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(error("design: cup.yaml\nsets: [small, huge]\n")
            .find("m.yaml:2:7: sets: the design cup.yaml has no parameter set 'huge' (its sets: tall, small, "
                  "wide)") != std::string::npos);
  CHECK(error("design: cup.yaml\nsets: [small, small]\n").find("set 'small' is named twice") !=
        std::string::npos);
  CHECK(error("design: cup.yaml\nsets: some\n").find("expected `all`") != std::string::npos);
  CHECK(error("design: cup.yaml\nsets: all\ngrid: {parameter_set: [tall]}\n")
            .find("'parameter_set' is also set by `sets`") != std::string::npos);
  CHECK(error("design: cup.yaml\nname: c_{set}\ngrid: {height: [4, 5]}\n").find("{set} is not a parameter") !=
        std::string::npos);
}

TEST_CASE("parameter sets: a set is added to a design's text, everything else kept", "[io][design][sets]") {
  const std::vector<std::pair<std::string, std::string>> values{{"height", "7"}, {"width", "6.5"}};
  // A block map: a new last line at the entries' indent, before what follows.
  const std::string block = add_parameter_set(kSetCup, "cup.yaml", "mine", values);
  CHECK(block == replaced(kSetCup, "  wide: {width: \"=height * 2.5\"}\n",
                          "  wide: {width: \"=height * 2.5\"}\n  mine: {height: 7, width: 6.5}\n"));
  CHECK(value_of(read_text(block, {"parameter_set=mine"}), "width") == 6.5);
  // A flow map: a new last entry before its closing brace, comments kept.
  const std::string flow_cup =
      replaced(kSetCup,
               "parameter_sets:\n  tall: {height: 8}\n  small: {height: 3, width: 5}\n  wide: {width: "
               "\"=height * 2.5\"}\n",
               "parameter_sets: {tall: {height: 8},  # tall\n  small: {height: 3}}  # end\n");
  CHECK(add_parameter_set(flow_cup, "cup.yaml", "mine", values) ==
        replaced(flow_cup, "{height: 3}}", "{height: 3}, mine: {height: 7, width: 6.5}}"));
  // No sets yet: a new `parameter_sets:` at the end.
  const std::string none = replaced(kSetCup,
                                    "parameter_sets:\n  tall: {height: 8}\n  small: {height: 3, width: 5}\n  "
                                    "wide: {width: \"=height * 2.5\"}\n",
                                    "");
  CHECK(add_parameter_set(none, "cup.yaml", "mine", values) ==
        none + "parameter_sets:\n  mine: {height: 7, width: 6.5}\n");
  // A set of that name already: refused at it.
  CHECK_THROWS_WITH(
      add_parameter_set(kSetCup, "cup.yaml", "small", values),
      Catch::StartsWith("cup.yaml:9:10: parameter_sets.small: the design has this set already"));
  // The file's parameter_set: replaced where written, else a new last line.
  CHECK(edit_values(kSetCup, "cup.yaml", {make_override("parameter_set", "tall")}) ==
        kSetCup + "parameter_set: tall\n");
  const std::string chosen = kSetCup + "parameter_set: small  # the default\n";
  CHECK(edit_values(chosen, "cup.yaml", {make_override("parameter_set", "wide")}) ==
        kSetCup + "parameter_set: wide  # the default\n");
}
