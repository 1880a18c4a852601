// Every bundled manifest (configs/examples/batch_*.yaml, documented in docs/batch.md) runs.

#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <string>
#include <vector>

#include "geometry/mesh/weld.h"
#include "geometry/validation/validate.h"
#include "io/mesh/read_mesh.h"
#include "tests/pipeline/batch/batch_fixture.h"

using namespace fabmesh;
using namespace fabmesh::testing;
namespace fs = std::filesystem;

TEST_CASE("batch: every configs/examples/batch_*.yaml manifest builds every variant valid",
          "[pipeline][batch][docs]") {
  std::vector<fs::path> manifests;
  for (const auto& e : fs::directory_iterator(fs::path(FABMESH_SOURCE_DIR) / "configs" / "examples")) {
    const std::string name = e.path().filename().string();
    if (name.rfind("batch_", 0) == 0 && e.path().extension() == ".yaml") manifests.push_back(e.path());
  }
  std::sort(manifests.begin(), manifests.end());
  REQUIRE(manifests.size() >= 2);
  for (const fs::path& manifest : manifests) {
    INFO(manifest);
    const fs::path out = fresh_dir("batch/examples/" + manifest.stem().string());
    int code = -1;
    const nlohmann::json report = batch_json({manifest.string(), "-o", out.string()}, &code);
    CHECK(code == 0);
    CHECK(report["variants"].get<int>() >= 5);
    CHECK(report["ok"] == report["variants"]);
    const std::vector<nlohmann::json> rows = summary_rows(out);
    CHECK(rows.size() == report["variants"].get<std::size_t>());
    for (const nlohmann::json& row : rows) {
      INFO(row["name"]);
      CHECK(row["valid"] == true);
      for (const nlohmann::json& f : row["files"]) {
        const fs::path path = out / f["path"].get<std::string>();
        REQUIRE(fs::is_regular_file(path));
        CHECK(fs::file_size(path) == f["bytes"].get<std::uintmax_t>());
        if (f["format"] == "stl") {
          // Read back and welded exactly, the written mesh is valid with the summary's triangles.
          const TriangleSoup soup = read_mesh(path.string());
          CHECK(soup.triangles.size() == row["triangles"].get<std::size_t>());
          CHECK(validate(weld(soup, WeldOptions{0.0}).soup).valid());  // STL repeats shared vertices
        }
      }
    }
  }
}
