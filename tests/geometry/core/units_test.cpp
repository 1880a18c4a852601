// The one table of units of length: what designs, the command line and the
// file writers (DXF, 3MF, G-code) read their scales and names from.

#include "geometry/core/units.h"

#include <catch2/catch.hpp>

using namespace fabmesh;

TEST_CASE("units: mm, cm, m and in with their scales, in the order messages list them", "[core][units]") {
  CHECK(length_unit_names() == std::vector<std::string>{"mm", "cm", "m", "in"});
  CHECK(metres_per_unit("mm") == 1e-3);
  CHECK(metres_per_unit("cm") == 1e-2);
  CHECK(metres_per_unit("m") == 1.0);
  CHECK(metres_per_unit("in") == 0.0254);
  CHECK(millimetres_per_unit("in") == Approx(25.4));
  CHECK(length_unit("in").dxf_insunits == 1);
  CHECK(length_unit("mm").dxf_insunits == 4);
  static_assert(metres_per_unit("cm") == 1e-2, "usable in constant expressions (3MF's table)");
  CHECK_THROWS_AS(metres_per_unit("ft"), InputError);
  CHECK_THROWS_WITH(metres_per_unit("ft"), "units 'ft' is not one of mm, cm, m, in");
}
