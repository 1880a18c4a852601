// The one mapping between exit codes and the statuses every report shows.

#include "pipeline/failure.h"

#include <catch2/catch.hpp>
#include <string>

using namespace fabmesh;

TEST_CASE("failure: each exit code has its status and back", "[pipeline][report]") {
  for (const int code : {kExitOk, kExitInvalid, kExitBadInput, kExitInternal, kExitEnvironment}) {
    INFO(code);
    CHECK(exit_code_of(status_of(code)) == code);
  }
  CHECK(status_of(kExitOk) == ItemStatus::Ok);
  CHECK(status_of(kExitInvalid) == ItemStatus::Invalid);
  CHECK(status_of(kExitBadInput) == ItemStatus::BadInput);
  CHECK(status_of(kExitInternal) == ItemStatus::Error);
  CHECK(status_of(kExitEnvironment) == ItemStatus::Environment);
}

TEST_CASE("failure: an unknown exit code is an error, a missing item exits 0", "[pipeline][report]") {
  CHECK(status_of(4) == ItemStatus::Error);
  CHECK(status_of(-1) == ItemStatus::Error);
  CHECK(exit_code_of(ItemStatus::Missing) == kExitOk);
}

TEST_CASE("failure: the status words are the ones the reports print", "[pipeline][report]") {
  CHECK(std::string(to_string(ItemStatus::Ok)) == "ok");
  CHECK(std::string(to_string(ItemStatus::Invalid)) == "invalid");
  CHECK(std::string(to_string(ItemStatus::BadInput)) == "bad input");
  CHECK(std::string(to_string(ItemStatus::Error)) == "error");
  CHECK(std::string(to_string(ItemStatus::Missing)) == "missing");
  CHECK(std::string(to_string(ItemStatus::Environment)) == "environment");
}
