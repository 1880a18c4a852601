// PrusaSlicer slices every part of an example mould exported as STL.

#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "geometry/mould/mould.h"
#include "io/mesh/stl.h"
#include "tests/geometry/mould/mould_example.h"
#include "tests/geometry/mould/mould_fixtures.h"
#include "tests/io/mesh/temp_dir.h"

using namespace fabmesh;
using namespace fabmesh::test;

namespace {

bool have_program(const std::string& name) {
  return std::system(("command -v " + name + " > /dev/null 2>&1").c_str()) == 0;
}

// The highest ";Z:" layer mark of a PrusaSlicer G-code file and its layer height.
void sliced_height(const std::string& gcode, double* top, double* layer) {
  std::istringstream in(gcode);
  std::string line;
  *top = 0.0;
  *layer = 0.0;
  while (std::getline(in, line)) {
    if (line.rfind(";Z:", 0) == 0) *top = std::max(*top, std::stod(line.substr(3)));
    if (line.rfind("; layer_height = ", 0) == 0) *layer = std::stod(line.substr(17));
  }
}

}  // namespace

TEST_CASE("mould slicing: PrusaSlicer slices every part of the golden box mould to its full height",
          "[mould][prusa]") {
  INFO(
      "prusa-slicer is not installed (scripts/install-deps.sh --test installs it): the mould parts must be "
      "sliced by it");
  REQUIRE(have_program("prusa-slicer"));
  const MouldExample e = read_mould_example(example_path("mould_golden_box_base.yaml"));
  REQUIRE(e.units == "cm");
  const Mould m = build_mould(e.profile, e.options);
  const TempDir dir;
  for (std::size_t i = 0; i < m.parts.size(); ++i) {
    const MouldPart& part = m.parts[i];
    INFO(part.name);
    TriangleSoup mm = part.soup;  // PrusaSlicer reads STL in millimetres
    double lo = 1e300, hi = -1e300;
    for (Vec3& v : mm.vertices) {
      v *= 10.0;
      lo = std::min(lo, v.z());
      hi = std::max(hi, v.z());
    }
    const std::string stl = dir.write("part" + std::to_string(i) + ".stl", encode_stl(mm));
    const std::string gcode = dir.file("part" + std::to_string(i) + ".gcode");
    const std::string cmd = "HOME='" + dir.file("home") + "' prusa-slicer --export-gcode --output '" + gcode +
                            "' '" + stl + "' > '" + dir.file("log.txt") + "' 2>&1";
    const int status = std::system(cmd.c_str());
    REQUIRE(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 0);
    std::ifstream in(gcode, std::ios::binary);
    REQUIRE(in.good());
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    CHECK_THAT(text, Catch::Contains("; estimated printing time"));
    double top = 0.0, layer = 0.0;
    sliced_height(text, &top, &layer);
    REQUIRE(layer > 0.0);
    CHECK(top > hi - lo - layer);
    CHECK(top <= hi - lo + layer);
  }
}
