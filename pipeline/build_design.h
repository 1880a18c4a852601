#pragma once
// The builders of the design kinds: design in, the parts of a Result out
// (pipeline/result.h), no I/O. A builder makes the design's meshes with the
// proofs of their construction, its curves, the exact geometry and programs
// of its kind, and the facts it reports; the job then validates the parts
// (pipeline/validate_parts.h).
// One overload of `build` per DesignBody alternative (build_vessel_design.cpp,
// build_countertop_design.cpp, build_surface_design.cpp, build_curve_design.cpp);
// build_design dispatches with std::visit and no fallback, so a kind
// without a builder does not compile.

#include <fmt/format.h>

#include <cstddef>
#include <limits>
#include <string>

#include "geometry/core/errors.h"
#include "geometry/core/stage_timer.h"
#include "io/design/design.h"
#include "pipeline/result.h"

namespace fabmesh {

struct PlaneReuse;  // pipeline/plane_memo.h

/// What every builder gets besides its design.
struct BuildContext {
  const DesignCommon& common;
  double tolerance = 0.0;      ///< the share of the design's tolerance the meshes may use
  bool wants_cutting = false;  ///< an output needs the drawing (cutting outline, profile template)
  StageTimer& watch;           ///< stage timings of the job
  /// Memory this process can use, bytes (process_memory_limit()); builders
  /// that know their arrays' size in advance refuse larger meshes with it.
  std::size_t memory_limit = std::numeric_limits<std::size_t>::max();
  bool wants_exact = false;  ///< an output writes the exact shape (step)
  bool wants_master =
      false;  ///< an output writes a vessel's casting master (master_stl, master_3mf, master_step)
  bool wants_cases = false;  ///< an output writes the mould parts' casting cases (case_stl, case_3mf)
  /// A batch's memo of countertop planes and this design's key in it; null:
  /// the plane is built and not kept.
  const PlaneReuse* reuse = nullptr;
};

/// The smaller of this machine's physical memory and the process's address
/// space limit (RLIMIT_AS), bytes.
std::size_t process_memory_limit();

/// Runs `build` (a stage given `share` of the design's `max_triangles`
/// budget), rethrowing its BudgetError in the design's numbers: "over the
/// SHARE a sheet may have of the budget of MAX_TRIANGLES (max_triangles: WHY)"
/// instead of "over the budget of SHARE", with `what` ("a sheet of the
/// shell") for "the mesh".
template <class Build>
auto within_share(std::size_t share, std::size_t max_triangles, const std::string& what,
                  const std::string& why, Build build) -> decltype(build());

/// The builders: each fills the build's part of a Result (purpose, parts,
/// curves, products, facts, max_deviation, tolerance_shares, warnings).
Result build(const CurveDesign& design, const BuildContext& context);
Result build(const VesselDesign& design, const BuildContext& context);
Result build(const CountertopDesign& design, const BuildContext& context);
Result build(const SurfaceDesign& design, const BuildContext& context);

/// A draft of a surface design to show at once (the studio's): the sheet
/// refined within `tolerance` for the surface alone (not for the shell's
/// offset sheets, whose bound crowds the grid toward singular corners) and
/// thickened as `build` does; neither proven nor validated. Its
/// max_deviation is the sheet's; its products the patch network.
/// \throw InputError (patches), GeometryError, BudgetError
Result surface_draft(const SurfaceDesign& design, double tolerance);

/// Builds `design` with the builder of its kind (its parts not validated yet).
/// \throw InputError (bad design), anything the builder throws
Result build_design(const Design& design, const BuildContext& context);

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
