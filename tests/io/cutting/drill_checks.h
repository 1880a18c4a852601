#pragma once
// Tap holes in router programs: the canned cycles a program drills with
// (read_canned_cycles, since the CNCjs interpreter has none) held to the
// holes the design places, and the rest of the program handed to the
// interpreter.

#include <catch2/catch.hpp>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "geometry/toolpath/cnc_options.h"
#include "tests/io/cutting/interpret.h"

namespace fabmesh::test {

/// A tap hole where the program must drill it, millimetres, in the
/// program's frame (slab coordinates for a kitchen).
struct ExpectedDrill {
  Vec2 center{0.0, 0.0};
  double diameter = 0.0;
  std::string label;
};

/// What the drilling must be, millimetres (and mm/min).
struct DrillSpec {
  double thickness = 0.0;  ///< the slab's: every hole goes through it
  double through = 0.0;    ///< depth + breakthrough: where the routed cuts go
  double safe_z = 0.0;     ///< the program's safe height: R no higher, the cycles start there
  double feed = 0.0;       ///< the drill feed
  double peck = 0.0;       ///< > 0: G83 with this Q; 0: G81
  double rounding = 1e-3;  ///< how far the program's rounding may move a number
  struct Tool {
    ToolType type = ToolType::Drill;
    double diameter = 0.0;
  };
  std::map<int, Tool> tools;  ///< the tool table the design declares (or implies)
  int end_mill = 1;
};

/// Every tap hole drilled exactly once, at its centre (within the program's
/// rounding), before any routing, by a drill of its diameter in the spindle
/// (M6 T<n>) running, through the slab from an R plane above the top, the
/// cycle cancelled by G80; each tool change after a retract to safe height
/// and M5 when the spindle runs, M3 after it; the end mill back for routing
/// (a program that changes no tool drills nothing).
inline void check_drilling(const CannedCycles& c, const std::vector<ExpectedDrill>& holes,
                           const DrillSpec& s) {
  const double unit = c.units == "G20" ? 25.4 : 1.0;  // program units to mm
  REQUIRE(c.blocks.size() == holes.size());
  std::vector<int> drilled(holes.size(), 0);
  for (const DrillBlock& b : c.blocks) {
    INFO("cycle block on line " << b.line);
    CHECK(b.cycle == (s.peck > 0.0 ? "G83" : "G81"));
    CHECK(b.stated_all);     // nothing left for a controller to carry over
    CHECK(b.initial_level);  // G98: back to safe height after the hole
    CHECK(b.cancelled);      // G80 follows
    CHECK(b.spindle_on);
    CHECK(b.line < c.first_feed_motion);  // drilled before any routing
    CHECK(b.z * unit <= -s.thickness + s.rounding);
    CHECK(b.z * unit == Approx(-s.through).margin(s.rounding));
    CHECK(b.r * unit > 0.0);  // above the top
    CHECK(b.r * unit <= s.safe_z + s.rounding);
    CHECK(b.start_z * unit == Approx(s.safe_z).margin(s.rounding));
    CHECK(b.f * unit == Approx(s.feed).margin(s.rounding));
    if (s.peck > 0.0) CHECK(b.q * unit == Approx(s.peck).margin(s.rounding));
    std::vector<std::size_t> at;
    for (std::size_t k = 0; k < holes.size(); ++k) {
      if (std::abs(b.x * unit - holes[k].center.x()) <= s.rounding &&
          std::abs(b.y * unit - holes[k].center.y()) <= s.rounding)
        at.push_back(k);
    }
    INFO("at X" << b.x << " Y" << b.y);
    REQUIRE(at.size() == 1);
    ++drilled[at[0]];
    INFO(holes[at[0]].label << " with tool " << b.tool);
    const auto tool = s.tools.find(b.tool);
    REQUIRE(tool != s.tools.end());
    CHECK(tool->second.type == ToolType::Drill);
    CHECK(tool->second.diameter == holes[at[0]].diameter);
  }
  for (std::size_t k = 0; k < holes.size(); ++k) {
    INFO(holes[k].label);
    CHECK(drilled[k] == 1);
  }
  // Each drill comes into the spindle once, then the end mill.
  std::map<int, int> changes;
  for (const ToolChange& t : c.changes) {
    INFO("M6 T" << t.tool << " on line " << t.line);
    ++changes[t.tool];
    if (t.spindle_was_on) {
      CHECK(t.stopped_first);
      CHECK(t.z_before * unit == Approx(s.safe_z).margin(s.rounding));
    }
    CHECK(t.started_after);
  }
  for (const auto& [tool, count] : changes) CHECK(count == 1);
  // A program that changes no tool runs with the bit in the spindle: it drills nothing.
  if (c.changes.empty()) {
    CHECK(c.blocks.empty());
  } else {
    CHECK(c.routing_tool == s.end_mill);
  }
  const auto router = s.tools.find(s.end_mill);
  REQUIRE(router != s.tools.end());
  CHECK(router->second.type == ToolType::EndMill);
}

/// The interpreter skips canned cycles: the whole program and the program
/// without its cycle blocks make the same motions, and the whole program's
/// unknown codes are the blocks' own (G98 and G81 or G83 on each). Returns
/// the trace of the program without them (no unknown code), for measuring.
inline Trace interpret_around_cycles(const std::string& program, const CannedCycles& c,
                                     const std::string& name) {
  const Trace whole = interpret(program, name);
  const Trace rest = interpret(c.without_cycles, "routed-" + name);
  REQUIRE(whole.motions.size() == rest.motions.size());
  std::size_t same = 0;
  for (std::size_t i = 0; i < whole.motions.size(); ++i) {
    const TraceMotion &a = whole.motions[i], &b = rest.motions[i];
    same += a.motion == b.motion && a.arc == b.arc && a.start == b.start && a.end == b.end ? 1 : 0;
  }
  CHECK(same == whole.motions.size());
  std::multiset<std::string> unknown(whole.unknown.begin(), whole.unknown.end()), expected;
  for (const DrillBlock& b : c.blocks) expected.insert("G98"), expected.insert(b.cycle);
  CHECK(unknown == expected);
  CHECK(rest.unknown.empty());
  return rest;
}

}  // namespace fabmesh::test
