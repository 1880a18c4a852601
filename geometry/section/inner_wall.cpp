#include "geometry/section/inner_wall.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "geometry/core/errors.h"
#include "geometry/sampling/offset_curve.h"

namespace fabmesh {
namespace {

OffsetSpec spec_of(const InnerWall& wall, std::size_t segment) {
  return {wall.wall, wall.side, fmt::format("wall {}", wall.wall),
          fmt::format("profile segment {}", segment + 1)};
}

// The offset arc of piece k: segment and the parameters of its two ends on it.
struct PieceArc {
  std::size_t segment;
  double s_a, s_b;
};

PieceArc piece_arc(const InnerWall& wall, std::size_t k) {
  const WallPoint& a = wall.points[k];
  const WallPoint& b = wall.points[k + 1];
  const std::size_t seg = std::min(a.segment, b.segment);
  // Across a joint the later segment's point is its start, the earlier one's end.
  return {seg, a.segment == seg ? a.s : 1.0, b.segment == seg ? b.s : 1.0};
}

// Where piece k first crosses coordinate `axis` (0: x, 1: y) = value, going
// from points[k] (at or above) to points[k + 1] (below): exact on the offset
// arc (bisection between the chord's end parameters), linear on a straight
// piece. The coordinate is set to exactly `value`; `snap` receives the move.
WallPoint crossing(const InnerWall& wall, const CompositeCurve& profile, std::size_t k, int axis,
                   double value, double* snap) {
  const WallPoint& a = wall.points[k];
  const WallPoint& b = wall.points[k + 1];
  WallPoint c = b;
  if (wall.straight[k]) {
    const double t = (a.point[axis] - value) / (a.point[axis] - b.point[axis]);
    c.point = a.point + std::clamp(t, 0.0, 1.0) * (b.point - a.point);
  } else {
    const PieceArc arc = piece_arc(wall, k);
    const Segment& seg = profile.segments()[arc.segment];
    const OffsetSpec spec = spec_of(wall, arc.segment);
    double above = arc.s_a, below = arc.s_b;
    Vec2 p = b.point;
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (above + below);
      if (mid == above || mid == below) break;
      const Vec2 q = offset_jet(seg, spec, mid).point;
      if (q[axis] >= value) {
        above = mid;
      } else {
        below = mid;
        p = q;
      }
    }
    c.point = p;
    c.segment = arc.segment;
    c.s = below;
  }
  *snap = std::max(*snap, std::abs(c.point[axis] - value));
  c.point[axis] = value;
  return c;
}

void keep_until(InnerWall& wall, std::size_t k, const WallPoint& cut) {
  const bool straight = wall.straight[k];
  wall.points.resize(k + 1);
  wall.straight.resize(k);
  wall.points.push_back(cut);
  wall.straight.push_back(straight);
}

}  // namespace

InnerWall sample_inner_wall(const CompositeCurve& profile, double wall, double side, bool rim_at_end,
                            const SampleOptions& options, const std::string& profile_name) {
  InnerWall out;
  out.wall = wall;
  out.side = side;
  const auto& segs = profile.segments();
  const double merge = 1e-3 * options.tolerance;
  double worst = 0.0, worst_gap = 0.0;
  for (std::size_t i = 0; i < segs.size(); ++i) {
    OffsetSpec spec = spec_of(out, i);
    if (!profile_name.empty()) spec.where = fmt::format("segment {} of {}", i + 1, profile_name);
    const OffsetChordBound bound(segs[i], spec);
    SampleOptions so = options;
    so.max_points = options.max_points - std::min(options.max_points, out.points.size());
    double achieved = 0.0;
    const std::vector<double> params = sample_parameters(bound, so, &achieved);
    worst = std::max(worst, achieved);
    for (std::size_t k = 0; k < params.size(); ++k) {
      const WallPoint p{offset_jet(segs[i], spec, params[k]).point, i, params[k]};
      if (k == 0 && !out.points.empty()) {
        const double gap = (out.points.back().point - p.point).norm();
        if (gap <= merge) {  // a smooth joint: one point (the later segment's start)
          worst_gap = std::max(worst_gap, gap);
          out.points.back() = p;
          continue;
        }
        out.straight.push_back(true);  // a corner: the offsets are bridged by a straight bevel
        out.points.push_back(p);
        continue;
      }
      if (!out.points.empty()) out.straight.push_back(false);
      out.points.push_back(p);
    }
  }
  out.max_deviation = worst + worst_gap;
  if (rim_at_end) {
    std::reverse(out.points.begin(), out.points.end());
    std::reverse(out.straight.begin(), out.straight.end());
  }
  return out;
}

