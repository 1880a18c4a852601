#include "io/dxf/dxf_chains.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <utility>

#include "geometry/core/errors.h"

namespace fabmesh {
namespace {

std::string fmt_point(const Vec2& p) { return fmt::format("({:.10g}, {:.10g})", p.x(), p.y()); }

// Ends of the open pieces, matched within `join`: each must meet exactly one other.
struct End {
  std::size_t piece = 0;
  bool at_end = false;  // false: the piece's start
  Vec2 p{0.0, 0.0};
};

std::string end_name(const End& e, const std::vector<DxfPiece>& pieces) {
  return fmt::format("{}'s {}", pieces[e.piece].entity, e.at_end ? "end" : "start");
}

// The partner of every end (index into `ends`).
std::vector<std::size_t> match_ends(const std::vector<End>& ends, const std::vector<DxfPiece>& pieces,
                                    double join, double cell, const std::string& where, double max_gap) {
  auto key = [cell](const Vec2& p) {
    return std::pair<std::int64_t, std::int64_t>(static_cast<std::int64_t>(std::floor(p.x() / cell)),
                                                 static_cast<std::int64_t>(std::floor(p.y() / cell)));
  };
  struct PairHash {
    std::size_t operator()(const std::pair<std::int64_t, std::int64_t>& k) const {
      const auto a = static_cast<std::uint64_t>(k.first);
      const auto b = static_cast<std::uint64_t>(k.second);
      return std::hash<std::uint64_t>()(a * 0x9E3779B97F4A7C15ULL ^ b);
    }
  };
  std::unordered_map<std::pair<std::int64_t, std::int64_t>, std::vector<std::size_t>, PairHash> grid;
  for (std::size_t i = 0; i < ends.size(); ++i) grid[key(ends[i].p)].push_back(i);
  std::vector<std::size_t> partner(ends.size());
  for (std::size_t i = 0; i < ends.size(); ++i) {
    const auto [kx, ky] = key(ends[i].p);
    std::vector<std::size_t> near;
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const auto it = grid.find({kx + dx, ky + dy});
        if (it == grid.end()) continue;
        for (const std::size_t j : it->second) {
          if (j != i && (ends[j].p - ends[i].p).norm() <= join) near.push_back(j);
        }
      }
    }
    if (near.empty()) {
      // The nearest end, to say how far the gap is.
      std::optional<std::size_t> nearest;
      for (std::size_t j = 0; j < ends.size(); ++j) {
        if (j != i && (!nearest || (ends[j].p - ends[i].p).norm() < (ends[*nearest].p - ends[i].p).norm()))
          nearest = j;
      }
      throw InputError(fmt::format(
          "{}: open chain: {} at {} meets no other end within max_gap {:.6g}{}", where,
          end_name(ends[i], pieces), fmt_point(ends[i].p), max_gap,
          nearest ? fmt::format(" (the nearest, {}, is {:.6g} away)", end_name(ends[*nearest], pieces),
                                (ends[*nearest].p - ends[i].p).norm())
                  : std::string()));
    }
    if (near.size() > 1) {
      std::string names = end_name(ends[i], pieces);
      for (const std::size_t j : near) names += ", " + end_name(ends[j], pieces);
      throw InputError(fmt::format(
          "{}: {} ends meet at {}: {}; entities overlap or branch there (a loop passes a point once)", where,
          near.size() + 1, fmt_point(ends[i].p), names));
    }
    partner[i] = near.front();
  }
  return partner;
}

// A piece as a loop runs through it.
DxfPiece oriented(const DxfPiece& p, bool forward) {
  if (forward) return p;
  DxfPiece r = p;
  std::swap(r.start, r.end);
  std::swap(r.ellipse.from_deg, r.ellipse.to_deg);
  std::reverse(r.beziers.begin(), r.beziers.end());
  for (BezierSpan& z : r.beziers) {
    std::reverse(z.points.begin(), z.points.end());
    std::reverse(z.weights.begin(), z.weights.end());
  }
  return r;
}

// Arcs and splines end exactly where they end; lines follow them.
bool exact(const DxfPiece& p) { return p.arc || p.spline; }

SegmentSpec line_to(const std::vector<Vec2>& points, const std::string& name) {
  SegmentSpec s;
  s.kind = SegmentKind::Line;
  s.points = points;
  s.declared = Continuity::G0;
  s.name = name;
  return s;
}

