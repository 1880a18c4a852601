// libFuzzer entry for the design reader: FABMESH_FUZZ_DESIGN_YAML reads the
// input as a design file (YAML) with `-D` overrides after NUL bytes,
// otherwise as a points CSV.
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
#include <vector>

#include "geometry/core/errors.h"
#include "io/design/number_limits.h"
#include "io/design/overrides.h"
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
  // The design is the text up to the first NUL byte; each further
  // NUL-separated piece is a `-D path=value` override applied to it.
  std::vector<fabmesh::Override> overrides;
  std::size_t end = text.find('\0');
  const std::string design_text = text.substr(0, end);
  try {
    while (end != std::string::npos) {
      const std::size_t next = text.find('\0', end + 1);
      overrides.push_back(fabmesh::parse_override(text.substr(end + 1, next - end - 1)));
      end = next;
    }
  } catch (const fabmesh::InputError&) {
    return 0;  // not path=value (the CLI reports it as bad input)
  }
  // A path in a folder that does not exist: a `polyline: {file: ...}` the
  // fuzzer writes is a missing file (FileError), never a real file or device
  // read by accident (an absolute path is read, and must be refused cleanly).
  try {
    const fabmesh::Design design =
        fabmesh::parse_design(design_text, "/nonexistent-fuzz-dir/design.yaml", overrides);
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
