// Arcs fitted to a tool path's G1 stretches: the proven bound against
// dense measurement both ways, tangent continuity, and the refusals.

#include "geometry/toolpath/arc_fit.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "geometry/toolpath/toolpath.h"
#include "tests/geometry/section/region_shapes.h"
#include "tests/geometry/toolpath/digitised_worktop.h"

using namespace fabmesh;
using namespace fabmesh::test;

namespace {

double distance_to_piece(const PathPiece& p, const Vec2& q) {
  if (p.kind == PieceKind::Line) {
    const Vec2 d = p.to - p.from;
    const double len2 = d.squaredNorm();
    const double t = len2 == 0.0 ? 0.0 : std::clamp((q - p.from).dot(d) / len2, 0.0, 1.0);
    return (p.from + t * d - q).norm();
  }
  // Dense enough for a measurement: the nearest of many points, refined by the circle where on the arc.
  double best = std::min((q - p.from).norm(), (q - p.to).norm());
  const double a0 = std::atan2(p.from.y() - p.center.y(), p.from.x() - p.center.x());
  const double aq = std::atan2(q.y() - p.center.y(), q.x() - p.center.x());
  double turn = p.sweep >= 0.0 ? aq - a0 : a0 - aq;
  turn = std::fmod(turn + 4.0 * M_PI, 2.0 * M_PI);
  if (turn <= std::abs(p.sweep)) best = std::min(best, std::abs((q - p.center).norm() - piece_radius(p)));
  return best;
}

double distance_to_path(const std::vector<PathPiece>& path, const Vec2& q) {
  double best = INFINITY;
  for (const PathPiece& p : path) best = std::min(best, distance_to_piece(p, q));
  return best;
}

// The largest distance from points of `a`, every `step` along it, to `b`.
double one_way(const std::vector<PathPiece>& a, const std::vector<PathPiece>& b, double step) {
  double worst = 0.0;
  for (const PathPiece& p : a) {
    const double len = piece_length(p);
    const int n = std::max(1, static_cast<int>(std::ceil(len / step)));
    for (int k = 0; k <= n; ++k) worst = std::max(worst, distance_to_path(b, piece_point(p, len * k / n)));
  }
  return worst;
}

// A digitised stretch: points on a circle arc of radius R about c, every `spacing`, each pushed
// off the circle by a deterministic wobble of amplitude `noise`, as the lines between them.
std::vector<PathPiece> digitised_arc(const Vec2& c, double R, double from, double to, double spacing,
                                     double noise) {
  const int n = static_cast<int>(std::ceil(std::abs(to - from) * R / spacing));
  std::vector<Vec2> pts;
  for (int k = 0; k <= n; ++k) {
    const double a = from + (to - from) * k / n;
    const double rr = R + (k == 0 || k == n ? 0.0 : noise * std::sin(12.9898 * k) * std::cos(4.1414 * k));
    pts.emplace_back(c + rr * Vec2(std::cos(a), std::sin(a)));
  }
  std::vector<PathPiece> out;
  for (std::size_t k = 0; k + 1 < pts.size(); ++k)
    out.push_back(line_piece(pts[k], pts[k + 1], PieceRole::Offset, 0));
  return out;
}

}  // namespace

