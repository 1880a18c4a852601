#pragma once
// Design files as plain, validated data (product.md "Design files").

#include <string>
#include <variant>
#include <vector>

#include "geometry/curves/curve_spec.h"

namespace fabmesh {

/// Keys every design has.
struct DesignCommon {
  std::string path;                  ///< the file it was read from
  std::string name;                  ///< default: the file's stem
  std::string kind;                  ///< curve | vessel | countertop | surface
  std::string units = "mm";
  double tolerance = 0.01;           ///< model units, > 0
  std::vector<std::string> outputs;  ///< default: stl, drc
};

/// kind: curve
struct CurveDesign {
  CurveSpec curve;
};

using DesignBody = std::variant<CurveDesign>;

struct Design {
  DesignCommon common;
  DesignBody body;
};

}  // namespace fabmesh
