#pragma once
// The curves of a design, by name, for the commands that work on curves.

#include <string>
#include <vector>

#include "io/design/design.h"

namespace fabmesh {

struct NamedCurve {
  std::string name;  ///< "curve", "profile", "outline", "holes[0]", ...
  CurveSpec spec;
};

/// Every curve a design declares, in file order.
std::vector<NamedCurve> design_curves(const Design& design);

}  // namespace fabmesh
