#include "io/design/overrides.h"

#include <catch2/catch.hpp>
#include <string>

#include "geometry/core/errors.h"
#include "io/design/read_design.h"
#include "tests/io/design/cup_design.h"

using namespace fabmesh;
using fabmesh::test::kCup;

namespace {

const std::string kComposite = R"(name: c
kind: curve
curve:
  family: tbezier
  segments:
    - points: [[0, 0], [1, 2], [3, 2.5], [4, 1]]
      lambda: 0
)";

Design with(const std::string& yaml, const std::vector<std::string>& defines) {
  std::vector<Override> overrides;
  for (const std::string& d : defines) overrides.push_back(parse_override(d));
  return parse_design(yaml, "cup.yaml", overrides);
}

std::string error_of(const std::string& yaml, const std::vector<std::string>& defines) {
  try {
    with(yaml, defines);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("overrides: -D replaces scalars, list entries and nested fields, and adds missing keys",
          "[io][design][overrides]") {
  const Design d = with(kCup, {"tolerance=0.01", "body.wall=0.25", "profile.points[1]=[1.2, 5]",
                               "profile.lambdas[0]=-1", "name=cup_thin"});
  CHECK(d.common.tolerance == 0.01);
  CHECK(d.common.name == "cup_thin");
  const auto& v = std::get<VesselDesign>(d.body);
  CHECK(v.wall == 0.25);
  CHECK(v.base == 0.4);
  CHECK(v.profile.bspline_points[1] == Vec2(1.2, 5));
  CHECK(v.profile.bspline_lambdas[0] == -1.0);
  const Design c = with(kComposite, {"curve.segments[0].mu=-1"});
  CHECK(std::get<CurveDesign>(c.body).curve.segments[0].mu == -1.0);
  // The later of two overrides of one field wins, as on OpenSCAD's command line.
  CHECK(std::get<VesselDesign>(with(kCup, {"body.wall=0.2", "body.wall=0.1"}).body).wall == 0.1);
}

TEST_CASE("overrides: a bad path or value is bad input naming the override, as in the file",
          "[io][design][overrides][errors]") {
  CHECK_THAT(error_of(kCup, {"body.wal=2"}),
             Catch::StartsWith("-D body.wal=2: body.wal: unknown key 'wal'") &&
                 Catch::Contains("expected one of: mode, wall, base"));
  CHECK_THAT(error_of(kCup, {"body.wall=-1"}),
             Catch::StartsWith("-D body.wall=-1: body.wall: wall = -1 must be > 0"));
  CHECK_THAT(error_of(kCup, {"profile.points[1]=[1]"}),
             Catch::StartsWith("-D profile.points[1]=[1]: profile.points[1]") && Catch::Contains("[x, y]"));
  CHECK_THAT(error_of(kCup, {"profile.points[9]=[1, 5]"}),
             Catch::Contains("profile.points has 5 entries; [9] is out of range"));
  CHECK_THAT(error_of(kCup, {"tolerance.x=1"}), Catch::Contains("tolerance is not a map"));
  CHECK_THAT(error_of(kCup, {"body.wall=[1, 2"}), Catch::Contains("the value is not valid YAML"));
  CHECK_THAT(error_of(kCup, {"units=furlong"}),
             Catch::StartsWith("-D units=furlong: units: 'furlong' is not one of"));
  CHECK_THROWS_AS(parse_override("body.wall"), InputError);
  CHECK_THROWS_AS(parse_override("=2"), InputError);
  CHECK_THROWS_AS(parse_override("points[x]=2"), InputError);
  CHECK_THROWS_AS(parse_override("body..wall=2"), InputError);
  // An error elsewhere in the file still names the file position.
  CHECK_THAT(error_of(kCup + "extra: 1\n", {"body.wall=0.2"}), Catch::StartsWith("cup.yaml:10:1: extra"));
}

TEST_CASE("design names: plain file names only", "[io][design][errors]") {
  for (const std::string name : {"../../x", "/an/absolute/x", ".", "..", ".hidden", "a/b", "back\\\\slash",
                                 "new\\nline", "tab\\there", "-rf"}) {
    INFO(name);
    const std::string yaml = "name: \"" + name + "\"\n" + kCup.substr(kCup.find('\n') + 1);
    CHECK_THAT(error_of(yaml, {}), Catch::Contains("is not a plain file name"));
  }
  CHECK_THAT(error_of("name: \"\"\n" + kCup.substr(kCup.find('\n') + 1), {}), Catch::Contains("it is empty"));
  CHECK_THAT(error_of("name: " + std::string(121, 'a') + "\n" + kCup.substr(kCup.find('\n') + 1), {}),
             Catch::Contains("longer than 120 bytes"));
  CHECK(with("name: tasse à café (v2)\n" + kCup.substr(kCup.find('\n') + 1), {}).common.name ==
        "tasse à café (v2)");
  // A NUL cannot reach a file name either.
  CHECK_THAT(error_of(std::string("name: \"a\\0b\"\n") + kCup.substr(kCup.find('\n') + 1), {}),
             Catch::Contains("is not a plain file name"));
}

TEST_CASE("design files: duplicate keys and a second YAML document are bad input", "[io][design][errors]") {
  CHECK_THAT(error_of(kCup + "tolerance: 0.5\n", {}),
             Catch::Contains("cup.yaml:10:1: tolerance: key 'tolerance' is given twice (first at line 4"));
  CHECK_THAT(error_of(kCup + "---\nname: other\n", {}), Catch::Contains("a second one starts here"));
  CHECK_THAT(error_of("? [x]\n: 1\n" + kCup, {}), Catch::Contains("a key must be a plain name"));
}

TEST_CASE("overrides: a control character in a value is refused, shown escaped in a whole message",
          "[io][design][overrides][errors]") {
  // A NUL would end the message (an exception's text is a C string) and make
  // yaml-cpp read the rest as UTF-16.
  const std::string nul("body.wall=0\0.2 and more", 23);
  CHECK(
      error_of(kCup, {nul}) ==
      "-D body.wall=0\\x00.2 and more: the value holds a control character (\\x00, byte 2), which YAML does "
      "not allow");
  CHECK_THAT(error_of(kCup, {"body.wall=0.2\x1b"}),
             Catch::StartsWith("-D body.wall=0.2\\x1b: the value holds"));
  // Tabs and line ends are YAML's own.
  CHECK(std::get<VesselDesign>(with(kCup, {"body.wall=\t0.25\r\n"}).body).wall == 0.25);
  // A path and a value held apart, as the studio's requests hold them: the value may hold '=', the path not.
  const Override o = make_override("body.wall", "=0.1 + 0.1");
  CHECK(o.path == "body.wall");
  CHECK(o.value == "=0.1 + 0.1");
  CHECK(o.text == "body.wall==0.1 + 0.1");
  CHECK_THROWS_AS(make_override("a=b", "1"), InputError);
  CHECK_THROWS_AS(make_override("", "1"), InputError);
}
