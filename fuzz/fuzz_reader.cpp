// libFuzzer entry for one mesh reader, chosen by FABMESH_FUZZ_PARSE
// (parse_stl, parse_obj, parse_ply, parse_off or parse_draco).
// A reader may only return a soup whose indices are in range, or throw
// FileError; anything else (a crash, another exception, a sanitizer report,
// a hang caught by -timeout) is a finding. Small soups also go through weld
// and validate, which must accept whatever a reader returns.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "geometry/core/errors.h"
#include "geometry/mesh/validate.h"
#include "geometry/mesh/weld.h"
#include "io/mesh/draco.h"
#include "io/mesh/obj.h"
#include "io/mesh/off.h"
#include "io/mesh/ply.h"
#include "io/mesh/stl.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  fabmesh::TriangleSoup soup;
  try {
    soup = fabmesh::FABMESH_FUZZ_PARSE(bytes, "fuzz-input");
  } catch (const fabmesh::FileError&) {
    return 0;  // rejected cleanly
  }
  for (const auto& t : soup.triangles) {
    for (const std::uint32_t i : t) {
      if (i >= soup.vertices.size()) __builtin_trap();
    }
  }
  for (const auto& p : soup.vertices) {
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z())) __builtin_trap();
  }
  if (soup.triangles.size() <= 2000) {
    const fabmesh::WeldResult welded = fabmesh::weld(soup);
    const fabmesh::ValidationReport report = fabmesh::validate(welded.soup);
    if (report.triangles != soup.triangles.size()) __builtin_trap();
  }
  return 0;
}
