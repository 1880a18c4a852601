#include "geometry/toolpath/drilling.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/core/errors.h"
#include "geometry/toolpath/boundary_index.h"

namespace fabmesh {
namespace {

std::string at(const Vec2& p) { return fmt::format("({:.6g}, {:.6g})", p.x(), p.y()); }

std::string tool_list(const CncOptions& o) {
  std::string out;
  for (const CncTool& t : o.tools) {
    if (t.type != ToolType::Drill) continue;
    out += fmt::format("{}T{} {:.6g}", out.empty() ? "" : ", ", t.number, t.diameter);
  }
  return out.empty() ? "none" : out;
}

// Distance from `p` to the closed polyline `loop`.
double loop_distance(const std::vector<Vec2>& loop, const Vec2& p, Vec2* nearest) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < loop.size(); ++k) {
    Vec2 on;
    const double d = segment_distance(loop[k], loop[(k + 1) % loop.size()], p, p, &on);
    if (d < best) best = d, *nearest = on;
  }
  return best;
}

}  // namespace

std::vector<DrillHole> drilling_order(std::vector<DrillHole> holes, const CncOptions& o) {
  const int router = end_mill_number(o);
  for (const DrillHole& h : holes) {
    if (!(h.diameter > 0.0 && std::isfinite(h.diameter))) {
      throw GeometryError(h.label, fmt::format("{}: drill diameter = {} must be > 0", h.label, h.diameter));
    }
    if (h.tool < 1 || h.tool > 999 || h.tool == router) {
      throw GeometryError(h.label, fmt::format("{}: tool {} is not a drill (the router bit is tool {})",
                                               h.label, h.tool, router));
    }
    if (o.tools.empty()) continue;
    const auto tool = std::find_if(o.tools.begin(), o.tools.end(), [&](const CncTool& t) {
      return t.number == h.tool && t.type == ToolType::Drill;
    });
    if (tool == o.tools.end()) {
      throw GeometryError(h.label, fmt::format("{}: tool {} is no drill of cnc.tools (drills: {})", h.label,
                                               h.tool, tool_list(o)));
    }
    if (tool->diameter != h.diameter) {
      throw GeometryError(
          h.label, fmt::format("{}: tool {} is a drill of diameter {:.6g}, not the hole's {:.6g}", h.label,
                               h.tool, tool->diameter, h.diameter));
    }
  }
  std::stable_sort(holes.begin(), holes.end(),
                   [](const DrillHole& a, const DrillHole& b) { return a.tool < b.tool; });
  return holes;
}

void check_drill_webs(const std::vector<DrillHole>& drills, const std::vector<std::size_t>& own,
                      const std::vector<const std::vector<Vec2>*>& loops,
                      const std::vector<std::string>& labels, double deviation, const CncOptions& o) {
  const double web = min_web(o);
  if (!(web > 0.0)) return;
  for (std::size_t k = 0; k < drills.size(); ++k) {
    const DrillHole& d = drills[k];
    const double r = 0.5 * d.diameter;
    for (std::size_t l = 0; l < loops.size(); ++l) {
      if (l == own[k] || loops[l]->empty()) continue;
      Vec2 nearest(0.0, 0.0);
      // The exact loop passes within `deviation` of its samples: the true gap is at most this.
      const double gap = loop_distance(*loops[l], d.center, &nearest) + deviation - r;
      if (gap >= web) continue;
      const Vec2 toward = nearest - d.center;
      const Vec2 rim = toward.norm() > 0.0 ? d.center + r * toward.normalized() : d.center;
      throw GeometryError(d.label, fmt::format("{}: the web between it and {} is at most {:.6g} near {}, "
                                               "narrower than {} (cnc.min_web; default one tool diameter)",
                                               d.label, labels[l] == "outline" ? "the outline" : labels[l],
                                               gap, at(0.5 * (rim + nearest)), web));
    }
  }
}

DrillingTotals drilling_totals(const std::vector<DrillHole>& drills, const CncOptions& o) {
  DrillingTotals t;
  const double r_plane = drill_retract(o), bottom = -(o.depth + o.breakthrough);
  for (std::size_t k = 0; k < drills.size(); ++k) {
    // Across at safe height, down to R, and from R (G98) back to safe height at the end.
    t.rapid += 2.0 * (o.safe_z - r_plane);
    if (k > 0) t.rapid += (drills[k].center - drills[k - 1].center).norm();
    t.feeding += r_plane - bottom;
    if (o.drill.peck > 0.0) {
      // G83: each peck goes Q deeper from R, then out to R, and back down to where it stopped.
      const auto pecks = static_cast<std::size_t>(std::ceil((r_plane - bottom) / o.drill.peck - 1e-9));
      for (std::size_t p = 1; p <= pecks; ++p) {
        const double z = std::max(bottom, r_plane - static_cast<double>(p) * o.drill.peck);
        t.rapid += (r_plane - z) * (p < pecks ? 2.0 : 1.0);
      }
    } else {
      t.rapid += r_plane - bottom;
    }
  }
  return t;
}

}  // namespace fabmesh
