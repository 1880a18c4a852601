#pragma once
// Test support for router programs: run a .nc file through the CNCjs
// interpreter (tools/node/gcode-trace.js), the exact distance from a point to
// a composite curve (Newton projection on the exact segments), and proof-level
// walks along the interpreted motions (Lipschitz steps: a distance cannot
// change faster than the point moves).

#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <unordered_map>
#include <vector>

#include "geometry/curves/composite.h"
#include "geometry/section/region.h"

namespace fabmesh::test {

/// One motion as the interpreter produced it (millimetres).
struct TraceMotion {
  bool arc = false;
  std::string motion;  ///< G0 G1 G2 G3
  Vec3 start{0, 0, 0}, end{0, 0, 0}, center{0, 0, 0};
  double feed = 0.0;    ///< mm per minute (F converted under G20); 0 when none was set
  std::string comment;  ///< on the motion's own line
  std::string section;  ///< the last comment line before it
  int line = 0;
};

struct Trace {
  std::vector<TraceMotion> motions;
  std::vector<std::string> unknown;  ///< G/M codes the interpreter has no handler for
  std::string units;                 ///< modal units at the end: G21 | G20
};

/// Empty when node and the npm package gcode-toolpath are installed, else
/// what is missing and how to install it (tests REQUIRE it to be empty).
std::string gcode_interpreter_problem();

/// Writes `gcode` to a scratch file named `name` after this process (in the
/// test build folder), interprets it and removes it; a file the interpreter
/// failed on is kept. \throw std::runtime_error naming what failed
Trace interpret_gcode(const std::string& gcode, const std::string& name);

/// Runs a .nc file through gcode-toolpath 3.0.0 with node (gcode-trace.js).
/// \throw std::runtime_error when the interpreter is missing or fails
Trace interpret_gcode_file(const std::string& file);

/// The motions of gcode-trace.js's JSON output.
Trace parse_trace(const std::string& json_text);

/// One canned drilling cycle block of a program (G81, or G83 with pecks),
/// its words in program units. The CNCjs interpreter has no handler for
/// canned cycles (it skips their lines and moves nowhere for them), so they
/// are read here. Z, R, Q and F are modal in a cycle: a block that leaves
/// one out has the previous block's (fabmesh's writer states them all).
struct DrillBlock {
  int line = 0;                ///< 1-based
  std::string cycle;           ///< G81 | G83
  bool initial_level = false;  ///< G98 in force: back to the level the cycle started from
  bool stated_all = false;     ///< the block itself states X, Y, Z, R and F (and Q for G83)
  double x = 0.0, y = 0.0, z = 0.0, r = 0.0, q = 0.0, f = 0.0;
  int tool = 0;             ///< the tool in the spindle (the last M6 T<n>; 0 before any)
  bool spindle_on = false;  ///< M3 in force
  bool cancelled = false;   ///< a G80 follows before any G0/G1/G2/G3
  double start_z = 0.0;     ///< the Z the tool was at when the block began (the initial level)
};

/// A tool change `M6 T<n>` (T on its line or an earlier one).
struct ToolChange {
  int line = 0;
  int tool = 0;
  bool spindle_was_on = false;  ///< M3 in force before it
  bool stopped_first = false;   ///< an M5 on the line before it
  double z_before = 0.0;        ///< the Z of the last motion before it (program units)
  bool started_after = false;   ///< M3 on the line after it
};

/// What a program's canned cycles and tool changes are.
struct CannedCycles {
  std::vector<DrillBlock> blocks;
  std::vector<ToolChange> changes;
  std::string units = "G21";  ///< G21 | G20 (the last given)
  int first_feed_motion = 0;  ///< the line of the first G1/G2/G3 (0: none)
  int routing_tool = 0;       ///< the tool in the spindle at that line
  /// The program without the cycle blocks' lines (G80 kept): what the
  /// interpreter runs the same as the whole program.
  std::string without_cycles;
};

/// Reads the canned drilling cycles (G81, G83; G80 cancels) and the tool
/// changes of a program, line by line: parenthesised comments dropped,
/// words as letter + number. \throw std::runtime_error on a cycle block
/// missing a word no earlier block gave, or a canned cycle other than G81/G83
CannedCycles read_canned_cycles(const std::string& program);

/// Length of a motion in the XY plane (arcs: radius times the turned angle;
/// the interpreter's convention: G2 clockwise, G3 counter-clockwise, equal
/// start and end a full circle).
double motion_length(const TraceMotion& m);
/// Point of a motion at fraction f in [0, 1] (z interpolated linearly).
Vec3 motion_point(const TraceMotion& m, double f);
/// Distance from p to the motion's XY path.
double motion_distance(const TraceMotion& m, const Vec2& p);

/// Exact distance from points to a composite curve: the samples nearest to q
/// along the curve (local minima) seed Newton's method on
/// f(s) = (c(s) - q) . c'(s) on their exact segment; a run that stops at a
/// segment's end continues in the neighbouring segment.
class CurveDistance {
 public:
  struct Foot {
    double distance = 0.0;
    std::size_t segment = 0;
    double s = 0.0;
    Vec2 point{0, 0};
  };
  CurveDistance(CompositeCurve curve, double spacing);
  /// The nearest point; when the curve is farther than `limit`, only a lower
  /// bound: distance = limit (segment and point unset).
  Foot nearest(const Vec2& q, double limit = std::numeric_limits<double>::infinity()) const;
  /// The curve's samples as a polygon (for inside tests), spacing apart.
  const std::vector<Vec2>& polygon() const { return polygon_; }

 private:
  struct Sample {
    Vec2 p;
    std::size_t segment;
    double s;
  };
  long long key(long long ix, long long iy) const { return ix * 1000003LL + iy; }
  double newton(std::size_t segment, double s, const Vec2& q) const;  // a foot parameter from s
  CompositeCurve curve_;
  double cell_;
  double max_gap_ = 0.0;  // longest chord between consecutive samples
  std::vector<Sample> samples_;
  std::vector<Vec2> polygon_;
  std::unordered_map<long long, std::vector<int>> grid_;
};

/// Even-odd inside test of a polygon.
bool inside_polygon(const std::vector<Vec2>& polygon, const Vec2& p);

/// Walks the XY path of `m` from start to end in steps chosen by `margin`:
/// margin(p) >= 0 is how far the checked quantity at p is from failing and
/// changes at most as fast as p moves (1-Lipschitz), so every point between
/// samples is proven when each sample has margin >= half the step. Returns
/// the least margin minus half the step around it (< 0: a failure, at *where).
double lipschitz_walk(const TraceMotion& m, const std::function<double(const Vec2&)>& margin, double min_step,
                      Vec2* where);

/// The same along a closed curve's arc length (the curve is 1-Lipschitz in
/// arc length): samples by Gauss-Legendre arc-length steps on each segment.
double lipschitz_walk_curve(const CompositeCurve& curve, const std::function<double(const Vec2&)>& margin,
                            double min_step, Vec2* where);

/// The loops of a countertop design (a file name in configs/examples, or a
/// path): outline and holes built with build_curve, labelled as the pipeline does.
struct ExampleRegion {
  CompositeCurve outline;
  std::vector<RegionHole> holes;
  double thickness = 0.0;
  double tolerance = 0.0;
  std::string name;
};
ExampleRegion load_countertop_example(const std::string& file_name);

}  // namespace fabmesh::test
