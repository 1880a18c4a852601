#include "geometry/toolpath/tabs.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geometry/core/errors.h"

namespace fabmesh {
namespace {

using Interval = std::pair<double, double>;

// Stretches [begin, end] of the path made of flat offset pieces.
std::vector<Interval> flat_stretches(const LoopPath& path, double min_radius) {
  std::vector<Interval> out;
  double u = 0.0;
  for (const PathPiece& p : path.pieces) {
    const double len = piece_length(p);
    if (p.role == PieceRole::Offset && p.radius_of_curvature >= min_radius) {
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

}  // namespace

std::vector<std::pair<double, double>> place_tabs(const LoopPath& path, const CncOptions& o) {
  std::vector<Interval> tabs;
  if (o.tabs.count == 0) return tabs;
  const double lifted = o.tabs.width + o.tool_diameter;
  const double gap = o.tool_diameter;
  // Admissible tab centres: inside flat stretches by half a tab, clear of the start point.
  std::vector<Interval> centres;
  for (const Interval& s : flat_stretches(path, tab_min_radius(o))) {
    const double lo = std::max(s.first, gap) + 0.5 * lifted,
                 hi = std::min(s.second, path.length - gap) - 0.5 * lifted;
    if (lo <= hi) centres.push_back({lo, hi});
  }
  const double count = static_cast<double>(o.tabs.count);
  for (std::size_t i = 0; i < o.tabs.count; ++i) {
    const double want = (static_cast<double>(i) + 0.5) * path.length / count;
    double best = INFINITY, best_d = INFINITY;
    for (const Interval& c : centres) {
      const double x = std::clamp(want, c.first, c.second);
      if (std::abs(x - want) < best_d) best_d = std::abs(x - want), best = x;
    }
    if (best == INFINITY) {
      throw GeometryError(
          path.label,
          fmt::format("{}: no room for tab {} of {} (width {} + tool diameter {}) on a straight or "
                      "gently curved stretch (radius of curvature >= {}) of its tool path "
                      "(length {:.6g})",
                      path.label, i + 1, o.tabs.count, o.tabs.width, o.tool_diameter, tab_min_radius(o),
                      path.length));
    }
    tabs.push_back({best - 0.5 * lifted, best + 0.5 * lifted});
    cut_out(centres, best - lifted - gap, best + lifted + gap);
  }
  std::sort(tabs.begin(), tabs.end());
  return tabs;
}

}  // namespace fabmesh
