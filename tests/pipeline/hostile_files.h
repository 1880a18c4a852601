#pragma once
// Small hostile mesh files of issue 24, made here rather than committed by
// hand: the tests write them, and the fuzzers' seeds of the same names must
// equal them (tests/data/fuzz-seeds/*/regression-*).

#include <cstdint>
#include <string>

#include "io/mesh/threemf.h"

namespace fabmesh::testing {

/// A 3MF model part: an empty mesh, then 10 levels of objects each made of
/// 20 components of the level below; the build places the top one. Expanded
/// naively that is 20^10 (about 10^13) component visits.
inline std::string nested_components_model() {
  std::string xml =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<model unit=\"millimeter\" xml:lang=\"en-US\" "
      "xmlns=\"http://schemas.microsoft.com/3dmanufacturing/core/2015/02\">\n"
      "<resources>\n<object id=\"1\" type=\"model\"><mesh><vertices/><triangles/></mesh></object>\n";
  for (int level = 2; level <= 11; ++level) {
    xml += "<object id=\"" + std::to_string(level) + "\" type=\"model\"><components>";
    for (int k = 0; k < 20; ++k) xml += "<component objectid=\"" + std::to_string(level - 1) + "\"/>";
    xml += "</components></object>\n";
  }
  xml += "</resources>\n<build><item objectid=\"11\"/></build>\n</model>\n";
  return xml;
}

/// A glTF document whose one triangle list takes its POSITION from an
/// accessor of 60 million VEC3 floats with no bufferView (all zeros, and no
/// byte of the file behind them).
inline std::string unbacked_positions_gltf() {
  return "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
         "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},"
         "\"mode\":4}]}],\"accessors\":[{\"componentType\":5126,\"count\":60000000,\"type\":\"VEC3\"}]}\n";
}

/// `json` as a binary glTF (GLB): the header and one JSON chunk, padded with spaces.
inline std::string glb_of(std::string json) {
  while (json.size() % 4 != 0) json += ' ';
  const auto u32 = [](std::uint32_t v) {
    std::string bytes(4, '\0');
    for (int i = 0; i < 4; ++i) bytes[static_cast<std::size_t>(i)] = static_cast<char>((v >> (8 * i)) & 0xFF);
    return bytes;
  };
  const auto length = static_cast<std::uint32_t>(12 + 8 + json.size());
  return "glTF" + u32(2) + u32(length) + u32(static_cast<std::uint32_t>(json.size())) + u32(0x4E4F534A) +
         json;
}

}  // namespace fabmesh::testing
