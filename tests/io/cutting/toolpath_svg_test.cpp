// The picture of a toolpath over its part.

#include "io/cutting/toolpath_svg.h"

#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/geometry/section/region_shapes.h"

using namespace fabmesh;
using namespace fabmesh::test;

TEST_CASE("toolpath svg: part, dashed tool paths, leads, plunges, tabs and dog-bones, well-formed XML",
          "[io][cutting][svg][toolpath]") {
  const CompositeCurve slab = polygon({Vec2(0, 0), Vec2(900, 0), Vec2(900, 600), Vec2(0, 600)});
  const CompositeCurve square = polygon({Vec2(300, 200), Vec2(600, 200), Vec2(600, 400), Vec2(300, 400)});
  CncOptions o;
  o.relief = CornerRelief::Dogbone;
  o.tabs.min_radius = 1000;
  const Toolpath tp = plan_toolpath(slab, {{square, "holes[0] (outline)"}}, o);
  CutLoopOptions co;
  std::vector<CutLoop> part{cut_loop(slab, "outline", true, co),
                            cut_loop(square, "holes[0] (outline)", false, co)};
  const std::string svg = encode_toolpath_svg(part, tp);
  for (const char* id :
       {"id=\"part\"", "id=\"path-0\"", "id=\"path-1\"", "id=\"lead-0\"", "id=\"lead-1\"", "id=\"plunge-0\"",
        "id=\"plunge-1\"", "id=\"tab-1-0\"", "id=\"tab-1-3\"", "id=\"dogbone-0-0\"", "id=\"dogbone-0-3\""}) {
    CHECK(svg.find(id) != std::string::npos);
  }
  CHECK(svg.find("id=\"tab-1-4\"") == std::string::npos);
  CHECK(svg.find("id=\"dogbone-0-4\"") == std::string::npos);
  CHECK(svg.find("stroke-dasharray") != std::string::npos);
  CHECK(svg.find("fill-rule=\"evenodd\"") != std::string::npos);
  // viewBox: everything drawn plus the 5 mm margin; the outline's lead starts outside the slab's path.
  const std::size_t view = svg.find("viewBox=\"");
  REQUIRE(view != std::string::npos);
  std::istringstream box(svg.substr(view + 9, svg.find('"', view + 9) - view - 9));
  double x0 = 0, y0 = 0, w = 0, h = 0;
  REQUIRE(static_cast<bool>(box >> x0 >> y0 >> w >> h));
  CHECK(x0 <= -6 - 5);
  CHECK(x0 + w >= 906 + 5);
  CHECK(y0 <= -606 - 5);  // y is written negated
  CHECK(y0 + h >= 6 + 5);
  // A real XML parser reads it.
  const std::filesystem::path file = std::filesystem::path(FABMESH_TEST_TMP) / "toolpath.svg";
  write_toolpath_svg(file.string(), part, tp);
  const std::string cmd =
      "python3 -c 'import sys, xml.dom.minidom; d = xml.dom.minidom.parse(sys.argv[1]); "
      "print(len(d.getElementsByTagName(\"path\")))' '" +
      file.string() + "'";
  FILE* pipe = popen(cmd.c_str(), "r");
  REQUIRE(pipe != nullptr);
  char buffer[64] = {0};
  const std::size_t n = fread(buffer, 1, sizeof buffer - 1, pipe);
  INFO("python3 with its xml module must be installed");
  REQUIRE(pclose(pipe) == 0);
  CHECK(std::stoi(std::string(buffer, n)) >= 1 + 2 + 2 + 4 + 4);
}
