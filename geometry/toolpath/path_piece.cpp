#include "geometry/toolpath/path_piece.h"

#include <algorithm>
#include <cmath>

namespace fabmesh {
namespace {

constexpr double kTwoPi = 2.0 * M_PI;

Vec2 unit_at(double angle) { return Vec2(std::cos(angle), std::sin(angle)); }

double start_angle(const PathPiece& p) {
  return std::atan2(p.from.y() - p.center.y(), p.from.x() - p.center.x());
}

// Distance along an arc from its start to the point of the circle at `angle`,
// or nullopt when that point is not on the arc (with a relative slack).
std::optional<double> arc_position(const PathPiece& p, double angle) {
  const double a0 = start_angle(p);
  double delta = p.sweep >= 0.0 ? angle - a0 : a0 - angle;
  delta = std::fmod(delta, kTwoPi);
  if (delta < 0.0) delta += kTwoPi;
  const double span = std::abs(p.sweep);
  const double slack = 1e-12 * kTwoPi;
  if (delta > span + slack) {
    if (delta > kTwoPi - slack) return 0.0;  // just before the start
    return std::nullopt;
  }
  return piece_radius(p) * std::min(delta, span);
}

// Points where the line through a (direction d, unit) meets the circle (c, r): parameters along d.
std::vector<double> line_circle(const Vec2& a, const Vec2& d, const Vec2& c, double r) {
  const Vec2 ac = a - c;
  const double b = ac.dot(d);
  const double disc = b * b - (ac.squaredNorm() - r * r);
  if (disc < 0.0) return {};
  const double s = std::sqrt(disc);
  if (s == 0.0) return {-b};
  return {-b - s, -b + s};
}

std::vector<PieceCrossing> line_line(const PathPiece& a, const PathPiece& b) {
  const Vec2 da = a.to - a.from, db = b.to - b.from;
  const double den = cross2(da, db);
  if (den == 0.0) return {};
  const Vec2 w = b.from - a.from;
  const double ta = cross2(w, db) / den, tb = cross2(w, da) / den;
  const double slack = 1e-12;
  if (ta < -slack || ta > 1 + slack || tb < -slack || tb > 1 + slack) return {};
  const double la = da.norm(), lb = db.norm();
  const double ua = std::clamp(ta, 0.0, 1.0) * la, ub = std::clamp(tb, 0.0, 1.0) * lb;
  return {{ua, ub, a.from + std::clamp(ta, 0.0, 1.0) * da}};
}

std::vector<PieceCrossing> line_arc(const PathPiece& line, const PathPiece& arc, bool swap) {
  const double len = piece_length(line);
  if (len == 0.0) return {};
  const Vec2 d = (line.to - line.from) / len;
  std::vector<PieceCrossing> out;
  for (double t : line_circle(line.from, d, arc.center, piece_radius(arc))) {
    if (t < -1e-12 * len || t > len * (1 + 1e-12)) continue;
    const Vec2 q = line.from + std::clamp(t, 0.0, len) * d;
    const auto u = arc_position(arc, std::atan2(q.y() - arc.center.y(), q.x() - arc.center.x()));
    if (!u) continue;
    const double ul = std::clamp(t, 0.0, len);
    out.push_back(swap ? PieceCrossing{*u, ul, q} : PieceCrossing{ul, *u, q});
  }
  return out;
}

std::vector<PieceCrossing> arc_arc(const PathPiece& a, const PathPiece& b) {
  const double ra = piece_radius(a), rb = piece_radius(b);
  const Vec2 d = b.center - a.center;
  const double dist = d.norm();
  if (dist == 0.0 || dist > ra + rb || dist < std::abs(ra - rb)) return {};
  const double x = (dist * dist + ra * ra - rb * rb) / (2 * dist);
  const double h = std::sqrt(std::max(0.0, ra * ra - x * x));
  const Vec2 e = d / dist, n(-e.y(), e.x());
  std::vector<PieceCrossing> out;
  for (double sign : {-1.0, 1.0}) {
    const Vec2 q = a.center + x * e + sign * h * n;
    const auto ua = arc_position(a, std::atan2(q.y() - a.center.y(), q.x() - a.center.x()));
    const auto ub = arc_position(b, std::atan2(q.y() - b.center.y(), q.x() - b.center.x()));
    if (ua && ub) out.push_back({*ua, *ub, q});
    if (h == 0.0) break;
  }
  return out;
}

}  // namespace

const char* to_string(PieceRole role) {
  switch (role) {
    case PieceRole::Offset:
      return "offset";
    case PieceRole::Corner:
      return "corner";
    case PieceRole::Dogbone:
      return "dogbone";
    case PieceRole::Link:
      return "link";
  }
  return "offset";
}

PathPiece line_piece(const Vec2& from, const Vec2& to, PieceRole role, std::size_t segment) {
  PathPiece p;
  p.kind = PieceKind::Line;
  p.from = from;
  p.to = to;
  p.role = role;
  p.segment = segment;
  return p;
}

PathPiece arc_piece(const Vec2& center, const Vec2& from, double sweep, PieceRole role, std::size_t segment) {
  PathPiece p;
  p.kind = PieceKind::Arc;
  p.center = center;
  p.from = from;
  p.sweep = sweep;
  p.role = role;
  p.segment = segment;
  const double r = (from - center).norm();
  p.to = center + r * unit_at(start_angle(p) + sweep);
  p.radius_of_curvature = r;
  return p;
}

double piece_radius(const PathPiece& p) { return (p.from - p.center).norm(); }

double piece_length(const PathPiece& p) {
  return p.kind == PieceKind::Line ? (p.to - p.from).norm() : piece_radius(p) * std::abs(p.sweep);
}

Vec2 piece_point(const PathPiece& p, double u) {
  const double len = piece_length(p);
  if (len == 0.0) return p.from;
  if (u >= len) return p.to;
  if (u <= 0.0) return p.from;
  if (p.kind == PieceKind::Line) return p.from + (p.to - p.from) * (u / len);
  return p.center + piece_radius(p) * unit_at(start_angle(p) + p.sweep * (u / len));
}

Vec2 piece_tangent(const PathPiece& p, double u) {
  if (p.kind == PieceKind::Line) return (p.to - p.from).normalized();
  const Vec2 radial = (piece_point(p, u) - p.center).normalized();
  return p.sweep >= 0.0 ? Vec2(-radial.y(), radial.x()) : Vec2(radial.y(), -radial.x());
}

std::pair<PathPiece, PathPiece> split_piece(const PathPiece& p, double u) {
  const Vec2 mid = piece_point(p, u);
  PathPiece a = p, b = p;
  a.to = mid;
  b.from = mid;
  if (p.kind == PieceKind::Arc) {
    const double f = u / piece_length(p);
    a.sweep = p.sweep * f;
    b.sweep = p.sweep - a.sweep;
  }
  return {a, b};
}

PathPiece reversed(const PathPiece& p) {
  PathPiece r = p;
  std::swap(r.from, r.to);
  r.sweep = -p.sweep;
  return r;
}

std::vector<Vec2> piece_polyline(const PathPiece& p, double sagitta) {
  if (p.kind == PieceKind::Line) return {p.from, p.to};
  const double r = piece_radius(p);
  // A chord spanning angle phi stays within r (1 - cos(phi / 2)) of its arc.
  const double phi = sagitta >= r ? M_PI / 2 : std::min(M_PI / 2, 2.0 * std::acos(1.0 - sagitta / r));
  const int n = std::max(1, static_cast<int>(std::ceil(std::abs(p.sweep) / phi)));
  std::vector<Vec2> out{p.from};
  const double a0 = start_angle(p);
  for (int i = 1; i < n; ++i) out.push_back(p.center + r * unit_at(a0 + p.sweep * i / n));
  out.push_back(p.to);
  return out;
}

std::vector<PieceCrossing> piece_crossings(const PathPiece& a, const PathPiece& b) {
  if (a.kind == PieceKind::Line && b.kind == PieceKind::Line) return line_line(a, b);
  if (a.kind == PieceKind::Line) return line_arc(a, b, false);
  if (b.kind == PieceKind::Line) return line_arc(b, a, true);
  return arc_arc(a, b);
}

double path_length(const std::vector<PathPiece>& pieces) {
  double total = 0.0;
  for (const PathPiece& p : pieces) total += piece_length(p);
  return total;
}

}  // namespace fabmesh