TEST_CASE("arc fit: a digitised arc becomes a few arcs within the proven bound, measured both ways",
          "[geometry][toolpath][arcfit]") {
  for (double noise : {0.0, 0.002, 0.004}) {
    INFO("noise " << noise);
    const std::vector<PathPiece> chain = digitised_arc(Vec2(0, 0), 1900, 0.2, 0.9, 5.0, noise);
    ArcFitOptions o;
    o.tolerance = 0.0125;
    o.max_radius = 6e4;
    const ArcFitResult fit = fit_arcs(chain, o);
    CHECK(fit.replaced > 0);
    CHECK(fit.pieces.size() < chain.size() / 4);
    CHECK(fit.deviation <= o.tolerance);
    CHECK(fit.arcs + fit.lines + (chain.size() - fit.replaced) == fit.pieces.size());
    // The ends stay, the pieces join end to end.
    CHECK(fit.pieces.front().from == chain.front().from);
    CHECK(fit.pieces.back().to == chain.back().to);
    for (std::size_t k = 1; k < fit.pieces.size(); ++k) CHECK(fit.pieces[k].from == fit.pieces[k - 1].to);
    // Measured both ways, every 0.05 along each: within the proven bound.
    const double measured = std::max(one_way(chain, fit.pieces, 0.05), one_way(fit.pieces, chain, 0.05));
    CHECK(measured <= fit.deviation + 1e-9);
    // Tangent continuity: fitted arcs meet with one tangent, and keep the chain's at its ends.
    for (std::size_t k = 1; k < fit.pieces.size(); ++k) {
      const PathPiece& a = fit.pieces[k - 1];
      const PathPiece& b = fit.pieces[k];
      if (a.kind != PieceKind::Arc || b.kind != PieceKind::Arc) continue;
      CHECK(cross2(piece_tangent(a, piece_length(a)), piece_tangent(b, 0.0)) == Approx(0.0).margin(1e-9));
    }
    CHECK(piece_tangent(fit.pieces.front(), 0.0).isApprox(piece_tangent(chain.front(), 0.0), 1e-12));
    const PathPiece& last = fit.pieces.back();
    CHECK(piece_tangent(last, piece_length(last))
              .isApprox(piece_tangent(chain.back(), piece_length(chain.back())), 1e-9));
  }
}

TEST_CASE("arc fit: the bound is exact for a chord and refuses chains that turn back or wind the other way",
          "[geometry][toolpath][arcfit]") {
  // A quarter circle of radius 10 against its chord: the sagitta 10 (1 - cos 45 deg).
  const PathPiece arc = arc_piece(Vec2(0, 0), Vec2(10, 0), M_PI / 2, PieceRole::Offset, 0);
  const std::vector<PathPiece> chord{line_piece(Vec2(10, 0), Vec2(0, 10), PieceRole::Offset, 0)};
  CHECK(fit_deviation(arc, chord) == Approx(10 * (1 - std::cos(M_PI / 4))).epsilon(1e-9));
  // Against two chords through a point off the circle: the larger of the point's offset and the sagittas.
  const Vec2 mid = 10.5 * Vec2(std::cos(M_PI / 4), std::sin(M_PI / 4));
  const std::vector<PathPiece> two{line_piece(Vec2(10, 0), mid, PieceRole::Offset, 0),
                                   line_piece(mid, Vec2(0, 10), PieceRole::Offset, 0)};
  // (the first chord passes 10 - 9.4485 from the circle at its foot, more than the point's 0.5)
  const Vec2 d = (mid - Vec2(10, 0)).normalized();
  const double foot = std::abs(cross2(Vec2(10, 0), d));
  CHECK(fit_deviation(arc, two) == Approx(std::max(0.5, 10 - foot)).epsilon(1e-9));
  // A chain that steps back along the arc is refused however close it stays.
  const Vec2 p1 = 10 * Vec2(std::cos(0.6), std::sin(0.6)), p2 = 10 * Vec2(std::cos(0.5), std::sin(0.5));
  const std::vector<PathPiece> back{line_piece(Vec2(10, 0), p1, PieceRole::Offset, 0),
                                    line_piece(p1, p2, PieceRole::Offset, 0),
                                    line_piece(p2, Vec2(0, 10), PieceRole::Offset, 0)};
  CHECK(fit_deviation(arc, back) == INFINITY);
  // The arc the other way round (three quarters clockwise) does not match the chord's span.
  const PathPiece other = arc_piece(Vec2(0, 0), Vec2(10, 0), -1.5 * M_PI, PieceRole::Offset, 0);
  CHECK(fit_deviation(other, chord) == INFINITY);
  // A line fitted to a zig-zag: the largest offset, 0.3.
  const PathPiece line = line_piece(Vec2(0, 0), Vec2(10, 0), PieceRole::Offset, 0);
  const std::vector<PathPiece> zig{line_piece(Vec2(0, 0), Vec2(3, 0.3), PieceRole::Offset, 0),
                                   line_piece(Vec2(3, 0.3), Vec2(6, -0.2), PieceRole::Offset, 0),
                                   line_piece(Vec2(6, -0.2), Vec2(10, 0), PieceRole::Offset, 0)};
  CHECK(fit_deviation(line, zig) == Approx(0.3).epsilon(1e-9));
}

