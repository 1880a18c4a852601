#pragma once
// A kitchen (a countertop with a `slab`): the top cut at its seams into
// pieces, each a proven slab mesh of its own (parts of role Piece), nested
// on slabs and verified exactly, and with `cnc` one router program per slab.

#include "geometry/section/region.h"
#include "io/design/design.h"
#include "pipeline/build_design.h"
#include "pipeline/result.h"

namespace fabmesh {

/// The tools a router program uses, for the report: the router bit, then
/// each drill (`number`, `type`, `diameter`).
std::vector<Facts> tool_facts(const Toolpath& program);

/// Adds the pieces to `out.parts` (after the whole top, which stays the
/// product), their facts under `kitchen`, and returns the layout.
/// \throw GeometryError at `seams`, `seams[i]` or `slab` (a piece that fits
///        no slab, a seam through a cut-out), RangeError, BudgetError
KitchenProducts build_kitchen(const CountertopDesign& design, const Region2& region,
                              const CompositeCurve& outline, const std::vector<RegionHole>& holes,
                              const BuildContext& context, Result& out);

}  // namespace fabmesh
