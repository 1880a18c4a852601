// The one wording of a job over its budget (docs/reports.md quotes it).

#include "geometry/core/budget.h"

#include <catch2/catch.hpp>

#include "geometry/core/errors.h"

using namespace fabmesh;

TEST_CASE("budget: over it is a BudgetError with the need, the budget and the advice", "[core][budget]") {
  bool made = false;
  auto need = [&] {
    made = true;
    return std::string("the slab needs 12 triangles");
  };
  require_within_budget(std::size_t{10}, 10, need, "raise max_triangles");
  require_within_budget(9.5, 10, need);
  CHECK_FALSE(made);  // the text is made only when it is thrown
  try {
    require_within_budget(std::size_t{12}, 10, need, "raise max_triangles");
    FAIL("no BudgetError");
  } catch (const BudgetError& e) {
    CHECK(std::string(e.what()) ==
          "the slab needs 12 triangles, over the budget of 10 (raise max_triangles)");
    CHECK(e.requested() == 12.0);
    CHECK(e.budget() == 10.0);
  }
  CHECK_THROWS_WITH(
      require_within_budget(10.5, 10, [] { return std::string("the curve needs 10.5 samples"); }),
      "the curve needs 10.5 samples, over the budget of 10");
}