TEST_CASE("arc fit: exact arcs and real corners stay, the tool's arcs round digitised points go",
          "[geometry][toolpath][arcfit]") {
  // A digitised convex stretch (the tool's small arcs round each point) between two real corners.
  std::vector<PathPiece> path;
  path.push_back(line_piece(Vec2(-100, 0), Vec2(0, 0), PieceRole::Offset, 0));
  path.push_back(arc_piece(Vec2(0, -6), Vec2(0, 0), -M_PI / 2, PieceRole::Corner, 1));  // a real corner
  Vec2 at = path.back().to;
  for (int k = 0; k < 60; ++k) {  // points 5 apart turning 1 degree each: lines and 1-degree arcs
    const double a = -1.0 * M_PI / 180.0;
    const Vec2 dir = piece_tangent(path.back(), piece_length(path.back()));
    path.push_back(line_piece(at, at + 5.0 * dir, PieceRole::Offset, 2));
    at = path.back().to;
    const Vec2 right(dir.y(), -dir.x());  // turning right round the corner point, 6 to the right
    path.push_back(arc_piece(at + 6.0 * right, at, a, PieceRole::Corner, 2));
    at = path.back().to;
  }
  const std::size_t before = path.size();
  ArcFitOptions o;
  o.tolerance = 0.01;
  const ArcFitResult fit = fit_arcs(path, o);
  CHECK(fit.replaced >= before - 3);
  CHECK(fit.arcs <= 10);
  CHECK(fit.pieces[0].kind == PieceKind::Line);
  CHECK(fit.pieces[1].role == PieceRole::Corner);  // the real corner stays
  CHECK(piece_radius(fit.pieces[1]) == Approx(6));
  const std::vector<PathPiece> stretch(path.begin() + 2, path.end());
  const std::vector<PathPiece> fitted(fit.pieces.begin() + 2, fit.pieces.end());
  CHECK(std::max(one_way(stretch, fitted, 0.05), one_way(fitted, stretch, 0.05)) <= fit.deviation + 1e-9);
  CHECK(fit.deviation <= o.tolerance);
}

TEST_CASE("arc fit: a digitised worktop is cut in arcs, within the tolerance, tabs and lengths consistent",
          "[geometry][toolpath][arcfit][digitised]") {
  // The worktop of the digitised test in toolpath_test.cpp: a concave front of radius 19 m by 301
  // points, convex back corners of radius 100 by 41 points each.
  const std::vector<Vec2> p = digitised_worktop_points();
  const CompositeCurve outline = polygon(p);
  CncOptions o;
  o.tolerance = 0.05;
  o.arc_fit = false;
  const Toolpath plain = plan_toolpath(outline, {}, o);
  o.arc_fit = true;
  const Toolpath fitted = plan_toolpath(outline, {}, o);
  const LoopPath& a = plain.loops[0];
  const LoopPath& b = fitted.loops[0];
  CHECK(a.fit_replaced == 0);
  CHECK(b.fit_replaced > 300);
  CHECK(b.pieces.size() < a.pieces.size() / 10);
  CHECK(b.fit_arcs == fitted.fit_arcs);
  CHECK(fitted.fit_deviation <= 0.5 * o.tolerance);
  CHECK(fitted.deviation <= 0.5 * o.tolerance);
  CHECK(b.length == Approx(a.length).margin(0.05));
  // Same tabs, same lead, the same clearance standard.
  CHECK(b.tabs.size() == 4);
  CHECK(fitted.warnings.empty());
  REQUIRE(b.lead);
  CHECK(b.lead->from.isApprox(a.lead->from, 1e-9));
  CHECK(fitted.clearance >= 0.5 * o.tool_diameter - o.tolerance);
  // Measured both ways against the unfitted path, every 0.05: within the proven fit.
  const double measured = std::max(one_way(a.pieces, b.pieces, 0.05), one_way(b.pieces, a.pieces, 0.05));
  CHECK(measured <= b.fit_deviation + 1e-9);
  // The cutting length estimate follows the fitted path.
  CHECK(toolpath_totals(fitted).cutting == Approx(toolpath_totals(plain).cutting).margin(0.05 * 3 * 2));
  // The share is reported.
  bool share = false;
  for (const ToleranceShare& s : fitted.tolerance_shares) {
    if (s.stage == "tool path chords and fitted arcs")
      share = s.given == Approx(0.5 * o.tolerance) && s.used <= s.given;
  }
  CHECK(share);
}
