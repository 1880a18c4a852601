#include "geometry/toolpath/cnc_options.h"

#include <fmt/format.h>

#include <cmath>

#include "geometry/core/error_checks.h"

namespace fabmesh {
namespace {

void require_non_negative(const std::string& field, double value) {
  require_in_range(field, value, 0.0, INFINITY);
}

void validate_tabs(const std::string& field, const TabOptions& tabs, double depth) {
  if (tabs.count > 1000) {
    throw RangeError(field + ".count", static_cast<double>(tabs.count),
                     fmt::format("{}.count = {} is outside [0, 1000]", field, tabs.count));
  }
  if (tabs.count == 0) return;
  require_positive(field + ".width", tabs.width);
  require_positive(field + ".height", tabs.height);
  if (tabs.height >= depth) {
    throw RangeError(field + ".height", tabs.height,
                     fmt::format("{}.height = {} must be below the depth {}", field, tabs.height, depth));
  }
  if (tabs.min_radius) require_positive(field + ".min_radius", *tabs.min_radius);
}

// The tool table: numbers in [1, 999] given once, diameters > 0, at most one
// end mill, of the router bit's diameter.
void validate_tools(const CncOptions& o) {
  std::size_t end_mills = 0;
  for (std::size_t i = 0; i < o.tools.size(); ++i) {
    const CncTool& t = o.tools[i];
    const std::string field = fmt::format("cnc.tools[{}]", i);
    if (t.number < 1 || t.number > 999) {
      throw RangeError(field + ".number", t.number,
                       fmt::format("{}.number = {} is outside [1, 999]", field, t.number));
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (o.tools[j].number == t.number) {
        throw RangeError(
            field + ".number", t.number,
            fmt::format("{}.number = {}: cnc.tools[{}] has that number already", field, t.number, j));
      }
    }
    require_positive(field + ".diameter", t.diameter);
    if (t.type != ToolType::EndMill) continue;
    if (++end_mills > 1) {
      throw RangeError(field + ".type", t.number,
                       fmt::format("{}: a second end_mill; the router cut uses one bit", field));
    }
    if (t.diameter != o.tool_diameter) {
      throw RangeError(field + ".diameter", t.diameter,
                       fmt::format("{}.diameter = {}: the end mill is the router bit, of "
                                   "cnc.tool_diameter = {}",
                                   field, t.diameter, o.tool_diameter));
    }
  }
  if (end_mills == 0 && !o.tools.empty()) {
    for (std::size_t i = 0; i < o.tools.size(); ++i) {
      if (o.tools[i].number == 1) {
        throw RangeError(fmt::format("cnc.tools[{}].number", i), 1,
                         fmt::format("cnc.tools lists no end_mill, so the router bit is tool 1, but "
                                     "cnc.tools[{}] is a drill numbered 1: list the router bit",
                                     i));
      }
    }
  }
}

}  // namespace

const char* to_string(ToolType t) {
  switch (t) {
    case ToolType::Drill:
      return "drill";
    case ToolType::Profile:
      return "profile";
    case ToolType::EndMill:
      break;
  }
  return "end_mill";
}

const char* to_string(CutDirection d) { return d == CutDirection::Climb ? "climb" : "conventional"; }

const char* to_string(CornerRelief r) { return r == CornerRelief::Dogbone ? "dogbone" : "none"; }

const char* to_string(EntryKind e) {
  switch (e) {
    case EntryKind::Ramp:
      return "ramp";
    case EntryKind::Helix:
      return "helix";
    case EntryKind::Plunge:
      break;
  }
  return "plunge";
}

void validate_cnc_options(const CncOptions& o) {
  require_positive("cnc.tool_diameter", o.tool_diameter);
  require_positive("cnc.depth", o.depth);
  require_non_negative("cnc.breakthrough", o.breakthrough);
  require_positive("cnc.step_down", o.step_down);
  require_positive("cnc.feed", o.feed);
  require_positive("cnc.plunge", o.plunge);
  require_positive("cnc.rapid", o.rapid);
  require_positive("cnc.spindle", o.spindle);
  require_positive("cnc.safe_z", o.safe_z);
  require_non_negative("cnc.lead_in", o.lead_in);
  require_positive("cnc.tolerance", o.tolerance);
  if (o.min_web) require_non_negative("cnc.min_web", *o.min_web);
  if (o.tolerance >= 0.5 * o.tool_diameter) {
    throw RangeError("cnc.tolerance", o.tolerance,
                     fmt::format("cnc.tolerance = {} must be smaller than the tool radius {}", o.tolerance,
                                 0.5 * o.tool_diameter));
  }
  const double passes = std::ceil((o.depth + o.breakthrough) / o.step_down);
  if (passes > 10000) {
    throw RangeError("cnc.step_down", o.step_down,
                     fmt::format("cnc.step_down = {} needs {} passes for a depth of {} (at most 10000)",
                                 o.step_down, passes, o.depth + o.breakthrough));
  }
  if (!(o.finish >= 0.0 && o.finish < 0.5 * o.tool_diameter)) {
    throw RangeError("cnc.finish", o.finish,
                     fmt::format("cnc.finish = {} must be in [0, {}), below the tool radius", o.finish,
                                 0.5 * o.tool_diameter));
  }
  validate_tabs("cnc.tabs", o.tabs, o.depth);
  for (std::size_t i = 0; i < o.hole_tabs.size(); ++i)
    validate_tabs(fmt::format("cnc.hole_tabs[{}]", i), o.hole_tabs[i], o.depth);
  if (o.entry != EntryKind::Plunge && !(o.ramp_angle_deg > 0.0 && o.ramp_angle_deg <= 45.0)) {
    throw RangeError("cnc.ramp_angle", o.ramp_angle_deg,
                     fmt::format("cnc.ramp_angle = {} must be in (0, 45] degrees", o.ramp_angle_deg));
  }
  if (o.helix_radius && !(*o.helix_radius > 0.0 && *o.helix_radius <= 0.5 * o.tool_diameter)) {
    throw RangeError("cnc.helix_radius", *o.helix_radius,
                     fmt::format("cnc.helix_radius = {} must be in (0, {}], at most the tool radius",
                                 *o.helix_radius, 0.5 * o.tool_diameter));
  }
  validate_tools(o);
  require_non_negative("cnc.drill.peck", o.drill.peck);
  if (o.drill.feed) require_positive("cnc.drill.feed", *o.drill.feed);
  if (o.drill.spindle) require_positive("cnc.drill.spindle", *o.drill.spindle);
  if (o.drill.retract) {
    require_positive("cnc.drill.retract", *o.drill.retract);
    if (*o.drill.retract > o.safe_z) {
      throw RangeError(
          "cnc.drill.retract", *o.drill.retract,
          fmt::format("cnc.drill.retract = {} must be at most cnc.safe_z = {}", *o.drill.retract, o.safe_z));
    }
  }
}

double tab_min_radius(const TabOptions& tabs, double tool_diameter) {
  return tabs.min_radius.value_or(20.0 * tool_diameter);
}

double ramp_length(const CncOptions& o, double drop) {
  return drop / std::tan(o.ramp_angle_deg * M_PI / 180.0);
}

double min_web(const CncOptions& o) { return o.min_web.value_or(o.tool_diameter); }

int end_mill_number(const CncOptions& o) {
  for (const CncTool& t : o.tools) {
    if (t.type == ToolType::EndMill) return t.number;
  }
  return 1;
}

double drill_feed(const CncOptions& o) { return o.drill.feed.value_or(o.plunge); }

double drill_spindle(const CncOptions& o) { return o.drill.spindle.value_or(o.spindle); }

double drill_retract(const CncOptions& o) { return o.drill.retract.value_or(o.safe_z); }

}  // namespace fabmesh
