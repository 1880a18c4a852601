// Choices and switches among a design's parameters (docs/design-files.md,
// "Choices and switches"): a text from a list or true / false, put where the
// design takes a text or a switch ("=mode"), switches in formulas as 1 and 0
// with `a ? b : c`, and every bad value named with what is allowed.

#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "geometry/core/errors.h"
#include "io/design/read_design.h"
#include "tests/io/design/design_text.h"

using namespace fabmesh;
using fabmesh::test::read_error;
using fabmesh::test::read_text;
using fabmesh::test::replaced;

namespace {

// A cup whose body is a choice, whose wall follows a switch, and whose mould
// is switched off. Line 5 declares mode (its value at column 17).
const std::string kChoiceCup = R"(name: cup
kind: vessel
units: cm
parameters:
  mode: {value: shell, choices: [shell, solid], description: "hollow or full"}
  thick: false
  wall: "=thick ? 0.4 : 0.3"
  with_mould: {value: false}
parameter_sets:
  full: {mode: solid, thick: true}
profile:
  family: quasi_bspline
  points: [[1.5, 6], [1, 4], [2, 3], [3, 2.5], [1.5, 2]]
  lambdas: [0, 0, 0]
body: {mode: "=mode", wall: "=wall"}
mould: "=with_mould"
)";

const DesignParameter& parameter(const Design& d, const std::string& name) {
  for (const DesignParameter& p : d.common.parameters) {
    if (p.name == name) return p;
  }
  FAIL("no parameter " << name);
  return d.common.parameters.front();
}

const VesselDesign& vessel(const Design& d) { return std::get<VesselDesign>(d.body); }

}  // namespace

TEST_CASE("parameter choices: a choice and switches, resolved and put in place", "[io][design][choices]") {
  const Design d = read_text(kChoiceCup);
  const DesignParameter& mode = parameter(d, "mode");
  CHECK(mode.kind == ParameterKind::Choice);
  CHECK(mode.text == "shell");
  CHECK(mode.value == 0);
  CHECK(mode.choices == std::vector<std::string>{"shell", "solid"});
  CHECK(mode.description == "hollow or full");
  const DesignParameter& thick = parameter(d, "thick");
  CHECK(thick.kind == ParameterKind::Switch);
  CHECK(thick.text == "false");
  CHECK(thick.value == 0);
  CHECK(parameter(d, "with_mould").kind == ParameterKind::Switch);
  // Put where the design takes them: the body's mode, the mould switched off.
  CHECK(vessel(d).mode == BodyMode::Shell);
  CHECK_FALSE(vessel(d).mould.has_value());
  // A switch in a formula is 1 or 0, and a ? b : c chooses.
  CHECK(parameter(d, "wall").value == 0.3);
  CHECK(vessel(d).wall == 0.3);

  const Design other = read_text(kChoiceCup, {"mode=solid", "thick=true", "with_mould=true"});
  CHECK(vessel(other).mode == BodyMode::Solid);
  CHECK(parameter(other, "thick").value == 1);
  CHECK(parameter(other, "wall").value == 0.4);
  CHECK(vessel(other).mould.has_value());  // `mould: true`: a mould of every default
  // The shell's wall stays in the design for the shell the choice also makes: unused, noted.
  CHECK(other.common.notes ==
        std::vector<std::string>{"body.wall is not used: the body is solid (cup.yaml:15:14)"});
  // Written as solid in the file, the wall is an error as ever.
  CHECK(read_error(replaced(kChoiceCup, "body: {mode: \"=mode\"", "body: {mode: solid")) ==
        "cup.yaml:15:27: body.wall: a solid body has no wall, base or rim");
  // A set gives choices and switches too.
  const Design full = read_text(kChoiceCup, {"parameter_set=full"});
  CHECK(vessel(full).mode == BodyMode::Solid);
  CHECK(parameter(full, "wall").value == 0.4);
  // YAML's other spellings of a switch.
  CHECK(parameter(read_text(kChoiceCup, {"thick=True"}), "thick").text == "true");
}

TEST_CASE("parameter choices: bad values name the parameter and what it takes", "[io][design][choices]") {
  CHECK(read_error(kChoiceCup, {"mode=glass"}) ==
        "-D mode=glass: parameters.mode: \"glass\" is not one of the choices: shell, solid");
  CHECK(read_error(kChoiceCup, {"thick=1"}) ==
        "-D thick=1: parameters.thick: thick is a switch: true or false");
  CHECK(read_error(kChoiceCup, {"wall=true"}) ==
        "-D wall=true: parameters.wall: wall is a number, not a switch");
  CHECK(read_error(replaced(kChoiceCup, "{value: shell,", "{value: glass,")) ==
        "cup.yaml:5:17: parameters.mode: \"glass\" is not one of the choices: shell, solid");
  CHECK(read_error(replaced(kChoiceCup, "full: {mode: solid, thick: true}", "full: {thick: 3}")) ==
        "cup.yaml:10:17: parameter_sets.full.thick: thick is a switch: true or false");
  // A choice is a text: not in a formula.
  CHECK(read_error(replaced(kChoiceCup, "\"=thick ? 0.4 : 0.3\"", "\"=mode * 2\"")) ==
        "cup.yaml:7:9: parameters.wall: \"=mode * 2\": 'mode' is a choice (shell, solid): write \"=mode\" "
        "alone "
        "where the design takes a text, not in a formula");
  CHECK(read_error(replaced(kChoiceCup, "choices: [shell, solid]", "choices: [shell, shell]"))
            .find("parameters.mode.choices[1]: the choice 'shell' is given twice") != std::string::npos);
  CHECK(read_error(replaced(kChoiceCup, "choices: [shell, solid]", "choices: [shell]"))
            .find("parameters.mode.choices") != std::string::npos);
  CHECK(read_error(replaced(kChoiceCup, "choices: [shell, solid]", "choices: [shell, solid], min: 1"))
            .find("parameters.mode.min: a choice has no min: it takes one of its choices") !=
        std::string::npos);
  CHECK(read_error(replaced(kChoiceCup, "with_mould: {value: false}", "with_mould: {value: false, max: 2}"))
            .find("parameters.with_mould.max: a switch has no max: it takes true or false") !=
        std::string::npos);
}
