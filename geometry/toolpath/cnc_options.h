#pragma once
// What a CNC router cut of a countertop needs to know: the tool, the depths,
// the feeds, the lead-in, the holding tabs and how concave corners are
// treated. All lengths in model units (the design's), feeds in model units
// per minute.

#include <cstddef>
#include <optional>
#include <vector>

namespace fabmesh {

/// Travel direction around each loop, for a spindle turning clockwise seen
/// from above (M3). Climb: the part stays on the tool's right (the outline
/// runs clockwise, holes counter-clockwise); conventional: the part stays on
/// its left (outline counter-clockwise, holes clockwise).
enum class CutDirection { Climb, Conventional };

/// What happens at a concave corner (a G0 joint the tool cannot reach).
/// None: such a corner is refused (GeometryError). Dogbone: the tool runs
/// into the corner along the bisector until its disc touches the corner
/// point and back, so the part's sharp corner is reached (the part loses a
/// circular notch of the tool radius there).
enum class CornerRelief { None, Dogbone };

/// How the tool goes down into the material at the start of each pass.
/// Plunge: straight down at the plunge feed, at the lead's start in the
/// waste. Ramp: down along the loop's own path at `ramp_angle_deg` from the
/// horizontal, at the cutting feed (the bit's side does the work, not its
/// tip), and at the end of the pass on along the ramp's stretch again at the
/// full depth of the pass. Helix: down on a helix in the waste before the
/// lead-in, round a circle of `helix_radius` that ends tangent to the lead
/// (or to the path without one), at the ramp angle as its pitch angle, then
/// once round flat at the pass's depth to clear the bore's floor.
enum class EntryKind { Plunge, Ramp, Helix };

const char* to_string(CutDirection d);
const char* to_string(CornerRelief r);
const char* to_string(EntryKind e);

/// Holding tabs on the outline: bridges of material left at the bottom of
/// the cut so the part does not move when it comes free.
struct TabOptions {
  std::size_t count = 4;  ///< tabs on the outline (0: none)
  /// Width of the bridge, measured along the tool-centre path: the tool rises
  /// over width + tool diameter of its path (its disc still cuts a radius
  /// before and after). > 0.
  double width = 10.0;
  double height = 3.0;  ///< the bridge's height above the bottom of the slab; in (0, depth)
  /// Tabs sit where the tool-centre path's radius of curvature is at least
  /// this (straight or gently curved stretches), > 0; unset: 20 tool
  /// diameters, or a loop's largest where it has no stretch that flat.
  std::optional<double> min_radius;
};

/// What a tool of the machine's table is: the router bit, a drill, or the
/// profile bit of an edge profile (its `diameter` the smallest cutting
/// diameter, at its tip).
enum class ToolType { EndMill, Drill, Profile };

const char* to_string(ToolType t);  ///< "end_mill" | "drill" | "profile"

/// One tool of the machine's tool table (key `cnc.tools`), selected in the
/// program by `M6 T<number>`.
struct CncTool {
  int number = 1;  ///< in [1, 999], unique in the table
  ToolType type = ToolType::EndMill;
  double diameter = 12.0;  ///< > 0; the end mill's is tool_diameter
};

/// How the drill holes (tap holes) are drilled (key `cnc.drill`): one canned
/// cycle block per hole, from the retract plane R down to
/// -(depth + breakthrough), then back to safe height (G98: the level the
/// cycle started from).
struct DrillCycle {
  double peck = 0.0;  ///< > 0: G83, pecks of this depth (Q) from R; 0: G81, one feed down
  std::optional<double>
      retract;  ///< R, the height above the top the feed starts from, in (0, safe_z]; unset: safe_z
  std::optional<double> feed;     ///< feed down, model units per minute, > 0; unset: the plunge feed
  std::optional<double> spindle;  ///< spindle speed while drilling, rpm, > 0; unset: `spindle`
};

/// Tab options that ask for no tabs (count 0), the rest at their defaults.
inline TabOptions no_tabs() {
  TabOptions t;
  t.count = 0;
  return t;
}

/// The cut. Defaults are a 12 mm straight router bit through a 30 mm slab.
struct CncOptions {
  double tool_diameter = 12.0;  ///< > 0
  double depth = 30.0;          ///< depth of cut, > 0: the slab thickness (the caller's default)
  double breakthrough = 0.0;    ///< extra depth below the slab (into the spoilboard), >= 0
  double step_down = 10.0;      ///< largest depth of one pass, > 0
  double feed = 3000.0;         ///< cutting feed, model units per minute, > 0
  double plunge = 600.0;        ///< plunge feed (vertical moves in material), > 0
  /// The machine's rapid (G0) rate, for the time estimate only, > 0.
  double rapid = 10000.0;
  double spindle = 18000.0;  ///< spindle speed, revolutions per minute, > 0
  double safe_z = 10.0;      ///< height of rapid moves above the slab's top (z = 0), > 0
  double lead_in = 8.0;      ///< length of the arc lead onto each loop from the waste side, >= 0
  TabOptions tabs;           ///< on the outline
  /// Tabs on each hole (cut-outs), in the order of plan_toolpath's holes, so
  /// the slug stays put until it is cut free by hand; a hole beyond the list,
  /// or with count 0, gets none.
  std::vector<TabOptions> hole_tabs;
  EntryKind entry = EntryKind::Plunge;
  /// Ramp entry: the ramp's angle from the horizontal, degrees, in (0, 45].
  /// A pass of step s ramps over s / tan(angle) of the path; where the loop
  /// is shorter, the ramp winds round it again (a helix on a circle).
  double ramp_angle_deg = 3.0;
  /// Helix entry: the radius of the tool centre's circle, in (0, tool
  /// radius] (the bore, helix radius + tool radius, then has no core). Unset:
  /// half the tool radius, or a quarter or an eighth where only that fits in
  /// the waste.
  std::optional<double> helix_radius;
  /// Replace the path's G1 stretches (a digitised outline's points, chords
  /// of non-circular offsets) by tangent-continuous arcs: the chords then
  /// keep within a quarter of the tolerance, the arcs within what they left
  /// of a half (arc_fit.h proves the bound).
  bool arc_fit = true;
  /// Finishing: > 0 leaves this much stock on every loop in the roughing
  /// passes (their path at tool radius + finish from the part), then cuts the
  /// part's edge in one pass at full depth on the exact path, entering along a
  /// tangent arc of this radius from inside the roughed slot. 0: no finishing
  /// pass. In [0, tool radius).
  double finish = 0.0;
  CutDirection direction = CutDirection::Climb;
  CornerRelief relief = CornerRelief::None;
  /// Largest distance between the tool-centre path and the exact offset of
  /// the exact curves (chords of non-circular stretches), model units, > 0.
  double tolerance = 0.01;
  /// Narrowest web of material allowed between two loops (a hole and the
  /// outline, two holes), >= 0 (0: no check); unset: one tool diameter.
  std::optional<double> min_web;
  std::size_t max_points = 5000000;  ///< budget of path points over all loops
  /// The tool table as the design gives it (`cnc.tools`): the router bit
  /// (at most one EndMill, of tool_diameter) and the drills. Empty: the
  /// router bit is tool 1 and the drills are numbered by the caller. A
  /// program changes tools (M6) only when it drills or a table is given.
  std::vector<CncTool> tools;
  DrillCycle drill;  ///< the drill holes' cycle
};

/// Throws RangeError naming the field ("cnc.tool_diameter", "cnc.tabs.height",
/// "cnc.tools[1].diameter", ...) and its value when an option is out of range
/// (NaN and infinities included), a tool number is repeated, the table holds
/// two end mills or one of another diameter than tool_diameter.
void validate_cnc_options(const CncOptions& options);

/// The tabs' minimum radius of curvature with its default (20 tool
/// diameters) resolved.
double tab_min_radius(const TabOptions& tabs, double tool_diameter);

/// The length of path one ramp descends over for a drop of `drop`.
double ramp_length(const CncOptions& options, double drop);

/// The minimum web with its default resolved.
double min_web(const CncOptions& options);

/// The router bit's number: the table's end mill, else 1.
int end_mill_number(const CncOptions& options);

/// The drill cycle's feed and spindle speed with their defaults resolved
/// (the plunge feed, the router's spindle speed).
double drill_feed(const CncOptions& options);
double drill_spindle(const CncOptions& options);
/// The drill cycle's retract plane R (height above the top), safe_z unless given.
double drill_retract(const CncOptions& options);

}  // namespace fabmesh
