#include "geometry/toolpath/loop_path.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "geometry/core/errors.h"
#include "geometry/toolpath/arc_fit.h"
#include "geometry/toolpath/offset_segment.h"

namespace fabmesh {
namespace {

using Pieces = std::vector<PathPiece>;

std::string at(const Vec2& p) { return fmt::format("({:.6g}, {:.6g})", p.x(), p.y()); }

const LoopCorner* corner_after(const std::vector<LoopCorner>& corners, std::size_t before) {
  for (const LoopCorner& c : corners) {
    if (c.before == before) return &c;
  }
  return nullptr;
}

// Distance from p to a piece, or a lower bound of it (arcs: the distance to their circle).
double distance_lower_bound(const Vec2& p, const PathPiece& piece) {
  if (piece.kind == PieceKind::Arc) return std::abs((p - piece.center).norm() - piece_radius(piece));
  const Vec2 d = piece.to - piece.from;
  const double len2 = d.squaredNorm();
  const double t = len2 == 0.0 ? 0.0 : std::clamp((p - piece.from).dot(d) / len2, 0.0, 1.0);
  return (piece.from + t * d - p).norm();
}

struct Trim {
  std::size_t ia = 0, ib = 0;
  double ua = 0.0, ub = 0.0, cost = INFINITY;
  Vec2 where{0.0, 0.0};
};

// The crossing of the tail of `a` with the head of `b` nearest to the corner
// (least path cut away on both sides), among pieces near the corner.
Trim find_trim(const Pieces& a, const Pieces& b, const LoopCorner& c, double r) {
  const double deflection = std::min(std::abs(c.turn), 3.0);
  const double reach = r * (2.0 / std::cos(0.5 * deflection) + std::tan(0.5 * deflection) + 1.0);
  std::vector<double> cum_a{0.0}, cum_b{0.0};
  for (const PathPiece& p : a) cum_a.push_back(cum_a.back() + piece_length(p));
  for (const PathPiece& p : b) cum_b.push_back(cum_b.back() + piece_length(p));
  Trim best;
  for (std::size_t ia = a.size(); ia-- > 0;) {
    if (distance_lower_bound(c.at, a[ia]) > reach) continue;
    for (std::size_t ib = 0; ib < b.size(); ++ib) {
      if (distance_lower_bound(c.at, b[ib]) > reach) continue;
      for (const PieceCrossing& x : piece_crossings(a[ia], b[ib])) {
        const double cost = (cum_a.back() - cum_a[ia] - x.u_first) + (cum_b[ib] + x.u_second);
        if (cost < best.cost) best = {ia, ib, x.u_first, x.u_second, cost, x.where};
      }
    }
  }
  return best;
}

// Cuts `a` after and `b` before their crossing; returns the crossing point.
Vec2 apply_trim(Pieces& a, Pieces& b, const Trim& t) {
  const double eps = 1e-12;
  Pieces na(a.begin(), a.begin() + static_cast<std::ptrdiff_t>(t.ia));
  const double la = piece_length(a[t.ia]);
  if (t.ua > eps * (1.0 + la)) na.push_back(t.ua >= la ? a[t.ia] : split_piece(a[t.ia], t.ua).first);
  Pieces nb;
  const double lb = piece_length(b[t.ib]);
  if (t.ub < lb - eps * (1.0 + lb)) nb.push_back(t.ub <= 0.0 ? b[t.ib] : split_piece(b[t.ib], t.ub).second);
  nb.insert(nb.end(), b.begin() + static_cast<std::ptrdiff_t>(t.ib) + 1, b.end());
  a = std::move(na);
  b = std::move(nb);
  if (!a.empty()) a.back().to = t.where;
  if (!b.empty()) b.front().from = t.where;
  return t.where;
}

// What goes between the offsets of two consecutive segments (travel order).
Pieces joint_pieces(Pieces& before, Pieces& after, const LoopCorner* corner, bool shallow,
                    std::size_t after_segment, const CutCurve& loop, double r) {
  const Vec2 end = before.back().to;
  if (!corner) {  // smooth: the offsets meet (up to the joint's tiny gap)
    if ((after.front().from - end).norm() <= 1e-6 * r) {
      after.front().from = end;
      return {};
    }
    return {line_piece(end, after.front().from, PieceRole::Link, after_segment)};
  }
  if (corner->turn > 0.0 && corner->turn < M_PI) {  // convex: an arc of the tool radius about the corner
    PathPiece arc = arc_piece(corner->at, end, corner->turn, PieceRole::Corner, after_segment);
    arc.to = after.front().from;
    return {arc};
  }
  const Trim t = find_trim(before, after, *corner, r);
  if (t.cost == INFINITY) {
    throw GeometryError(loop.label,
                        fmt::format("{}: at the concave corner {} the tool paths of {} and {} do not "
                                    "meet (a segment shorter than the tool needs)",
                                    loop.label, at(corner->at), segment_name(*loop.curve, corner->before),
                                    segment_name(*loop.curve, corner->after)));
  }
  const Vec2 x = apply_trim(before, after, t);
  if (before.empty() || after.empty()) {
    throw GeometryError(loop.label,
                        fmt::format("{}: near the concave corner {} a segment is shorter than the "
                                    "tool needs (its tool path vanishes)",
                                    loop.label, at(corner->at)));
  }
  if (shallow) return {};                                         // cut through: the offsets meet at x
  const Vec2 d = corner->at + r * (x - corner->at).normalized();  // the disc touches the corner point
  PathPiece in = line_piece(x, d, PieceRole::Dogbone, after_segment);
  PathPiece out = line_piece(d, x, PieceRole::Dogbone, after_segment);
  in.radius_of_curvature = out.radius_of_curvature = 0.0;
  return {in, out};
}

// Distance from the start of the longest run of flat pieces to its middle
// (or the middle of the flattest piece when no run is flat enough).
double choose_start(const Pieces& pieces, double gentle) {
  const std::size_t n = pieces.size();
  auto flat = [&](std::size_t i) {
    return pieces[i].role == PieceRole::Offset && pieces[i].radius_of_curvature >= gentle;
  };
  std::vector<double> cum{0.0};
  for (const PathPiece& p : pieces) cum.push_back(cum.back() + piece_length(p));
  // Runs may wrap around the end: start scanning after a piece that is not flat.
  std::size_t first = n;
  for (std::size_t i = 0; i < n; ++i) {
    if (!flat(i)) {
      first = (i + 1) % n;
      break;
    }
  }
  if (first == n) return 0.5 * cum.back();  // all flat
  double best_len = 0.0, best_mid = -1.0, run_len = 0.0, run_start = cum[first];
  for (std::size_t k = 0; k <= n; ++k) {
    const std::size_t i = (first + k) % n;
    if (k < n && flat(i)) {
      if (run_len == 0.0) run_start = cum[i];
      run_len += piece_length(pieces[i]);
      continue;
    }
    if (run_len > best_len) best_len = run_len, best_mid = std::fmod(run_start + 0.5 * run_len, cum.back());
    run_len = 0.0;
  }
  if (best_mid >= 0.0) return best_mid;
  std::size_t flattest = 0;
  for (std::size_t i = 1; i < n; ++i) {
    if (pieces[i].radius_of_curvature > pieces[flattest].radius_of_curvature) flattest = i;
  }
  return cum[flattest] + 0.5 * piece_length(pieces[flattest]);
}

// The closed chain re-started at distance u.

}  // namespace

std::vector<PathPiece> rotate_path(const std::vector<PathPiece>& pieces, double u) {
  double acc = 0.0;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const double len = piece_length(pieces[i]);
    if (u > acc + len && i + 1 < pieces.size()) {
      acc += len;
      continue;
    }
    const double local = std::clamp(u - acc, 0.0, len);
    std::vector<PathPiece> out;
    const bool split = local > 1e-9 * len && local < len * (1 - 1e-9);
    const std::size_t next = split ? i + 1 : (local >= 0.5 * len ? i + 1 : i);
    if (split) out.push_back(split_piece(pieces[i], local).second);
    for (std::size_t k = 0; k < pieces.size(); ++k) {
      const std::size_t j = (next + k) % pieces.size();
      if (split && j == i) break;
      out.push_back(pieces[j]);
    }
    if (split) out.push_back(split_piece(pieces[i], local).first);
    return out;
  }
  return pieces;
}