bool cut_inner_wall(InnerWall& wall, const CompositeCurve& profile, double z_cut) {
  for (std::size_t k = 0; k + 1 < wall.points.size(); ++k) {
    const Vec2 a = wall.points[k].point, b = wall.points[k + 1].point;
    const double tz = (b.y() < z_cut) ? (a.y() - z_cut) / (a.y() - b.y()) : 2.0;
    const double tr = (b.x() < 0.0) ? a.x() / (a.x() - b.x()) : 2.0;
    if (tz > 1.0 && tr > 1.0) continue;
    const bool at_base = tz <= tr;
    double snap = 0.0;
    const WallPoint c = crossing(wall, profile, k, at_base ? 1 : 0, at_base ? z_cut : 0.0, &snap);
    wall.max_deviation += snap;
    keep_until(wall, k, c);
    return at_base;
  }
  return false;
}

void level_inner_wall(InnerWall& wall, const CompositeCurve& profile, double z_top, bool rim_at_end) {
  const Vec2 top = wall.points.front().point;
  if (top.y() > z_top) {
    // Cut away what rises above the rim: from the first piece that comes down to z_top.
    std::size_t k = 0;
    while (k + 1 < wall.points.size() && wall.points[k + 1].point.y() > z_top) ++k;
    if (k + 1 == wall.points.size()) {
      throw GeometryError(
          "rim", fmt::format("rim: level: the inner wall never comes down to the rim height {}", z_top));
    }
    double snap = 0.0;
    const WallPoint c = crossing(wall, profile, k, 1, z_top, &snap);
    wall.max_deviation += snap;
    wall.points.erase(wall.points.begin(), wall.points.begin() + static_cast<long>(k));
    wall.straight.erase(wall.straight.begin(), wall.straight.begin() + static_cast<long>(k));
    wall.points.front() = c;
    return;
  }
  if (top.y() == z_top) return;
  // The wall ends below the rim: continue it along its end tangent (a straight piece).
  const Segment& seg = rim_at_end ? profile.segments().back() : profile.segments().front();
  const std::size_t index = rim_at_end ? profile.size() - 1 : 0;
  const OffsetJet end = offset_jet(seg, spec_of(wall, index), rim_at_end ? 1.0 : 0.0);
  const Vec2 up = (rim_at_end ? end.d1 : Vec2(-end.d1)).normalized();
  if (!(up.y() > 1e-6)) {
    throw GeometryError("rim",
                        fmt::format("rim: level needs an inner wall that rises toward the rim; it runs "
                                    "({:.6g}, {:.6g}) there (use rim: square)",
                                    up.x(), up.y()));
  }
  WallPoint e = wall.points.front();
  e.point = top + (z_top - top.y()) / up.y() * up;
  e.point.y() = z_top;
  wall.points.insert(wall.points.begin(), e);
  wall.straight.insert(wall.straight.begin(), true);
}

void inner_wall_pieces(const InnerWall& wall, const CompositeCurve& profile, int group,
                       std::vector<std::unique_ptr<ExactArc>>& arcs, std::vector<ArcPiece>& pieces) {
  std::vector<const ExactArc*> offsets(profile.size(), nullptr);
  for (std::size_t k = 0; k + 1 < wall.points.size(); ++k) {
    if (wall.straight[k]) {
      arcs.push_back(std::make_unique<LineArc>(wall.points[k].point, wall.points[k + 1].point));
      pieces.push_back({arcs.back().get(), 0.0, 1.0, group});
      continue;
    }
    const PieceArc arc = piece_arc(wall, k);
    if (!offsets[arc.segment]) {
      arcs.push_back(
          std::make_unique<OffsetArc>(profile.segments()[arc.segment], spec_of(wall, arc.segment)));
      offsets[arc.segment] = arcs.back().get();
    }
    pieces.push_back({offsets[arc.segment], std::min(arc.s_a, arc.s_b), std::max(arc.s_a, arc.s_b), group});
  }
}

std::vector<ExactPiece> inner_wall_exact_pieces(const InnerWall& wall, const CompositeCurve& profile) {
  std::vector<ExactPiece> pieces;
  std::optional<std::size_t> arc_segment;  // the segment of the last piece when it is an offset arc
  for (std::size_t k = 0; k + 1 < wall.points.size(); ++k) {
    const Vec2& a = wall.points[k].point;
    const Vec2& b = wall.points[k + 1].point;
    if (wall.straight[k]) {
      if (a != b) pieces.push_back({Segment::line(a, b), {}, 0.0, 1.0});
      arc_segment.reset();
      continue;
    }
    const PieceArc arc = piece_arc(wall, k);
    if (arc.s_a == arc.s_b) continue;
    if (arc_segment == arc.segment && pieces.back().s1 == arc.s_a) {
      pieces.back().s1 = arc.s_b;  // the same segment's offset runs on
    } else {
      pieces.push_back({profile.segments()[arc.segment], spec_of(wall, arc.segment), arc.s_a, arc.s_b});
    }
    arc_segment = arc.segment;
  }
  return pieces;
}

}  // namespace fabmesh
