// Every bundled example says how big it is in a machine-checkable comment
// (`# size: 2400 x 650 x 30 mm`), and is that big: its mesh's bounding box
// (a curve's sampled points) matches the comment within the design's
// tolerance on each face of the box.

#include <catch2/catch.hpp>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include "geometry/fairing/build_curve.h"
#include "geometry/mesh/bounding_box.h"
#include "geometry/sampling/sample_curve.h"
#include "io/design/read_design.h"
#include "io/file.h"
#include "pipeline/build_design.h"
#include "pipeline/design_curves.h"

using namespace fabmesh;
namespace fs = std::filesystem;

namespace {

struct StatedSize {
  std::vector<double> extents;  // 2 (a curve) or 3 numbers
  std::string units;
};

StatedSize stated_size(const std::string& text, const std::string& name) {
  static const std::regex size(R"(# size: ([0-9.]+) x ([0-9.]+)(?: x ([0-9.]+))? (mm|cm|m|in)\n)");
  std::smatch m;
  INFO(name);
  REQUIRE(std::regex_search(text, m, size));
  StatedSize s;
  for (int i = 1; i <= 3; ++i) {
    if (m[i].matched) s.extents.push_back(std::stod(m[i].str()));
  }
  s.units = m[4].str();
  return s;
}

// The extents of what the design builds: the mesh's bounding box, or a curve's sampled points.
std::vector<double> measured_size(const Design& design) {
  BoundingBox box;
  if (std::holds_alternative<CurveDesign>(design.body)) {
    for (const NamedCurve& nc : design_curves(design)) {
      SampleOptions so;
      so.tolerance = 0.5 * design.common.tolerance;
      for (const Vec2& p : sample_curve(build_curve(nc.spec).curve, so).points) {
        box.lo = box.lo.cwiseMin(Vec3(p.x(), p.y(), 0.0));
        box.hi = box.hi.cwiseMax(Vec3(p.x(), p.y(), 0.0));
      }
    }
    return {box.size().x(), box.size().y()};
  }
  StageTimings timings;
  StageTimer watch(timings);
  const BuildContext context{design.common, 0.9 * design.common.tolerance, false, watch};
  box = bounding_box(product(build_design(design, context))->mesh.vertices);
  return {box.size().x(), box.size().y(), box.size().z()};
}

}  // namespace

TEST_CASE("examples: every bundled design is as big as its size comment says", "[pipeline][examples]") {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(std::string(FABMESH_SOURCE_DIR) + "/configs/examples")) {
    // batch_*.yaml are batch manifests (docs/batch.md), not designs: their variants are checked by the batch
    // tests.
    const bool manifest = entry.path().filename().string().rfind("batch_", 0) == 0;
    if (entry.path().extension() == ".yaml" && !manifest) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  REQUIRE(files.size() >= 20);
  for (const fs::path& file : files) {
    const std::string name = file.filename().string();
    INFO(name);
    const StatedSize stated = stated_size(read_file(file.string()), name);
    const Design design = read_design(file.string());
    CHECK(stated.units == design.common.units);
    const std::vector<double> measured = measured_size(design);
    REQUIRE(measured.size() == stated.extents.size());
    for (std::size_t k = 0; k < measured.size(); ++k) {
      INFO("extent " << k << ": measured " << measured[k] << ", stated " << stated.extents[k]);
      // The mesh lies within the tolerance of the exact shape, so each of the two
      // faces of its box may lie that far inside the exact box's.
      CHECK(std::abs(measured[k] - stated.extents[k]) <= 2.0 * design.common.tolerance);
    }
  }
}
