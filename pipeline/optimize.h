#pragma once
// The fairest shape parameters of a design's curves (`fabmesh optimize`, the
// library's optimize): each curve faired for its family's energy.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "geometry/fairing/build_curve.h"
#include "io/design/design.h"

namespace fabmesh {

/// One curve of a design with its fairest parameters.
struct OptimizedCurve {
  std::string name;             ///< its design key: "curve", "profile", "holes[0]"
  nlohmann::ordered_json json;  ///< family, the fairest parameters and energies, joints (docs/reports.md)
  BuiltCurve built;             ///< the curve with those parameters
};

/// Optimizes every curve of `design`, in the design's order.
/// \throw InputError placed in the design: a kind without curves, an
///        H-Bézier curve (optimize is defined for tbezier and quasi_bspline)
std::vector<OptimizedCurve> optimize_design(const Design& design);

/// The `optimize --json` document: one item per curve, {design, curve, ...}.
nlohmann::ordered_json optimize_items(const std::string& design_file,
                                      const std::vector<OptimizedCurve>& curves);

}  // namespace fabmesh
