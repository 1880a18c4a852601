#include "geometry/toolpath/cnc_options.h"

#include <fmt/format.h>

#include <cmath>

#include "geometry/core/errors.h"

namespace fabmesh {
namespace {

void require_non_negative(const std::string& field, double value) {
  require_in_range(field, value, 0.0, INFINITY);
}

}  // namespace

const char* to_string(CutDirection d) { return d == CutDirection::Climb ? "climb" : "conventional"; }

const char* to_string(CornerRelief r) { return r == CornerRelief::Dogbone ? "dogbone" : "none"; }

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
  if (o.tabs.count > 1000) {
    throw RangeError("cnc.tabs.count", static_cast<double>(o.tabs.count),
                     fmt::format("cnc.tabs.count = {} is outside [0, 1000]", o.tabs.count));
  }
  if (o.tabs.count > 0) {
    require_positive("cnc.tabs.width", o.tabs.width);
    require_positive("cnc.tabs.height", o.tabs.height);
    if (o.tabs.height >= o.depth) {
      throw RangeError(
          "cnc.tabs.height", o.tabs.height,
          fmt::format("cnc.tabs.height = {} must be below the depth {}", o.tabs.height, o.depth));
    }
    if (o.tabs.min_radius) require_positive("cnc.tabs.min_radius", *o.tabs.min_radius);
  }
}

double tab_min_radius(const CncOptions& o) { return o.tabs.min_radius.value_or(20.0 * o.tool_diameter); }

double min_web(const CncOptions& o) { return o.min_web.value_or(o.tool_diameter); }

}  // namespace fabmesh
