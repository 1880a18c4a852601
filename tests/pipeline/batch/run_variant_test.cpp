#include "pipeline/batch/run_variant.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "io/design/manifest.h"
#include "pipeline/batch/plan.h"
#include "pipeline/batch/sha256.h"
#include "pipeline/plane_memo.h"
#include "tests/pipeline/cli_harness.h"

using namespace fabmesh;
namespace fs = std::filesystem;

namespace {

// An ok row listing `files` (a JSON list), as the ledger holds it.
std::string ok_row(const nlohmann::json& files) {
  return nlohmann::json{{"name", "cup"}, {"status", "ok"}, {"files", files}}.dump();
}

}  // namespace

TEST_CASE("batch: a row stands when its files are as recorded, and a damaged row does not",
          "[pipeline][batch]") {
  const fs::path dir = fabmesh::testing::fresh_dir("batch/row_stands");
  fs::create_directories(dir / "cup");
  std::ofstream(dir / "cup" / "cup.stl", std::ios::binary) << "solid";
  const nlohmann::json file = {{"path", "cup/cup.stl"}, {"bytes", 5}, {"sha256", sha256_hex("solid")}};
  CHECK(row_stands(ok_row(nlohmann::json::array({file})), dir.string()));
  nlohmann::json longer = file;
  longer["bytes"] = 6;
  std::string why;
  CHECK_FALSE(row_stands(ok_row(nlohmann::json::array({longer})), dir.string(), &why));
  CHECK_THAT(why, Catch::Contains("has 5 bytes, not the 6 recorded"));
  CHECK(row_stands(R"({"status":"bad input"})", dir.string()));

  // Found by fuzz_ledger: a row that passed the ledger's check with files in
  // another form threw nlohmann's type_error out of the run (an internal
  // error), or converted 1e300 to a size (undefined behaviour).
  for (const nlohmann::json& files :
       {nlohmann::json::array({1}), nlohmann::json::array({{{"path", 1}}}),
        nlohmann::json::array({{{"path", "cup/cup.stl"}, {"bytes", 1e300}}}),
        nlohmann::json::array({{{"path", "cup/cup.stl"}, {"bytes", -5}}}),
        nlohmann::json::array({{{"sha256", nullptr}}}), nlohmann::json{{"a", file}}}) {
    INFO(files.dump());
    why.clear();
    CHECK_FALSE(row_stands(ok_row(files), dir.string(), &why));
    CHECK_THAT(why, Catch::Contains("does not write"));
  }
  for (const char* row : {"[1]", "5", R"({"status":5})", R"({"status":"ok","files":7})", "{"}) {
    INFO(row);
    CHECK_FALSE(row_stands(row, dir.string()));
  }
}

TEST_CASE("batch: a row naming a file outside the batch folder does not stand, and nothing is read there",
          "[pipeline][batch]") {
  const fs::path dir = fabmesh::testing::fresh_dir("batch/row_outside");
  fs::create_directories(dir / "out");
  // A file outside DIR whose size and digest the planted row records: were
  // it read, the row would stand and a rerun would trust it.
  std::ofstream(dir / "secret.txt", std::ios::binary) << "solid";
  for (const std::string& path :
       {(dir / "secret.txt").string(), std::string("../secret.txt"), std::string("cup/../../secret.txt"),
        std::string("./cup.stl"), std::string("")}) {
    INFO(path);
    const nlohmann::json file = {{"path", path}, {"bytes", 5}, {"sha256", sha256_hex("solid")}};
    std::string why;
    CHECK_FALSE(row_stands(ok_row(nlohmann::json::array({file})), (dir / "out").string(), &why));
    CHECK_THAT(why, Catch::Contains("outside the batch folder"));
  }
}

TEST_CASE(
    "batch: countertop variants of other thicknesses take the plane the first one kept, and the same files",
    "[pipeline][batch][plane_memo]") {
  const fs::path dir = fabmesh::testing::fresh_dir("batch/plane_memo");
  fs::copy_file(fabmesh::testing::example("countertop_cnc.yaml"), dir / "top.yaml");
  std::ofstream(dir / "m.yaml") << "design: top.yaml\nname: top_t{thickness}_{tolerance}\n"
                                   "grid:\n  thickness: [30, 34, 38]\n  tolerance: [0.05, 0.1]\n";
  const BatchManifest manifest = read_manifest((dir / "m.yaml").string());
  const BatchPlan plan = plan_batch(manifest);
  REQUIRE(plan.size() == 6);
  PlaneMemo memo;
  for (std::size_t i = 0; i < plan.size(); ++i) {
    INFO(plan.name(i));
    const BatchRow kept = run_variant(manifest, i, plan.variant(i), (dir / "kept").string(), &memo);
    const BatchRow fresh = run_variant(manifest, i, plan.variant(i), (dir / "fresh").string());
    REQUIRE(kept.status == VariantStatus::Ok);
    REQUIRE(fresh.status == VariantStatus::Ok);
    REQUIRE(kept.files.size() == fresh.files.size());
    CHECK(kept.files.size() >= 3);  // stl, dxf, nc, toolpath_svg
    for (std::size_t f = 0; f < kept.files.size(); ++f) {
      CHECK(kept.files[f].path == fresh.files[f].path);
      CHECK(kept.files[f].sha256 == fresh.files[f].sha256);
    }
  }
  // The grid's last key varies fastest: the tolerance. Each tolerance's
  // plane is built by its first thickness and taken by the other two.
  CHECK(memo.size() == 2);
  CHECK(memo.reused() == 4);
}
