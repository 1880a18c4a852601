// A batch's memo of countertop planes: what it keeps and drops, and that a
// countertop built from a kept plane is the one built from scratch.

#include "pipeline/plane_memo.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "io/design/design_source.h"
#include "pipeline/job.h"
#include "pipeline/report.h"
#include "tests/pipeline/batch/batch_fixture.h"

using namespace fabmesh;
using namespace fabmesh::testing;
namespace fs = std::filesystem;

namespace {

// A plane of `points` outline points (only its size matters to the memo).
std::shared_ptr<const CountertopPlane> plane_of_size(std::size_t points) {
  auto plane = std::make_shared<CountertopPlane>();
  plane->region.outer.assign(points, Vec2(0.0, 0.0));
  return plane;
}

// The report of `result` written into `folder`, without its timings and with
// the folder's path as "OUT", as JSON text.
std::string report_without_timings(const Result& result, const fs::path& folder) {
  nlohmann::ordered_json j = to_json(result);
  j.erase("timings_ms");
  std::string text = j.dump();
  const std::string path = folder.string();
  for (std::size_t at = text.find(path); at != std::string::npos; at = text.find(path, at))
    text.replace(at, path.size(), "OUT");
  return text;
}

}  // namespace

TEST_CASE("plane memo: finds what it keeps, drops the least recently used beyond its bytes",
          "[pipeline][batch][plane_memo]") {
  const std::size_t one = plane_bytes(*plane_of_size(1000)) + 1;  // a plane and a one-letter key
  PlaneMemo memo(3 * one);
  CHECK(memo.find("a") == nullptr);
  memo.keep("a", plane_of_size(1000));
  memo.keep("b", plane_of_size(1000));
  memo.keep("c", plane_of_size(1000));
  CHECK(memo.size() == 3);
  REQUIRE(memo.find("a") != nullptr);  // now the most recently used: "b" is the least
  memo.keep("d", plane_of_size(1000));
  CHECK(memo.size() == 3);
  CHECK(memo.find("b") == nullptr);
  CHECK(memo.find("a") != nullptr);
  CHECK(memo.find("c") != nullptr);
  CHECK(memo.find("d") != nullptr);
  CHECK(memo.reused() == 4);

  // A key kept already keeps its first plane; a plane larger than the memo is not kept.
  const auto first = memo.find("d");
  memo.keep("d", plane_of_size(1000));
  CHECK(memo.find("d") == first);
  memo.keep("e", plane_of_size(4000));
  CHECK(memo.find("e") == nullptr);
  CHECK(memo.size() == 3);
  memo.keep("f", nullptr);
  CHECK(memo.find("f") == nullptr);
}

TEST_CASE("plane memo: found and kept from several threads at once", "[pipeline][batch][plane_memo]") {
  PlaneMemo memo;
  std::vector<std::shared_ptr<const CountertopPlane>> found(400);
  tbb::parallel_for(std::size_t{0}, found.size(), [&](std::size_t i) {
    const std::string key = "k" + std::to_string(i % 4);
    found[i] = memo.find(key);
    if (found[i] == nullptr) {
      memo.keep(key, plane_of_size(10 + i % 4));
      found[i] = memo.find(key);
    }
  });
  CHECK(memo.size() == 4);
  for (std::size_t i = 0; i < found.size(); ++i) {
    REQUIRE(found[i] != nullptr);
    CHECK(found[i]->region.outer.size() == 10 + i % 4);  // each key's plane, whoever kept it
  }
}

TEST_CASE(
    "plane memo: every bundled countertop and kitchen at three thicknesses is the same from a kept plane",
    "[pipeline][batch][plane_memo][countertop][kitchen]") {
  const fs::path dir = fresh_dir("plane_memo/examples");
  std::size_t designs = 0;
  for (const auto& entry : fs::directory_iterator(FABMESH_SOURCE_DIR "/configs/examples")) {
    const std::string file = entry.path().filename().string();
    if (entry.path().extension() != ".yaml" || file.rfind("batch_", 0) == 0) continue;
    INFO(file);
    const DesignSource source = DesignSource::read(entry.path().string());
    const Design as_given = source.resolve({});
    const auto* top = std::get_if<CountertopDesign>(&as_given.body);
    if (top == nullptr) continue;
    ++designs;
    const double thickness = top->thickness;
    PlaneMemo memo;
    for (int k = 0; k < 3; ++k) {
      const double t = thickness + 5.0 * k;
      INFO(t);
      const std::vector<Override> overrides{parse_override(fmt::format("thickness={}", t)),
                                            parse_override("name=top_" + std::to_string(k))};
      BlankedText blanked{plane_free_keys(), {}};
      const Design design = source.resolve(overrides, nullptr, &blanked);
      const fs::path fresh = dir / (file + std::to_string(k)) / "fresh";
      const fs::path reused = dir / (file + std::to_string(k)) / "reused";
      const Result a = run_job(design, into(fresh));
      JobOptions options = into(reused);
      options.reuse = {&memo, blanked.text};
      const Result b = run_job(design, options);
      CHECK(memo.reused() == static_cast<std::size_t>(k));  // the first builds the plane, the others take it
      CHECK(report_without_timings(a, fresh).size() > 100);
      CHECK(report_without_timings(a, fresh) == report_without_timings(b, reused));
      const auto files = output_tree(fresh);
      CHECK(!files.empty());
      CHECK(files == output_tree(reused));
    }
    // Another tolerance samples other loops: a plane of its own, not a kept one.
    const double tolerance = source.resolve({}).common.tolerance;
    BlankedText blanked{plane_free_keys(), {}};
    const Design coarser =
        source.resolve({parse_override(fmt::format("tolerance={}", 2 * tolerance))}, nullptr, &blanked);
    const fs::path fresh = dir / (file + "_coarser") / "fresh";
    const fs::path reused = dir / (file + "_coarser") / "reused";
    JobOptions options = into(reused);
    options.reuse = {&memo, blanked.text};
    // What the run gives: its report, or the error it refuses the design with.
    auto outcome = [&](const JobOptions& o, const fs::path& folder) {
      try {
        return report_without_timings(run_job(coarser, o), folder);
      } catch (const std::exception& e) {
        return std::string("refused: ") + e.what();
      }
    };
    const std::string b = outcome(options, reused);
    CHECK(memo.reused() == 2);
    CHECK(memo.size() == 2);
    CHECK(outcome(into(fresh), fresh) == b);
  }
  CHECK(designs >= 10);
}
