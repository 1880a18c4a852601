#pragma once
// The router's whole job for a countertop: the tool-centre path around every
// hole and then the outline, in depth passes, with lead-ins and holding
// tabs, as a list of 3D moves. Coordinates: the design's x, y; z = 0 on the
// slab's top face, negative into the material.

#include <cstddef>
#include <limits>
#include <vector>

#include "geometry/core/tolerance_budget.h"
#include "geometry/section/region.h"
#include "geometry/toolpath/cnc_options.h"
#include "geometry/toolpath/drilling.h"
#include "geometry/toolpath/loop_path.h"
#include "geometry/toolpath/manufacturability.h"
#include "geometry/toolpath/profiling.h"

namespace fabmesh {

enum class MoveKind {
  Rapid,    ///< G0 at safe height
  Plunge,   ///< straight down at the plunge feed (in the waste, at the lead's start)
  LeadIn,   ///< the lead arc onto the loop, at the cutting feed
  Ramp,     ///< down along the loop's path at the ramp angle (EntryKind::Ramp), at the cutting feed
  Helix,    ///< down round the helix circle in the waste (EntryKind::Helix), at the cutting feed
  Cut,      ///< along the loop at the cutting feed
  LeadOut,  ///< the lead arc run backwards off the loop
  TabUp,    ///< straight up onto a tab (plunge feed)
  TabDown,  ///< straight down after a tab (plunge feed)
  Retract,  ///< G0 up to safe height
};

const char* to_string(MoveKind kind);

/// One move from the previous position to `to`. Arcs (shape Arc) turn about
/// `center` by `sweep` radians (positive: counter-clockwise seen from above,
/// G3); their start is the previous position. An arc's z goes from the
/// previous position's to to.z() in proportion to the turn (a helix); only
/// ramps and helix entries change z along an arc. A helix move may turn a
/// whole circle (sweep +-2 pi, ending where it starts).
struct ToolMove {
  MoveKind kind = MoveKind::Rapid;
  PieceKind shape = PieceKind::Line;
  Vec3 to{0.0, 0.0, 0.0};
  Vec2 center{0.0, 0.0};
  double sweep = 0.0;
  PieceRole role = PieceRole::Offset;  ///< Cut moves: what the piece is (offset, corner, dog-bone)
  std::size_t loop = 0;                ///< index into Toolpath::loops
  bool finishing = false;              ///< part of the finishing pass (options.finish > 0)
};

struct Toolpath {
  CncOptions options;
  ManufacturabilityReport checks;
  std::vector<LoopPath> loops;  ///< cutting order: the holes as given, then the outline
  /// With options.finish > 0: each loop's roughing path (tool radius +
  /// finish from the part, its tabs over the finishing path's), same order;
  /// `loops` are then the finishing paths. Empty without finishing.
  std::vector<LoopPath> roughing;
  std::vector<ToolMove> moves;  ///< the first is a Rapid at safe_z; the program starts by rising to safe_z
  std::vector<double> pass_z;   ///< z of each depth pass, descending to -(depth + breakthrough)
  double tab_z = 0.0;           ///< z over the outline's tabs: -(depth - tabs.height)
  /// Tabs that asked for more room than their loop has (placed where they
  /// fit; the rest left out), one line per loop, for the report.
  std::vector<std::string> warnings;
  /// Proven bound: the tool-centre path (chords of chains, exact lines and
  /// arcs) vs the exact offset of the exact curves, model units.
  double deviation = 0.0;
  /// Proven lower bound of the distance between the tool-centre path
  /// (dog-bones excepted) and the exact part boundary: the tool cuts into the
  /// part by at most tool radius - clearance (<= options.tolerance).
  double clearance = 0.0;
  /// Arc fitting (options.arc_fit), over every path cut (roughing ones
  /// too): pieces replaced, the arcs and lines fitted in their place, and the
  /// largest proven distance between a fit and what it replaced.
  std::size_t fit_replaced = 0, fit_arcs = 0, fit_lines = 0;
  double fit_deviation = 0.0;
  /// The share of options.tolerance the program's number rounding may use (encode_gcode).
  double rounding_allowance = 0.0;
  /// How options.tolerance was divided (see plan_toolpath).
  std::vector<ToleranceShare> tolerance_shares;
  /// Tap holes drilled before any routing, in the order drilled
  /// (drilling_order); their loops are not among `loops`.
  std::vector<DrillHole> drills;
  /// An edge profile's passes after the routing (profile_runs), with the
  /// profile bit; no runs: none.
  ProfilePasses profiling;
};

/// A program's moves by how the machine runs them: lengths (model units) and
/// the time they take at their rates, without acceleration (so a lower bound).
struct ToolpathTotals {
  double cutting = 0.0;   ///< lead-ins, ramps, cuts and lead-outs, at the cutting feed
  double plunging = 0.0;  ///< plunges and moves onto and off tabs, at the plunge feed
  double rapid = 0.0;     ///< rapids and retracts (the drill cycles' too), at options.rapid
  double drilling = 0.0;  ///< the drill cycles' feeds down, at drill_feed(options)
  /// cutting / feed + plunging / plunge + rapid / rapid (+ drilling / drill feed)
  double minutes = 0.0;
};

/// The totals of `path`: arcs by their exact length, from the first move's
/// end; the drill cycles by drilling_totals (and the rapid from the last
/// hole to the first move's end).
ToolpathTotals toolpath_totals(const Toolpath& path);

/// Plans the cut of the region bounded by `outline` and `holes` (as
/// build_region takes them: closed, simple, holes inside and disjoint).
/// Order of work: options (RangeError naming the field), the region
/// (build_region's GeometryError), check_manufacturability (GeometryError
/// naming loop, segment, point, radius or gap), the loop paths, their
/// clearance from the part (GeometryError where the tool cannot pass, e.g.
/// a notch narrower than the tool), tabs on the outline (options.tabs) and on
/// each hole (options.hole_tabs), placed where they fit (place_tabs; those
/// that do not are left out with a line in `warnings`). With ramp entry each
/// pass starts at the previous pass's depth (the slab's top for the first),
/// ramps down along the path forward over half the ramp length and back to
/// the start, then cuts the loop at its depth: the ramp's floor is taken down
/// gradually, never by a plunge of the tool's tip. With options.finish,
/// every pass of a loop runs on its roughing path, then one finishing pass
/// at full depth runs on `loops`, entering from the roughed slot along a
/// tangent arc of radius finish. With helix entry each pass goes down (in
/// the waste, at the lead's start) to the previous pass's floor, descends
/// round LoopPath::helix at the ramp angle to its depth, turns once more
/// there, then runs the lead-in; the helix's radius is options.helix_radius,
/// or else the first of r/2, r/4, r/8 whose circle keeps the tool clear of
/// the part (as the lead's: GeometryError naming the loop and the clear
/// radius it needs when none does). The lead arc has radius 2 lead_in / pi (a quarter
/// circle of length lead_in); where it would cut into the part it is halved,
/// twice, then left out (the plunge then lands on the path).
/// Tolerance budget (cnc.tolerance = t): chords of chains t/2 (with
/// arc_fit, "tool path chords and fitted arcs" t/2: chords within t/4, the
/// arcs fitted to them and to digitised stretches within what a loop's
/// chords left of t/2, arc_fit.h), boundary
/// samples for the checks t/10, arcs as chords in the clearance check t/20,
/// the material shallow concave corners keep t/4 (shallow_corner_depth), the
/// G-code's rounding t/20 (Toolpath::rounding_allowance).
/// \throw RangeError, GeometryError, BudgetError
Toolpath plan_toolpath(const CompositeCurve& outline, const std::vector<RegionHole>& holes,
                       const CncOptions& options);

}  // namespace fabmesh