double nearest_along(const std::vector<PathPiece>& pieces, const Vec2& q) {
  double best = std::numeric_limits<double>::infinity(), best_u = 0.0, u0 = 0.0;
  for (const PathPiece& p : pieces) {
    const double len = piece_length(p);
    std::vector<double> candidates{0.0, len};
    if (p.kind == PieceKind::Line) {
      const Vec2 d = p.to - p.from;
      if (d.squaredNorm() > 0.0)
        candidates.push_back(std::clamp((q - p.from).dot(d) / d.squaredNorm(), 0.0, 1.0) * len);
    } else {
      // The turn from the arc's start to q's direction, in the arc's own sense.
      const double a0 = std::atan2(p.from.y() - p.center.y(), p.from.x() - p.center.x());
      const double aq = std::atan2(q.y() - p.center.y(), q.x() - p.center.x());
      double turn = p.sweep >= 0.0 ? aq - a0 : a0 - aq;
      turn = std::fmod(turn + 4.0 * M_PI, 2.0 * M_PI);
      if (turn <= std::abs(p.sweep)) candidates.push_back(turn * piece_radius(p));
    }
    for (const double s : candidates) {
      const double d = (piece_point(p, s) - q).norm();
      if (d < best) best = d, best_u = u0 + s;
    }
    u0 += len;
  }
  return best_u;
}

