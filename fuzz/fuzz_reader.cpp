// libFuzzer entry for one mesh reader, chosen by FABMESH_FUZZ_PARSE
// (parse_stl, parse_obj, parse_ply, parse_off, fuzz::parse_draco,
// fuzz::parse_3mf or fuzz::parse_gltf).
// A reader may only return a soup whose indices are in range, or throw
// FileError; anything else (a crash, another exception, a sanitizer report,
// a hang caught by -timeout) is a finding. Small soups also go through weld
// and validate, which must accept whatever a reader returns.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "geometry/core/errors.h"
#include "geometry/mesh/weld.h"
#include "geometry/validation/validate.h"
#include "io/mesh/draco.h"
#include "io/mesh/gltf.h"
#include "io/mesh/obj.h"
#include "io/mesh/off.h"
#include "io/mesh/ply.h"
#include "io/mesh/stl.h"
#include "io/mesh/threemf.h"

namespace fabmesh::fuzz {

// The container formats instance meshes (components, nodes): a smaller
// budget than the default keeps each input's work and memory small.
constexpr std::size_t kMaxTriangles = 200000;

/// A zip archive ("PK") is read as it is; anything else is taken as the 3D
/// model part of a package made for it, so that mutations reach lib3mf's
/// XML reading instead of failing the zip's CRC checks.
TriangleSoup parse_3mf(std::string_view bytes, const std::string& name) {
  ThreeMfReadOptions options;
  options.max_triangles = kMaxTriangles;
  if (bytes.substr(0, 2) == "PK") return merged_soup(fabmesh::parse_3mf(bytes, name, options));
  return merged_soup(fabmesh::parse_3mf(threemf_package(bytes), name, options));
}

TriangleSoup parse_draco(std::string_view bytes, const std::string& name) {
  return fabmesh::parse_draco(bytes, name, kMaxTriangles);
}

TriangleSoup parse_gltf(std::string_view bytes, const std::string& name) {
  GltfReadOptions options;
  options.max_triangles = kMaxTriangles;
  return fabmesh::parse_gltf(bytes, name, options).soup;
}

}  // namespace fabmesh::fuzz

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
