// The design reader against hostile text: numbers out of range, text that is
// not UTF-8, trees too large for their bytes. Each is bad input (FileError)
// at its line and column, never a value silently changed.

#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "geometry/core/errors.h"
#include "io/design/overrides.h"
#include "io/design/points_csv.h"
#include "io/design/read_design.h"
#include "io/design/utf8.h"
#include "tests/io/mesh/temp_dir.h"

using namespace fabmesh;

namespace {

const std::string kCurve =
    "kind: curve\ntolerance: 0.01\ncurve:\n  family: quasi_bspline\n"
    "  points: [[1.5, 6], [1, 5], [2, 4], [3, 3], [1.5, 2]]\n";

// The message of the FileError that parsing `yaml` (with `overrides`) throws ("" if none).
std::string error_of(const std::string& yaml, const std::vector<std::string>& defines = {}) {
  try {
    std::vector<Override> overrides;
    for (const std::string& d : defines) overrides.push_back(parse_override(d));
    parse_design(yaml, "d.yaml", overrides);
  } catch (const FileError& e) {
    return e.what();
  }
  return "";
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  text.replace(text.find(from), from.size(), to);
  return text;
}

}  // namespace

TEST_CASE("design: a number beyond 1e12 in magnitude is bad input naming the field", "[io][design][errors]") {
  REQUIRE(error_of(kCurve).empty());
  CHECK_THAT(error_of(replaced(kCurve, "[1.5, 6]", "[1e300, 6]")),
             Catch::StartsWith("d.yaml:5:13: curve.points[0][0]: 1e300 is too large") &&
                 !Catch::Contains("nan") && !Catch::Contains("inf"));
  CHECK_THAT(error_of(kCurve, {"curve.points[2]=[2, -1.5e12]"}),
             Catch::Contains("curve.points[2][1]") && Catch::Contains("-1.5e12 is too large"));
  // The limit itself is accepted.
  CHECK(error_of(replaced(kCurve, "[1.5, 6]", "[1e12, 6]")).find("too large") == std::string::npos);
  CHECK_THAT(error_of(replaced(kCurve, "tolerance: 0.01", "tolerance: 1e300")),
             Catch::Contains("tolerance: 1e300 is too large"));
}

TEST_CASE("points csv: a coordinate beyond 1e12 is bad input at its row and column", "[io][design][errors]") {
  CHECK(parse_points_csv("1e12,-1e12\n", "p.csv").size() == 1);
  CHECK_THROWS_WITH(parse_points_csv("x,y\n0,0\n1, 2e12\n", "p.csv"),
                    Catch::StartsWith("p.csv:3:4: y = 2e12 is too large"));
  CHECK_THROWS_WITH(parse_points_csv("0,0\n1e999,0\n", "p.csv"),
                    Catch::StartsWith("p.csv:2:1: x = 1e999 is not a finite number"));
}

TEST_CASE(
    "points csv: every coordinate reads to the double strtod reads it to, and what it refuses is refused",
    "[io][design][errors]") {
  // The reader takes the fast path (from_chars) and falls back on strtod:
  // the values must be strtod's to the bit, whichever path read them.
  std::vector<std::string> texts = {"0",
                                    "-0",
                                    "1",
                                    "+1.5",
                                    ".5",
                                    "5.",
                                    "0x1p3",
                                    "1e-320",
                                    "-4.9e-324",
                                    "1e12",
                                    "999999999999.9999999999999999",
                                    "2.2250738585072011e-308",
                                    "0.1000000000000000055511151231257827021181583404541015625",
                                    "123456789012345678901234567890e-18",
                                    "7E2",
                                    "1e+3",
                                    "00012.5"};
  std::mt19937_64 random(20261201);
  std::uniform_real_distribution<double> value(-1e6, 1e6);
  for (int i = 0; i < 3000; ++i) {
    const double v = value(random);
    texts.push_back(fmt::format("{}", v));       // the shortest text that reads back to v
    texts.push_back(fmt::format("{:.20g}", v));  // more digits than a double holds
    texts.push_back(fmt::format("{:.3f}", v));   // a digitiser's
  }
  std::size_t checked = 0;
  for (const std::string& text : texts) {
    INFO(text);
    const std::vector<Vec2> points = parse_points_csv(text + ",0\n", "p.csv");
    REQUIRE(points.size() == 1);
    const double expected = std::strtod(text.c_str(), nullptr);
    const double read = points[0].x();
    CHECK(std::memcmp(&read, &expected, sizeof expected) == 0);
    ++checked;
  }
  CHECK(checked == texts.size());
  for (const char* text : {"1p3", "0x", "1e", "--1", "1.2.3", "nan(", "inf0"}) {
    INFO(text);
    CHECK_THROWS_AS(parse_points_csv("0,0\n" + std::string(text) + ",0\n", "p.csv"),
                    FileError);  // not as a header
  }
}

