#pragma once
// Units of length: designs say theirs, files record or imply theirs.

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/core/errors.h"

namespace fabmesh {

/// A unit of length a design (`units`, `export_units`) or the command line
/// (`--export-units`) may name.
struct LengthUnit {
  std::string_view name;  ///< as designs write it: "mm"
  double metres;          ///< metres per unit
  int dxf_insunits;       ///< the code of a DXF header's $INSUNITS
};

/// The units of length fabmesh knows, in the order messages list them.
inline constexpr std::array<LengthUnit, 4> kLengthUnits = {{
    {"mm", 1e-3, 4},
    {"cm", 1e-2, 5},
    {"m", 1.0, 6},
    {"in", 0.0254, 1},
}};

/// The names of kLengthUnits in order: the choices of a `units` field.
inline std::vector<std::string> length_unit_names() {
  std::vector<std::string> names;
  names.reserve(kLengthUnits.size());
  for (const LengthUnit& u : kLengthUnits) names.emplace_back(u.name);
  return names;
}

/// Throws the InputError of a unit fabmesh does not know.
[[noreturn]] inline void throw_unknown_length_unit(std::string_view units) {
  std::string known;
  for (const LengthUnit& u : kLengthUnits) known += (known.empty() ? "" : ", ") + std::string(u.name);
  throw InputError("units '" + std::string(units) + "' is not one of " + known);
}

/// The unit of kLengthUnits named `units`.
/// \throw InputError for any other name
constexpr const LengthUnit& length_unit(std::string_view units) {
  for (const LengthUnit& u : kLengthUnits) {
    if (u.name == units) return u;
  }
  throw_unknown_length_unit(units);
}

/// Metres per unit for the units fabmesh knows: mm, cm, m, in.
/// \throw InputError for any other unit
constexpr double metres_per_unit(std::string_view units) { return length_unit(units).metres; }

/// Millimetres per unit (mm 1, cm 10, m 1000, in 25.4). \throw InputError
inline double millimetres_per_unit(std::string_view units) { return 1e3 * metres_per_unit(units); }

}  // namespace fabmesh
