// ToleranceBudget: shares that fit, what is left, and overspending caught.

#include "geometry/core/tolerance_budget.h"

#include <catch2/catch.hpp>
#include <stdexcept>

using namespace fabmesh;

TEST_CASE("tolerance budget: a stage gets what the ones before left, exactly", "[core][tolerance]") {
  ToleranceBudget b(0.3);
  const double section = b.take("section", 0.5);
  CHECK(section == 0.5 * 0.3);
  b.use("section", 0.1);
  // What the section left: the total less what it used, not less its share.
  CHECK(b.take_rest("revolution") == 0.3 - 0.1);
  b.use("revolution", 0.2);
  REQUIRE(b.shares().size() == 2);
  CHECK(b.shares()[0].stage == "section");
  CHECK(b.shares()[0].given == section);
  CHECK(b.shares()[0].used == 0.1);
  CHECK(b.shares()[1].done);
  // Nothing left: the next stage gets 0, not a negative share.
  CHECK(b.take_rest("writing") == 0.0);
}

TEST_CASE("tolerance budget: shares that exceed the total, and overspending, are bugs", "[core][tolerance]") {
  ToleranceBudget b(1.0);
  b.take("chords", 0.5);
  b.take("boundary", 0.1);
  b.take("arcs", 0.05);
  b.take("rounding", 0.05);
  CHECK_THROWS_AS(b.take("more", 0.5), std::logic_error);
  CHECK_THROWS_AS(b.use("chords", 0.51), std::logic_error);  // more than its share
  CHECK_THROWS_AS(b.use("nobody", 0.0), std::logic_error);   // never took one
  CHECK_THROWS_AS(b.use("boundary", -1e-9), std::logic_error);
  CHECK_NOTHROW(b.use("chords", 0.5));
  CHECK_THROWS_AS(ToleranceBudget(0.0), std::logic_error);
  CHECK_THROWS_AS(b.take("zero", 0.0), std::logic_error);
  // What a stage does not use returns to the budget for the stages after it.
  ToleranceBudget c(1.0);
  c.take("section", 0.6);
  c.use("section", 0.2);
  CHECK_NOTHROW(c.take("revolution", 0.8));
}
