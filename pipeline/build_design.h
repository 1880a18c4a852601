#pragma once
// The builders of the design kinds: design in, validated mesh out, no I/O.
// Each mesh builder validates its mesh with validate_built (validate_built.h)
// as soon as it is made, with the proofs of its construction.
// One overload of `build` per DesignBody alternative (build_vessel_design.cpp,
// build_countertop_design.cpp, build_surface_design.cpp, build_curve_design.cpp);
// build_design dispatches with std::visit and no fallback, so a kind
// without a builder does not compile.

#include <fmt/format.h>

#include <cstddef>
#include <string>

#include "geometry/core/errors.h"
#include "pipeline/built_mesh.h"
#include "pipeline/validate_built.h"

namespace fabmesh {

/// Runs `build` (a stage given `share` of the design's `max_triangles`
/// budget), rethrowing its BudgetError in the design's numbers: "over the
/// SHARE a sheet may have of the budget of MAX_TRIANGLES (max_triangles: WHY)"
/// instead of "over the budget of SHARE", with `what` ("a sheet of the
/// shell") for "the mesh".
template <class Build>
auto within_share(std::size_t share, std::size_t max_triangles, const std::string& what,
                  const std::string& why, Build build) -> decltype(build());

BuiltMesh build(const CurveDesign& design, const BuildContext& context);
BuiltMesh build(const VesselDesign& design, const BuildContext& context);
BuiltMesh build(const CountertopDesign& design, const BuildContext& context);
BuiltMesh build(const SurfaceDesign& design, const BuildContext& context);

/// A draft of a surface design to show at once (the studio's): the sheet
/// refined within `tolerance` for the surface alone (not for the shell's
/// offset sheets, whose bound crowds the grid toward singular corners) and
/// thickened as `build` does; neither proven nor validated. Its
/// max_deviation is the sheet's; its shape the patch network.
/// 	hrow InputError (patches), GeometryError, BudgetError
BuiltMesh surface_draft(const SurfaceDesign& design, double tolerance);

/// Builds and validates `design` with the builder of its kind.
/// \throw InputError (bad design), anything the builder throws
BuiltMesh build_design(const Design& design, const BuildContext& context);

template <class Build>
auto within_share(std::size_t share, std::size_t max_triangles, const std::string& what,
                  const std::string& why, Build build) -> decltype(build()) {
  try {
    return build();
  } catch (const BudgetError& e) {
    std::string message = e.what();
    const std::string budget = fmt::format("over the budget of {}", share);
    if (const std::size_t at = message.find(budget); at != std::string::npos) {
      message.replace(at, budget.size(),
                      fmt::format("over the {} {} may have of the budget of {} (max_triangles: {})", share,
                                  what, max_triangles, why));
    }
    if (const std::size_t at = message.find("the mesh needs"); at != std::string::npos)
      message.replace(at, 8, what);
    throw BudgetError(e.requested(), static_cast<double>(max_triangles), message, e.location());
  }
}

}  // namespace fabmesh
