#include "geometry/toolpath/tabs.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace fabmesh {
namespace {

using Interval = std::pair<double, double>;

// Stretches [begin, end] of the path made of flat offset pieces, and of the
// tool's arcs round convex corners that turn no more than a gentle curve of
// min_radius turns over one tool diameter (a digitised outline's points).
std::vector<Interval> flat_stretches(const LoopPath& path, double min_radius, double tool_diameter) {
  std::vector<Interval> out;
  double u = 0.0;
  for (const PathPiece& p : path.pieces) {
    const double len = piece_length(p);
    const bool gentle_corner = p.role == PieceRole::Corner && std::abs(p.sweep) * min_radius <= tool_diameter;
    if ((p.role == PieceRole::Offset && p.radius_of_curvature >= min_radius) || gentle_corner) {
      if (!out.empty() && out.back().second == u) {
        out.back().second = u + len;
      } else {
        out.push_back({u, u + len});
      }
    }
    u += len;
  }
  return out;
}

// Removes (lo, hi) from a sorted list of intervals.
void cut_out(std::vector<Interval>& intervals, double lo, double hi) {
  std::vector<Interval> out;
  for (const Interval& iv : intervals) {
    if (iv.second < lo || iv.first > hi) {
      out.push_back(iv);
      continue;
    }
    if (iv.first < lo) out.push_back({iv.first, lo});
    if (iv.second > hi) out.push_back({hi, iv.second});
  }
  intervals = std::move(out);
}

// The radius of curvature tabs need on this loop: the one asked for, else
// 20 tool diameters, or the loop's flattest offset stretch where it has none
// that flat (a round cut-out is curved all along: its tabs go anywhere on it,
// rather than nowhere).
double loop_tab_radius(const LoopPath& path, const TabOptions& tabs, double tool_diameter) {
  const double wanted = tab_min_radius(tabs, tool_diameter);
  if (tabs.min_radius) return wanted;
  double flattest = 0.0;
  for (const PathPiece& p : path.pieces) {
    if (p.role == PieceRole::Offset) flattest = std::max(flattest, p.radius_of_curvature);
  }
  return flattest > 0.0 ? std::min(wanted, flattest) : wanted;
}

}  // namespace

TabPlacement place_tabs(const LoopPath& path, const TabOptions& want_tabs, const CncOptions& o,
                        double clear_start) {
  TabPlacement out;
  if (want_tabs.count == 0) return out;
  const double lifted = want_tabs.width + o.tool_diameter;
  const double gap = o.tool_diameter;
  const double min_radius = loop_tab_radius(path, want_tabs, o.tool_diameter);
  // Admissible tab centres: inside flat stretches by half a tab, clear of the start point.
  std::vector<Interval> centres;
  for (const Interval& s : flat_stretches(path, min_radius, o.tool_diameter)) {
    const double lo = std::max(s.first, std::max(gap, clear_start)) + 0.5 * lifted,
                 hi = std::min(s.second, path.length - gap) - 0.5 * lifted;
    if (lo <= hi) centres.push_back({lo, hi});
  }
  const double count = static_cast<double>(want_tabs.count);
  std::size_t missing = 0;
  for (std::size_t i = 0; i < want_tabs.count; ++i) {
    const double want = (static_cast<double>(i) + 0.5) * path.length / count;
    double best = INFINITY, best_d = INFINITY;
    for (const Interval& c : centres) {
      const double x = std::clamp(want, c.first, c.second);
      if (std::abs(x - want) < best_d) best_d = std::abs(x - want), best = x;
    }
    if (best == INFINITY) {
      ++missing;
      continue;
    }
    out.tabs.push_back({best - 0.5 * lifted, best + 0.5 * lifted});
    cut_out(centres, best - lifted - gap, best + lifted + gap);
  }
  std::sort(out.tabs.begin(), out.tabs.end());
  if (missing > 0) {
    out.warning = fmt::format(
        "{}: {} of {} tabs placed; no room for {} more (each needs {:.6g} = width {:.6g} + tool diameter "
        "{:.6g} of a straight or gently curved stretch, radius of curvature >= {:.6g}, of its tool path of "
        "length {:.6g}, one tool diameter from the others{}): narrow the tabs, lower min_radius or ask for "
        "fewer",
        path.label, out.tabs.size(), want_tabs.count, missing, lifted, want_tabs.width, o.tool_diameter,
        min_radius, path.length, clear_start > gap ? " and clear of the ramp" : "");
  }
  return out;
}

}  // namespace fabmesh
