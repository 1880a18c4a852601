// The user reference's examples are real: every YAML block in docs/ is a
// design fabmesh reads and, when its kind has a mesh, builds and validates.

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/design/read_design.h"
#include "pipeline/job.h"
#include "pipeline/output_table.h"

using namespace fabmesh;
namespace fs = std::filesystem;

namespace {

struct Block {
  std::string file;
  int line = 0;
  std::string text;
};

std::vector<Block> yaml_blocks() {
  std::vector<Block> blocks;
  for (const auto& entry : fs::directory_iterator(fs::path(FABMESH_SOURCE_DIR) / "docs")) {
    if (entry.path().extension() != ".md") continue;
    std::ifstream in(entry.path());
    std::string line;
    int number = 0;
    Block* open = nullptr;
    while (std::getline(in, line)) {
      ++number;
      if (open == nullptr && line == "```yaml") {
        blocks.push_back({entry.path().filename().string(), number, ""});
        open = &blocks.back();
      } else if (open != nullptr && line == "```") {
        open = nullptr;
      } else if (open != nullptr) {
        open->text += line + "\n";
      }
    }
  }
  return blocks;
}

}  // namespace

TEST_CASE("docs: every YAML example of the reference is a design that reads and builds", "[docs]") {
  const std::vector<Block> blocks = yaml_blocks();
  CHECK(blocks.size() >= 8);
  for (const Block& b : blocks) {
    INFO(b.file << ":" << b.line);
    const Design design = parse_design(b.text, b.file);
    CHECK_NOTHROW(resolve_outputs(design));
    if (std::holds_alternative<CurveDesign>(design.body)) continue;
    const Result result = prepare_job(design, {}).first;
    REQUIRE(product(result) != nullptr);
    CHECK(product(result)->validation.valid());
    CHECK(result.max_deviation <= design.common.tolerance);
  }
}