// The closed curve spec of a chain of oriented pieces: lines end exactly
// where the exact arcs they meet end; two arcs whose ends differ by more than
// the joints' check allows get a short line between them.
CurveSpec loop_spec(const std::vector<DxfPiece>& q, double bridge, std::size_t& bridges) {
  const std::size_t n = q.size();
  auto joint = [&](std::size_t k) -> Vec2 {  // where q[k] meets q[k + 1]
    const DxfPiece& a = q[k];
    const DxfPiece& b = q[(k + 1) % n];
    if (exact(a)) return a.end;
    if (exact(b)) return b.start;
    return a.end;
  };
  CurveSpec spec;
  spec.closed = true;
  spec.closing_declared = Continuity::G0;
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2 from = joint((k + n - 1) % n);
    const DxfPiece& p = q[k];
    if (!exact(p)) {
      spec.segments.push_back(line_to(
          spec.segments.empty() ? std::vector<Vec2>{from, joint(k)} : std::vector<Vec2>{joint(k)}, p.entity));
      spec.segments.back().wall = p.wall;
      continue;
    }
    if (k > 0 && exact(q[k - 1]) && (q[k - 1].end - p.start).norm() > bridge) {
      spec.segments.push_back(
          line_to({p.start}, fmt::format("gap between {} and {}", q[k - 1].entity, p.entity)));
      ++bridges;
    }
    if (p.spline) {
      // Each polynomial cubic piece as the uniform B-spline span that is the
      // same curve; each rational one as the rational cubic Bézier it is.
      for (std::size_t i = 0; i < p.beziers.size(); ++i) {
        const BezierSpan& z = p.beziers[i];
        SegmentSpec s;
        if (z.rational) {
          s.kind = SegmentKind::RationalBezier;
          s.points.assign(z.points.begin(), z.points.end());
          s.weights = z.weights;
        } else {
          s.kind = SegmentKind::QuasiBSpline;
          const std::array<Vec2, 4> b = bspline_span_of(z.points);
          s.points.assign(b.begin(), b.end());
        }
        s.declared = Continuity::G0;
        s.name = p.beziers.size() == 1 ? p.entity : fmt::format("{} piece {}", p.entity, i + 1);
        spec.segments.push_back(std::move(s));
      }
      continue;
    }
    SegmentSpec s;
    s.kind = SegmentKind::EllipseArc;
    s.ellipse = p.ellipse;
    s.declared = Continuity::G0;
    s.name = p.entity;
    spec.segments.push_back(s);
  }
  if ((n > 1 || q.front().spline) && exact(q.back()) && exact(q.front()) &&
      (q.back().end - q.front().start).norm() > bridge) {
    spec.segments.push_back(
        line_to({q.front().start}, fmt::format("gap between {} and {}", q.back().entity, q.front().entity)));
    ++bridges;
  }
  return spec;
}

// The loops the open pieces make, by following each end to its partner:
// ends 2k and 2k + 1 are open[k]'s start and end. \throw InputError
std::vector<std::vector<DxfPiece>> walk(const std::vector<DxfPiece>& pieces,
                                        const std::vector<std::size_t>& open,
                                        const std::vector<std::size_t>& partner, const std::string& where,
                                        std::vector<std::size_t>& first) {
  std::vector<std::vector<DxfPiece>> chains;
  std::vector<bool> used(open.size(), false);
  for (std::size_t k = 0; k < open.size(); ++k) {
    if (used[k]) continue;
    std::vector<DxfPiece> chain;
    std::size_t cur = k;
    bool forward = true;
    for (std::size_t steps = 0; steps <= open.size(); ++steps) {
      used[cur] = true;
      chain.push_back(oriented(pieces[open[cur]], forward));
      const std::size_t next_end = partner[2 * cur + (forward ? 1 : 0)];
      const std::size_t next = next_end / 2;
      const bool next_forward = next_end % 2 == 0;  // entered at its start
      if (next == k && next_forward) break;         // back where the loop began
      if (used[next]) {
        throw InputError(fmt::format("{}: {} meets {} twice; the entities do not make a loop", where,
                                     pieces[open[cur]].entity, pieces[open[next]].entity));
      }
      cur = next;
      forward = next_forward;
    }
    chains.push_back(std::move(chain));
    first.push_back(open[k]);
  }
  return chains;
}

}  // namespace

DxfChains chain_pieces(const std::vector<DxfPiece>& pieces, double max_gap, double extent,
                       const std::string& where) {
  const double join = std::max(max_gap, 1e-12 * extent);
  const double bridge = 1e-10 * extent;  // below the joints' own check (1e-9 of the curve's extent)
  DxfChains out;
  // Whole circles, ellipses and closed splines are loops by themselves; the rest is chained.
  std::vector<std::vector<DxfPiece>> chains;
  std::vector<std::size_t> first;  // each chain's first piece
  std::vector<std::size_t> open;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const DxfPiece& p = pieces[i];
    if (p.closed || (p.spline && (p.end - p.start).norm() <= join)) {
      chains.push_back({p});
      first.push_back(i);
    } else if (!p.arc && !p.spline && (p.end - p.start).norm() <= join) {
      ++out.skipped;  // a line no longer than the gap joined across: a point
    } else {
      open.push_back(i);
    }
  }
  std::vector<End> ends;
  ends.reserve(2 * open.size());
  for (const std::size_t i : open) {
    ends.push_back({i, false, pieces[i].start});
    ends.push_back({i, true, pieces[i].end});
  }
  const std::vector<std::size_t> partner =
      match_ends(ends, pieces, join, std::max(join, 1e-9 * extent), where, max_gap);
  for (std::vector<DxfPiece>& chain : walk(pieces, open, partner, where, first))
    chains.push_back(std::move(chain));

  std::vector<std::size_t> order(chains.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return pieces[first[a]].order < pieces[first[b]].order;
  });
  for (const std::size_t i : order) {
    out.loops.push_back(loop_spec(chains[i], bridge, out.bridges));
    out.first_entities.push_back(pieces[first[i]].entity);
  }
  return out;
}

}  // namespace fabmesh