TEST_CASE("design: a tolerance below 1e-12 is refused quoting the value as written, never as 0",
          "[io][design][errors]") {
  CHECK_THAT(error_of(replaced(kCurve, "tolerance: 0.01", "tolerance: 4.9e-324")),
             Catch::StartsWith("d.yaml:2:12: tolerance: tolerance = 4.9e-324 is below 1e-12"));
  CHECK_THAT(error_of(kCurve, {"tolerance=1e-13"}), Catch::Contains("tolerance = 1e-13 is below 1e-12"));
  CHECK(error_of(kCurve, {"tolerance=1e-12"}).empty());
  CHECK_THAT(error_of(kCurve, {"tolerance=0"}), Catch::Contains("tolerance = 0 must be > 0"));
}

TEST_CASE("design: text that is not UTF-8 is bad input at its line and column", "[io][design][errors]") {
  CHECK_THAT(error_of(replaced(kCurve, "kind: curve", "kind: curve\nname: cup\xff")),
             Catch::StartsWith("d.yaml:2:10: the design is not UTF-8 text (byte 0xFF here)"));
  CHECK_THAT(error_of("\xc3"), Catch::StartsWith("d.yaml:1:1: the design is not UTF-8 text (byte 0xC3"));
  CHECK_THAT(error_of(kCurve, {"name=cup\xed\xa0\x80"}), Catch::Contains("-D: the value is not UTF-8 text"));
  // Well-formed multi-byte names pass.
  CHECK(error_of("name: \"Tasse \xc3\xa0 th\xc3\xa9 \xe2\x82\xac \xf0\x9f\x8d\xb5\"\n" + kCurve).empty());
}

TEST_CASE("utf8: malformed sequences are found at their first byte", "[io][design]") {
  CHECK(invalid_utf8_offset("") == std::string_view::npos);
  CHECK(invalid_utf8_offset("a\xc3\xa9\xe2\x82\xac\xf0\x9f\x8d\xb5\xf4\x8f\xbf\xbf") ==
        std::string_view::npos);
  CHECK(invalid_utf8_offset("ab\x80") == 2);             // a continuation byte alone
  CHECK(invalid_utf8_offset("a\xc0\xaf") == 1);          // overlong '/'
  CHECK(invalid_utf8_offset("a\xe0\x80\xaf") == 1);      // overlong, three bytes
  CHECK(invalid_utf8_offset("a\xed\xa0\x80") == 1);      // a UTF-16 surrogate
  CHECK(invalid_utf8_offset("a\xf4\x90\x80\x80") == 1);  // above U+10FFFF
  CHECK(invalid_utf8_offset("abc\xe2\x82") == 3);        // cut short
  CHECK(invalid_utf8_offset(std::string_view("a\0b", 3)) == std::string_view::npos);
}

TEST_CASE(
    "design: a design of more YAML values than the budget, or an alias bomb, is refused before it is built",
    "[io][design][errors]") {
  // 2^18 values: a list of 100000 points holds 300001.
  std::string many = "kind: curve\ncurve:\n  family: tbezier\n  segments:\n    - polyline: [";
  for (int i = 0; i < 100000; ++i) many += i == 0 ? "[0,0]" : ",[1,1]";
  many += "]\n";
  CHECK_THAT(error_of(many), Catch::Contains("more than 262144 YAML values") &&
                                 Catch::Contains("polyline: {file: points.csv}"));
  // Ten aliases of ten aliases of ... : a few hundred bytes that stand for 10^9 values.
  std::string bomb = "kind: curve\nl0: &l0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int i = 1; i <= 9; ++i) {
    bomb += "l" + std::to_string(i) + ": &l" + std::to_string(i) + " [";
    for (int k = 0; k < 10; ++k) bomb += (k ? ", *l" : "*l") + std::to_string(i - 1);
    bomb += "]\n";
  }
  CHECK_THAT(error_of(bomb), Catch::Contains("more than 262144 YAML values"));
  // An alias inside the node it names is refused too (yaml-cpp would recurse).
  CHECK_THAT(error_of("kind: curve\na: &a [1, *a]\n"), Catch::Contains("an alias may not stand for a node"));
}

TEST_CASE("design fuzz seeds: every design and points CSV seed reads", "[io][design]") {
  const std::filesystem::path seeds = std::filesystem::path(FABMESH_SOURCE_DIR) / "tests/data/fuzz-seeds";
  int designs = 0, csvs = 0;
  for (const auto& e : std::filesystem::directory_iterator(seeds / "design")) {
    if (e.path().extension() != ".yaml") continue;
    INFO(e.path());
    CHECK_NOTHROW(read_design(e.path().string()));
    ++designs;
  }
  for (const auto& e : std::filesystem::directory_iterator(seeds / "csv")) {
    INFO(e.path());
    CHECK_FALSE(read_points_csv(e.path().string()).empty());
    ++csvs;
  }
  CHECK(designs >= 5);
  CHECK(csvs >= 2);
}
