#pragma once
// Units of length: designs say theirs, files record or imply theirs.

#include <string_view>

#include "geometry/core/errors.h"

namespace fabmesh {

/// Metres per unit for the units fabmesh knows: mm, cm, m, in.
/// \throw InputError for any other unit
inline double metres_per_unit(std::string_view units) {
  if (units == "mm") return 1e-3;
  if (units == "cm") return 1e-2;
  if (units == "m") return 1.0;
  if (units == "in") return 0.0254;
  throw InputError("units '" + std::string(units) + "' is not one of mm, cm, m, in");
}

/// Millimetres per unit (mm 1, cm 10, m 1000, in 25.4). \throw InputError
inline double millimetres_per_unit(std::string_view units) { return 1e3 * metres_per_unit(units); }

}  // namespace fabmesh
