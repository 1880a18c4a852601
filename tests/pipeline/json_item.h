#pragma once
// Reading the `--json` documents of the commands in tests.

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>

namespace fabmesh::testing {

/// The one item of a `--json` document (docs/reports.md: always an array of
/// items, one per input), for a command given one input.
inline nlohmann::json only_item(const std::string& json_text) {
  INFO(json_text);
  const nlohmann::json items = nlohmann::json::parse(json_text);
  REQUIRE(items.is_array());
  REQUIRE(items.size() == 1);
  REQUIRE(items[0].is_object());
  return items[0];
}

}  // namespace fabmesh::testing
