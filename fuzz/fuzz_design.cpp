// libFuzzer entry for the design reader: FABMESH_FUZZ_DESIGN_YAML reads the
// input as a design file (YAML), otherwise as a points CSV.
// parse_design and parse_points_csv may only return or throw FileError (bad
// input, located); anything else (a crash, another exception, a sanitizer
// report, a hang caught by -timeout, memory beyond -rss_limit_mb) is a
// finding. What they return must hold only finite numbers within the
// documented magnitude (io/design/number_limits.h).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <variant>

#include "geometry/core/errors.h"
#include "io/design/number_limits.h"
#include "io/design/points_csv.h"
#include "io/design/read_design.h"

namespace {

void require_bounded(double v) {
  if (!std::isfinite(v) || std::abs(v) > fabmesh::kMaxDesignNumber) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
#ifdef FABMESH_FUZZ_DESIGN_YAML
  // A path in a folder that does not exist: a `polyline: {file: ...}` the
  // fuzzer writes is a missing file (FileError), never a real file or device
  // read by accident (an absolute path is read, and must be refused cleanly).
  try {
    const fabmesh::Design design = fabmesh::parse_design(text, "/nonexistent-fuzz-dir/design.yaml");
    require_bounded(design.common.tolerance);
    if (!(design.common.tolerance >= fabmesh::kMinDesignTolerance)) __builtin_trap();
  } catch (const fabmesh::FileError&) {
    return 0;  // rejected cleanly
  }
#else
  try {
    for (const fabmesh::Vec2& p : fabmesh::parse_points_csv(text, "points.csv")) {
      require_bounded(p.x());
      require_bounded(p.y());
    }
  } catch (const fabmesh::FileError&) {
    return 0;
  }
#endif
  return 0;
}
