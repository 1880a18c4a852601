#include "geometry/core/side_by_side.h"

#include <atomic>
#include <catch2/catch.hpp>
#include <stdexcept>
#include <string>

using namespace fabmesh;

TEST_CASE("side_by_side: both pieces of work run to their end", "[core]") {
  std::atomic<int> first{0};
  std::atomic<int> second{0};
  side_by_side([&] { first = 1; }, [&] { second = 2; });
  CHECK(first == 1);
  CHECK(second == 2);
}

TEST_CASE("side_by_side: the failure is the one of the work in turn", "[core]") {
  const auto message = [](const std::function<void()>& a, const std::function<void()>& b) {
    try {
      side_by_side(a, b);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("none");
  };
  const auto fails = [](const char* what) { return [what] { throw std::runtime_error(what); }; };
  const auto succeeds = [] {};
  // Both fail: the first's, every time, whichever finished first.
  for (int i = 0; i < 50; ++i) CHECK(message(fails("first"), fails("second")) == "first");
  CHECK(message(succeeds, fails("second")) == "second");
  CHECK(message(fails("first"), succeeds) == "first");
  CHECK(message(succeeds, succeeds) == "none");
  // The second runs to its end even when the first fails.
  std::atomic<bool> finished{false};
  CHECK(message(fails("first"), [&] { finished = true; }) == "first");
  CHECK(finished);
}