std::pair<Vec2, Vec2> path_point(const std::vector<PathPiece>& pieces, double u) {
  double acc = 0.0;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const double len = piece_length(pieces[i]);
    if (u <= acc + len || i + 1 == pieces.size()) {
      const double local = std::clamp(u - acc, 0.0, len);
      return {piece_point(pieces[i], local), piece_tangent(pieces[i], local)};
    }
    acc += len;
  }
  return {Vec2::Zero(), Vec2::UnitX()};
}

PathPiece lead_arc(const LoopPath& path, CutDirection direction, double radius) {
  const PathPiece& first = path.pieces.front();
  const Vec2 s = first.from, d = piece_tangent(first, 0.0);
  const Vec2 waste = direction == CutDirection::Conventional ? Vec2(d.y(), -d.x()) : Vec2(-d.y(), d.x());
  const Vec2 c = s + radius * waste;
  const Vec2 ccw_tangent(waste.y(), -waste.x());  // rot90ccw(-waste)
  const double sweep_in = ccw_tangent.dot(d) > 0.0 ? M_PI / 2 : -M_PI / 2;
  PathPiece lead = reversed(arc_piece(c, s, -sweep_in, PieceRole::Link, first.segment));
  lead.to = s;
  return lead;
}

LoopPath build_loop_path(const CutCurve& loop, const LoopCheck& check, const LoopPathOptions& o) {
  const CompositeCurve& curve = *loop.curve;
  const std::size_t n = curve.size();
  const double r = o.radius;
  SegmentOffsetOptions so;
  so.radius = r;
  so.tolerance = o.chain_tolerance;
  so.max_points = o.max_points;
  LoopPath out;
  out.label = loop.label;
  out.outer = loop.outer;
  std::vector<std::size_t> order(n);
  for (std::size_t k = 0; k < n; ++k) order[k] = loop.reversed ? n - 1 - k : k;
  std::vector<Pieces> offsets;
  for (std::size_t k = 0; k < n; ++k) {
    double achieved = 0.0;
    offsets.push_back(offset_segment(curve.segments()[order[k]], loop.reversed, order[k], so, &achieved));
    out.deviation = std::max(out.deviation, achieved);
  }
  std::vector<Pieces> joints(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t next = (k + 1) % n;
    // The curve joint after segment `before` (curve order) is this travel joint.
    const std::size_t before = loop.reversed ? order[next] : order[k];
    const LoopCorner* corner = corner_after(check.convex_corners, before);
    if (!corner) corner = corner_after(check.concave_corners, before);
    const LoopCorner* shallow = corner ? nullptr : corner_after(check.shallow_corners, before);
    joints[k] = joint_pieces(offsets[k], offsets[next], corner ? corner : shallow, shallow != nullptr,
                             order[next], loop, r);
  }
  Pieces pieces;
  for (std::size_t k = 0; k < n; ++k) {
    for (const PathPiece& p : offsets[k]) {
      if (piece_length(p) > 1e-12 * r) pieces.push_back(p);
    }
    pieces.insert(pieces.end(), joints[k].begin(), joints[k].end());
  }
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    PathPiece& next = pieces[(i + 1) % pieces.size()];
    if ((next.from - pieces[i].to).norm() > 1e-6 * r) {
      throw std::logic_error(fmt::format("{}: the tool path has a gap of {} at {}", loop.label,
                                         (next.from - pieces[i].to).norm(), at(pieces[i].to)));
    }
    next.from = pieces[i].to;
  }
  if (o.direction == CutDirection::Climb) {
    std::reverse(pieces.begin(), pieces.end());
    for (PathPiece& p : pieces) p = reversed(p);
  }
  out.pieces = rotate_path(pieces, choose_start(pieces, o.gentle_radius));
  out.chord_deviation = out.deviation;
  if (o.arc_fit_tolerance > out.chord_deviation) {
    ArcFitOptions fo;
    fo.tolerance = o.arc_fit_tolerance - out.chord_deviation;  // what the chords left
    fo.max_radius = 1e4 * r;
    ArcFitResult fit = fit_arcs(out.pieces, fo);
    out.pieces = std::move(fit.pieces);
    out.fit_replaced = fit.replaced;
    out.fit_arcs = fit.arcs;
    out.fit_lines = fit.lines;
    out.fit_deviation = fit.deviation;
    out.deviation += fit.deviation;  // the chords' bound plus the fit's: a triangle inequality
  }
  out.length = path_length(out.pieces);
  return out;
}

}  // namespace fabmesh
