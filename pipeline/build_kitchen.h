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

/// The edge kinds of the top's outer loop: walls where a kitchen's outline
/// marks its segments (`edge: wall`, a DXF template's WALLS layer), exposed
/// elsewhere.
std::vector<EdgeKind> top_edge_kinds(const CountertopDesign& design, const Region2& region,
                                     const CompositeCurve& outline);

/// A top's or a piece's mesh with its exposed edges profiled as
/// design.edges says (build_profiled_slab within what the plan's
/// `deviation` from its exact curves leaves of the build's tolerance), and the
/// profile's facts under `edges` in `out` (kind, radius, rings, the chords'
/// sagitta). Validated in full like any mesh without a construction proof.
/// \throw GeometryError at `edges.radius` (the profile does not fit), BudgetError
TriangleSoup profiled_mesh(const CountertopDesign& design, const ProfiledPlan& plan, double thickness,
                           double deviation, const BuildContext& context, Result& out);

/// The profiling passes' bit and depth for design.edges (no runs yet):
/// cnc.tools' profile bit, else one of the end mill's diameter numbered
/// after every other tool; its tip at the top round's (bevel's) height.
/// `warnings` gets a line when the profile has a bottom round (not cut
/// from above).
/// \throw GeometryError at `edges.radius` (the tip would cut the holding
///        tabs) or `slab.spacing` (> 0: the bit would reach the next piece)
ProfilePasses profile_passes(const CountertopDesign& design, const CncOptions& cnc, double spacing,
                             double deviation, std::vector<std::string>& warnings);

/// Adds the pieces to `out.parts` (after the whole top, which stays the
/// product), their facts under `kitchen`, and returns the layout.
/// \throw GeometryError at `seams`, `seams[i]` or `slab` (a piece that fits
///        no slab, a seam through a cut-out), RangeError, BudgetError
KitchenProducts build_kitchen(const CountertopDesign& design, const Region2& region,
                              const CompositeCurve& outline, const std::vector<RegionHole>& holes,
                              const BuildContext& context, Result& out);

}  // namespace fabmesh
