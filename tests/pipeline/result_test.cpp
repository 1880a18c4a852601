// A job's one Result: its parts, and the one serializer every report of it
// comes from, so that a fact added in one place is seen everywhere.

#include "pipeline/result.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "pipeline/batch/batch_row.h"
#include "pipeline/job.h"
#include "pipeline/load_design.h"
#include "pipeline/report.h"
#include "pipeline/studio/studio_session.h"
#include "pipeline/summary.h"
#include "tests/pipeline/cli_harness.h"

using namespace fabmesh;
using namespace fabmesh::testing;

namespace {

// The result `run` would make of an example, built and validated, nothing written.
Result built(const std::string& name, JobPlan* plan_out = nullptr) {
  const Design design = load_design(example(name));
  const JobPlan plan = plan_job(design, {});
  if (plan_out != nullptr) *plan_out = plan;
  return build_job(design, plan);
}

}  // namespace

TEST_CASE("result: a fact added in one place is in run --json, a batch row and the studio's build",
          "[pipeline][result]") {
  JobPlan plan;
  Result result = built("vessel_golden_shell.yaml", &plan);
  REQUIRE(fit(result));
  // The one place: the result's facts (a builder adds its own the same way).
  result.facts.set("added_for_this_test", 42);
  Facts group;
  group.set("depth", 2.5).set("label", "seen");
  result.facts.set("added_group", group);

  const nlohmann::ordered_json run_item =
      design_item("cup.yaml", result);  // run --json; the library's to_json
  CHECK(run_item.at("build").at("added_for_this_test") == 42);
  CHECK(run_item.at("build").at("added_group").at("label") == "seen");

  BatchRow row;  // batch: summary.jsonl, and back when shards are merged
  record_result(row, result);
  CHECK(row_json(row).at("build").at("added_for_this_test") == 42);
  const BatchRow read_back = row_from_json(nlohmann::ordered_json::parse(row_json(row).dump()));
  CHECK(read_back.build.number("added_for_this_test") == 42.0);
  CHECK(read_back.build.group("added_group").text("label") == "seen");

  const nlohmann::json studio = nlohmann::json::parse(studio_build_report("cup.yaml", result, plan.formats));
  CHECK(studio.at("build").at("added_for_this_test") == 42);  // POST /api/build
  CHECK(studio.contains("pending"));
}

TEST_CASE("result: a vessel with a mould is one result of many parts, each validated with its proof",
          "[pipeline][result]") {
  const Result result = built("mould_golden.yaml");
  REQUIRE(fit(result));
  REQUIRE(result.parts.size() >= 3);
  CHECK(result.parts.front().role == PartRole::Product);
  CHECK(result.parts.front().name == result.name);
  std::size_t sides = 0;
  for (const Part& part : result.parts) {
    INFO(part.name);
    CHECK(part.validated);
    CHECK(part.validation.valid());
    CHECK(part.validation.volume > 0.0);
    if (part.role == PartRole::MouldSide) {
      ++sides;
      CHECK(part.name == "side-" + std::to_string(sides));
      CHECK(part.validation.self_intersection == IntersectionCheck::ProvenByConstruction);
    }
  }
  CHECK(sides >= 2);
  CHECK(parts_of(result, PartRole::MouldSide).size() == sides);
  // The report lists every part, in order, with its role and verdict.
  const nlohmann::ordered_json j = to_json(result);
  REQUIRE(j.at("parts").size() == result.parts.size());
  for (std::size_t i = 0; i < result.parts.size(); ++i) {
    CHECK(j["parts"][i]["name"] == result.parts[i].name);
    CHECK(j["parts"][i]["role"] == to_string(result.parts[i].role));
    CHECK(j["parts"][i]["valid"] == true);
  }
  // The builder's mould facts name the same parts.
  const auto& mould_parts = std::get<std::vector<Facts>>(*result.facts.group("mould").find("parts"));
  CHECK(mould_parts.size() + 1 == result.parts.size());
}

TEST_CASE("result: facts keep their types through JSON", "[pipeline][result]") {
  Facts facts;
  facts.set("count", std::size_t{7}).set("ratio", 0.25).set("flag", true).set("name", "x");
  facts.set("sizes", std::vector<double>{1.0, 2.5}).set("words", std::vector<std::string>{"a", "b"});
  Facts inner;
  inner.set("k", -3);
  facts.set("rows", std::vector<Facts>{inner, inner});
  facts.set("count", 8);  // set again: replaced in place
  const nlohmann::ordered_json j = facts_json(facts);
  CHECK(j.dump() ==
        R"({"count":8,"flag":true,"name":"x","ratio":0.25,"rows":[{"k":-3},{"k":-3}],"sizes":[1.0,2.5],)"
        R"("words":["a","b"]})");
  const Facts back = facts_from_json(j);
  CHECK(facts_json(back) == j);
  CHECK(back.number("count") == 8.0);
  CHECK(std::holds_alternative<std::int64_t>(*back.find("count")));
  CHECK_THROWS_AS(back.text("count"), std::logic_error);
  CHECK_THROWS_AS(facts_from_json(nlohmann::ordered_json::array()), InputError);
}

TEST_CASE("result: the summary prints lengths without rounding noise and keeps warnings off its lines",
          "[pipeline][result][summary]") {
  Result result = built("countertop_g1.yaml");
  REQUIRE(fit(result));
  result.bbox_min.z() = 6.66134e-17;  // what a sum of exact lengths may leave
  result.bbox_min.x() = -2.14143e-15;
  result.warnings = {"design.yaml:3:1: a warning"};
  std::ostringstream out, err;
  print_summary(result, out);
  print_warnings(result, "design.yaml", err);
  CHECK(out.str().find("e-1") == std::string::npos);
  CHECK(out.str().find("x 0..") != std::string::npos);
  CHECK(out.str().find("warning") == std::string::npos);
  CHECK(err.str() == "fabmesh: warning: design.yaml:3:1: a warning\n");
  CHECK(summary_number(1e-3, 10.0) == 1e-3);
  CHECK(summary_number(1e-13, 10.0) == 0.0);
}
