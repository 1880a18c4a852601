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

}  // namespace fabmesh::testing
