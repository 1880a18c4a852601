#include <catch2/catch.hpp>

#include "geometry/mould/mould.h"
#include "geometry/validation/validate.h"
#include "tests/geometry/mould/mould_example.h"
#include "tests/geometry/mould/mould_fixtures.h"

using namespace fabmesh;
using namespace fabmesh::test;

TEST_CASE("mould examples: every mould_*.yaml builds a mould whose parts pass the full validation",
          "[mould][examples]") {
  for (const char* file : {"mould_golden.yaml", "mould_golden_box_base.yaml", "mould_p1_moved.yaml",
                           "mould_p3_moved.yaml", "mould_lambdas.yaml"}) {
    INFO(file);
    const MouldExample e = read_mould_example(example_path(file));
    CHECK(e.units == "cm");
    const Mould m = build_mould(e.profile, e.options);
    CHECK(m.undercuts.empty());
    CHECK(m.warnings.empty());
    CHECK(m.parts.size() == static_cast<std::size_t>(e.options.parts) + (e.options.base_part ? 1 : 0));
    CHECK(m.keys.centres.size() == static_cast<std::size_t>(e.options.keys));
    for (const MouldPart& part : m.parts) {
      INFO(part.name);
      const ValidationReport full = validate(part.soup);
      for (const std::string& d : describe_defects(full)) INFO(d);
      CHECK(full.valid());
      REQUIRE(full.genus.has_value());
      CHECK(*full.genus == 0);
      CHECK(full.components == 1);
    }
    CHECK(std::abs(m.plaster_volume + m.cavity_volume - m.block_volume - m.key_volume) <=
          m.volume_error_bound);
  }
}
