// A value only building can judge (a base taller than the cavity, a wall too
// thick for the profile's curvature, a tolerance over the triangle budget, a
// Draco output that cannot hold the tolerance) is reported at the key that
// gave it: file:line:column or the -D override, then the key, then why.

#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

#include "io/file.h"
#include "tests/pipeline/cli_harness.h"

using namespace fabmesh;
using namespace fabmesh::testing;
namespace fs = std::filesystem;

namespace {

// The golden shell with `find` replaced by `replace`, written to `dir/name`.
std::string shell_with(const fs::path& dir, const std::string& name, const std::string& find,
                       const std::string& replace) {
  return edited_example(dir, "vessel_golden_shell.yaml", find, replace, name);
}

// Runs `args` and requires a refusal with nothing written.
CliResult refused(const fs::path& dir, std::vector<std::string> args) {
  args.insert(args.end(), {"-o", (dir / "out").string()});
  const CliResult r = run_fabmesh(args);
  INFO(r.out << r.err);
  CHECK(r.code == 2);
  CHECK((!fs::exists(dir / "out") || fs::is_empty(dir / "out")));
  return r;
}

}  // namespace

TEST_CASE("located errors: a base taller than the cavity is reported at body.base", "[pipeline][errors]") {
  const fs::path dir = fresh_dir("located_base");
  const std::string design = shell_with(dir, "tall_base.yaml", "base: 0.4", "base: 5");
  const CliResult r = refused(dir, {"run", design});
  CHECK(names_place(r.err, design, "body.base"));
  CHECK_THAT(r.err, Catch::Contains("leaves no cavity"));
  const CliResult d = refused(dir, {"run", example("vessel_golden_shell.yaml"), "-D", "body.base=100"});
  CHECK_THAT(d.err, Catch::Contains("-D body.base=100: body.base: base 100 leaves no cavity"));
}

TEST_CASE(
    "located errors: a wall too thick for the profile is reported at body.wall, naming the segment once",
    "[pipeline][errors]") {
  const fs::path dir = fresh_dir("located_wall");
  const std::string design = shell_with(dir, "thick.yaml", "wall: 0.3", "wall: 3");
  const CliResult r = refused(dir, {"run", design});
  CHECK(names_place(r.err, design, "body.wall"));
  CHECK_THAT(r.err, Catch::Contains("segment 3 of " + design + ":"));
  CHECK_THAT(r.err, !Catch::Contains("profile profile"));
  // Without a base, the base is the wall: a wall too thick is still at body.wall.
  const CliResult d = refused(dir, {"run", example("vessel_golden_shell.yaml"), "-D", "body.wall=0.6"});
  CHECK_THAT(d.err, Catch::StartsWith("fabmesh: error: -D body.wall=0.6: body.wall: wall 0.6 is too thick"));
}

TEST_CASE("located errors: a budget error is reported at the tolerance, in the design's unit",
          "[pipeline][errors]") {
  const fs::path dir = fresh_dir("located_budget");
  const std::string design = example("vessel_golden_shell.yaml");
  const CliResult r = refused(dir, {"run", design, "-D", "max_triangles=10"});
  CHECK(names_place(r.err, design, "tolerance"));
  // The design's tolerance as written, not the share of it the mesh gets.
  CHECK_THAT(r.err, Catch::Contains("tolerance: 0.005 cm: the mesh needs at least"));
  const CliResult d = refused(dir, {"run", design, "-D", "tolerance=1e-12"});
  CHECK_THAT(d.err, Catch::Contains("-D tolerance=1e-12: tolerance: 1e-12 cm: the mesh needs at least"));
}

TEST_CASE("located errors: a Draco output that cannot hold the tolerance fails at its outputs entry",
          "[pipeline][errors]") {
  const fs::path dir = fresh_dir("located_draco");
  // 1 km above the origin at 0.05 mm: float32 positions alone move vertices by more.
  const std::string design =
      shell_with(dir, "far.yaml", "points: [[1.5, 6], [1, 5], [2, 4], [3, 3], [1.5, 2]]",
                 "points: [[1.5, 100006], [1, 100005], [2, 100004], [3, 100003], [1.5, 100002]]\n"
                 "  # far from the origin");
  const CliResult r = refused(dir, {"run", design, "-D", "outputs=[drc]", "-D", "on_output_error=fail"});
  CHECK_THAT(r.err, Catch::Contains("-D outputs=[drc]: outputs[0]: drc: Draco cannot keep every vertex"));
}

TEST_CASE("located errors: a mould option is reported at its key under mould, never at body",
          "[pipeline][errors]") {
  const fs::path dir = fresh_dir("located_mould");
  // Three parts pull 30 degrees off the keys' axes: the golden mould's 0.2 mm sockets are too tight.
  const std::string design = example("mould_golden.yaml");
  const CliResult r = refused(dir, {"run", design, "-D", "mould.parts=3"});
  CHECK(names_place(r.err, design, "mould.key_clearance"));
  CHECK_THAT(r.err, !Catch::Contains("body."));
  const CliResult d = refused(dir, {"run", design, "-D", "mould.parts=3", "-D", "mould.key_clearance=0.03"});
  CHECK_THAT(d.err, Catch::StartsWith("fabmesh: error: -D mould.key_clearance=0.03: mould.key_clearance: "));
}

TEST_CASE("located errors: a value the design never wrote is reported at its key as (default)",
          "[pipeline][errors]") {
  const fs::path dir = fresh_dir("located_default");
  // A mould the design does not have, made by -D: its keys are placed at the default
  // positions, where 30 mm keys do not fit (the default key_clearance releases for every
  // `parts` since issue 24, so `-D mould.parts=3` alone builds).
  const std::string design = example("vessel_golden_solid.yaml");
  const CliResult r = refused(dir, {"run", design, "-D", "mould.key_radius=3"});
  CHECK_THAT(r.err, Catch::StartsWith("fabmesh: error: " + design + ": mould.keys[0] (default): "));
  CHECK_THAT(r.err, !Catch::Contains("body."));
}
