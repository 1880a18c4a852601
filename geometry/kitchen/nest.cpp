#include "geometry/kitchen/nest.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>
#include <CGAL/squared_distance_2.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>

#include "geometry/core/errors.h"

namespace fabmesh {
namespace {

// Exact constructions for the verification (squared distances of the written
// coordinates); exact predicates on doubles for the search.
using Exact = CGAL::Exact_predicates_exact_constructions_kernel;
using ExactFT = Exact::FT;
using ExactPoint = Exact::Point_2;
using ExactSegment = Exact::Segment_2;
using Fast = CGAL::Exact_predicates_inexact_constructions_kernel;
using FastPoint = Fast::Point_2;
using FastSegment = Fast::Segment_2;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 2, std::size_t>;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::array<int, 4> kQuarterTurns = {0, 90, 180, 270};

std::string num(double v) { return fmt::format("{:.12g}", v); }
std::string at(const Vec2& p) { return fmt::format("({}, {})", num(p.x()), num(p.y())); }
std::string count(std::size_t n, const char* one, const char* many) {
  return fmt::format("{} {}", n, n == 1 ? one : many);
}

// "piece-2", or "piece 2 (unnamed)" for a piece without a name.
std::string label(const std::vector<NestPiece>& pieces, std::size_t i) {
  return pieces[i].name.empty() ? fmt::format("piece {} (unnamed)", i + 1) : pieces[i].name;
}

std::string defect_label(const SlabStock& stock, std::size_t d) {
  const SlabDefect& defect = stock.defects[d];
  if (defect.radius > 0.0) {
    return fmt::format("defect {} (a circle of radius {} at {})", d + 1, num(defect.radius),
                       at(defect.center));
  }
  return fmt::format("defect {} (a polygon of {})", d + 1, count(defect.polygon.size(), "point", "points"));
}

bool finite(const Vec2& p) { return std::isfinite(p.x()) && std::isfinite(p.y()); }

// Twice the signed area (shoelace), halved.
double area_of(const std::vector<Vec2>& p) {
  double a = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) a += cross2(p[i], p[(i + 1) % p.size()]);
  return 0.5 * a;
}

// An axis-aligned box [x0, x1] x [y0, y1].
struct Bounds {
  double x0 = kInf;
  double y0 = kInf;
  double x1 = -kInf;
  double y1 = -kInf;
};

Bounds bounds_of(const std::vector<Vec2>& points) {
  Bounds b;
  for (const Vec2& p : points) {
    b.x0 = std::min(b.x0, p.x());
    b.y0 = std::min(b.y0, p.y());
    b.x1 = std::max(b.x1, p.x());
    b.y1 = std::max(b.y1, p.y());
  }
  return b;
}

Bounds edge_bounds(const Vec2& a, const Vec2& b) {
  return {std::min(a.x(), b.x()), std::min(a.y(), b.y()), std::max(a.x(), b.x()), std::max(a.y(), b.y())};
}

// `b` grown by `by` on every side, rounded outward: it holds every point
// within `by` of `b`.
Bounds grown(const Bounds& b, double by) {
  return {std::nextafter(b.x0 - by, -kInf), std::nextafter(b.y0 - by, -kInf), std::nextafter(b.x1 + by, kInf),
          std::nextafter(b.y1 + by, kInf)};
}

bool meet(const Bounds& a, const Bounds& b) {
  return a.x0 <= b.x1 && b.x0 <= a.x1 && a.y0 <= b.y1 && b.y0 <= a.y1;
}

// Whether everything at or beyond `hi` is far enough from everything at or
// before `lo` along one axis, exactly: hi - lo >= spacing, or hi > lo for a
// spacing of 0 (touching is not allowed either).
bool gap_ok(double lo, double hi, double spacing) {
  if (spacing > 0.0) return ExactFT(hi) - ExactFT(lo) >= ExactFT(spacing);
  return hi > lo;
}

// The boxes alone prove that their contents are at least `spacing` apart.
bool boxes_apart(const Bounds& a, const Bounds& b, double spacing) {
  return gap_ok(a.x1, b.x0, spacing) || gap_ok(b.x1, a.x0, spacing) || gap_ok(a.y1, b.y0, spacing) ||
         gap_ok(b.y1, a.y0, spacing);
}

// The least double c (up to an ulp) with gap_ok(lo, c, spacing): where the
// next thing may start after something ending at `lo`.
double next_start(double lo, double spacing) {
  double c = lo + spacing;
  while (!gap_ok(lo, c, spacing)) c = std::nextafter(c, kInf);
  return c;
}

// An offset o with low + o >= target in doubles, as small as rounding allows.
double offset_for(double low, double target) {
  double o = target - low;
  while (low + o < target) o = std::nextafter(o, kInf);
  return o;
}

ExactPoint exact(const Vec2& p) { return ExactPoint(p.x(), p.y()); }
FastPoint fast(const Vec2& p) { return FastPoint(p.x(), p.y()); }

double point_segment_d2(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double length2 = d.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((p - a).dot(d) / length2, 0.0, 1.0) : 0.0;
  return (p - (a + t * d)).squaredNorm();
}

// Far above the rounding error of point_segment_d2's distance (a few ulps of
// the coordinates): within it of the limit, the exact test decides.
double tolerance(double scale) { return 1e-9 * (1.0 + scale); }

double magnitude(const Vec2& p) { return std::max(std::abs(p.x()), std::abs(p.y())); }

// Segments [a0, a1] and [b0, b1] do not meet and are at least `spacing`
// apart: decided in doubles where that is certain, exactly otherwise.
bool segments_clear(const Vec2& a0, const Vec2& a1, const Vec2& b0, const Vec2& b1, double spacing) {
  if (CGAL::do_intersect(FastSegment(fast(a0), fast(a1)), FastSegment(fast(b0), fast(b1)))) return false;
  if (spacing == 0.0) return true;
  const double d = std::sqrt(std::min({point_segment_d2(a0, b0, b1), point_segment_d2(a1, b0, b1),
                                       point_segment_d2(b0, a0, a1), point_segment_d2(b1, a0, a1)}));
  const double tol =
      tolerance(std::max({magnitude(a0), magnitude(a1), magnitude(b0), magnitude(b1), spacing}));
  if (d > spacing + tol) return true;
  if (d < spacing - tol) return false;
  const ExactFT s(spacing);
  return CGAL::squared_distance(ExactSegment(exact(a0), exact(a1)), ExactSegment(exact(b0), exact(b1))) >=
         s * s;
}

// Segment [a, b] is at least `reach` from `center`, the same way.
bool segment_clear_of_point(const Vec2& a, const Vec2& b, const Vec2& center, double radius, double spacing) {
  const double reach = radius + spacing;
  const double d = std::sqrt(point_segment_d2(center, a, b));
  const double tol = tolerance(std::max({magnitude(a), magnitude(b), magnitude(center), reach}));
  if (d > reach + tol) return true;
  if (d < reach - tol) return false;
  const ExactFT r = ExactFT(radius) + ExactFT(spacing);
  return CGAL::squared_distance(ExactSegment(exact(a), exact(b)), exact(center)) >= r * r;
}

// A closed loop in slab coordinates, ready for the search's tests.
struct Outline {
  std::vector<Vec2> points;
  std::vector<FastPoint> fast;
  Bounds box;
};

Outline outline_of(std::vector<Vec2> points) {
  Outline o;
  o.fast.reserve(points.size());
  for (const Vec2& p : points) o.fast.push_back(fast(p));
  o.box = bounds_of(points);
  o.points = std::move(points);
  return o;
}

bool inside(const std::vector<FastPoint>& loop, const Vec2& p) {
  return CGAL::bounded_side_2(loop.begin(), loop.end(), fast(p), Fast()) != CGAL::ON_UNBOUNDED_SIDE;
}

// The edges of `o` whose boxes meet `near`.
std::vector<std::size_t> edges_meeting(const Outline& o, const Bounds& near) {
  std::vector<std::size_t> edges;
  const std::size_t n = o.points.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (meet(edge_bounds(o.points[i], o.points[(i + 1) % n]), near)) edges.push_back(i);
  }
  return edges;
}

// The search's test of two loops: at least `spacing` apart, neither inside
// the other. Edges are tested only where their boxes come within `spacing`.
bool loops_clear(const Outline& a, const Outline& b, double spacing) {
  if (boxes_apart(a.box, b.box, spacing)) return true;
  const std::vector<std::size_t> ea = edges_meeting(a, grown(b.box, spacing));
  const std::vector<std::size_t> eb = edges_meeting(b, grown(a.box, spacing));
  const std::size_t na = a.points.size();
  const std::size_t nb = b.points.size();
  std::vector<Bounds> eb_boxes;
  eb_boxes.reserve(eb.size());
  for (const std::size_t j : eb) eb_boxes.push_back(edge_bounds(b.points[j], b.points[(j + 1) % nb]));
  for (const std::size_t i : ea) {
    const Vec2& a0 = a.points[i];
    const Vec2& a1 = a.points[(i + 1) % na];
    const Bounds near = grown(edge_bounds(a0, a1), spacing);
    for (std::size_t k = 0; k < eb.size(); ++k) {
      if (!meet(near, eb_boxes[k])) continue;
      if (!segments_clear(a0, a1, b.points[eb[k]], b.points[(eb[k] + 1) % nb], spacing)) return false;
    }
  }
  // No edges meet: the loops are apart unless one holds the other.
  return !inside(a.fast, b.points.front()) && !inside(b.fast, a.points.front());
}

// A defect as the search sees it.
struct Obstacle {
  bool circle = false;
  Vec2 center{0.0, 0.0};
  double radius = 0.0;
  Outline outline;  // the polygon, or just the circle's box
};

bool clear_of(const Outline& piece, const Obstacle& obstacle, double spacing) {
  if (!obstacle.circle) return loops_clear(piece, obstacle.outline, spacing);
  if (boxes_apart(piece.box, obstacle.outline.box, spacing)) return true;
  const std::size_t n = piece.points.size();
  const Bounds near = grown(obstacle.outline.box, spacing);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& a = piece.points[i];
    const Vec2& b = piece.points[(i + 1) % n];
    if (!meet(edge_bounds(a, b), near)) continue;
    if (!segment_clear_of_point(a, b, obstacle.center, obstacle.radius, spacing)) return false;
  }
  return !inside(piece.fast, obstacle.center);
}

void require_stock(const SlabStock& stock) {
  for (const auto& [key, value] : {std::pair<const char*, double>{"slab.length", stock.length},
                                   {"slab.width", stock.width},
                                   {"slab.margin", stock.margin},
                                   {"slab.spacing", stock.spacing}}) {
    if (!std::isfinite(value)) {
      throw RangeError(key, value, fmt::format("{} = {} is not a finite number", key, value),
                       ErrorLocation{key});
    }
  }
  if (stock.margin < 0.0) {
    throw RangeError("slab.margin", stock.margin,
                     fmt::format("slab.margin = {} must be >= 0", num(stock.margin)),
                     ErrorLocation{"slab.margin"});
  }
  if (!(stock.length - 2.0 * stock.margin > 0.0) || !(stock.width - 2.0 * stock.margin > 0.0)) {
    throw RangeError("slab.margin", stock.margin,
                     fmt::format("slab.margin = {} leaves no usable area on a {} x {} slab",
                                 num(stock.margin), num(stock.length), num(stock.width)),
                     ErrorLocation{"slab.margin"});
  }
  if (stock.spacing < 0.0) {
    throw RangeError("slab.spacing", stock.spacing,
                     fmt::format("slab.spacing = {} must be >= 0", num(stock.spacing)),
                     ErrorLocation{"slab.spacing"});
  }
  for (std::size_t d = 0; d < stock.defects.size(); ++d) {
    const SlabDefect& defect = stock.defects[d];
    const std::string key = fmt::format("slab.defects[{}]", d);
    const bool points_finite = std::all_of(defect.polygon.begin(), defect.polygon.end(), finite);
    if (!finite(defect.center) || !std::isfinite(defect.radius) || !points_finite) {
      throw GeometryError(key, fmt::format("{} has a coordinate that is not a finite number", key));
    }
    if (defect.radius < 0.0) {
      throw GeometryError(key, fmt::format("{} has a negative radius {}", key, num(defect.radius)));
    }
    if (defect.radius > 0.0 && !defect.polygon.empty()) {
      throw GeometryError(key,
                          fmt::format("{} gives both a radius and a polygon; a defect is one of them", key));
    }
    if (defect.radius == 0.0 && defect.polygon.size() < 3) {
      throw GeometryError(key, fmt::format("{} is neither a circle (radius > 0) nor a polygon of at least 3 "
                                           "points (it has {})",
                                           key, defect.polygon.size()));
    }
  }
}

void require_pieces(const std::vector<NestPiece>& pieces) {
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const auto& outer = pieces[i].outer;
    if (outer.size() < 3) {
      throw GeometryError("slab", fmt::format("{} has {} to place; its outer loop needs at least 3",
                                              label(pieces, i), count(outer.size(), "point", "points")));
    }
    if (!std::all_of(outer.begin(), outer.end(), finite)) {
      throw GeometryError("slab",
                          fmt::format("{} has a coordinate that is not a finite number", label(pieces, i)));
    }
  }
}

std::vector<Obstacle> obstacles_of(const SlabStock& stock) {
  std::vector<Obstacle> out;
  for (const SlabDefect& d : stock.defects) {
    Obstacle o;
    if (d.radius > 0.0) {
      o.circle = true;
      o.center = d.center;
      o.radius = d.radius;
      o.outline.box = grown(Bounds{d.center.x(), d.center.y(), d.center.x(), d.center.y()}, d.radius);
    } else {
      o.outline = outline_of(d.polygon);
    }
    out.push_back(std::move(o));
  }
  return out;
}

// A piece in one allowed turn, about the origin.
struct Turned {
  int rotation = 0;
  std::vector<Vec2> points;
  Bounds box;
};

struct Item {
  std::size_t piece = 0;
  double area = 0.0;
  std::vector<Turned> turns;
};

// The turns the grain allows: the design box's long side along x (0 or 180
// degrees when it is at least as wide as tall, else 90 or 270), or all four.
std::vector<int> allowed_turns(const std::vector<Vec2>& outer, bool grain_along) {
  if (!grain_along) return {kQuarterTurns.begin(), kQuarterTurns.end()};
  const Bounds b = bounds_of(outer);
  if (b.x1 - b.x0 >= b.y1 - b.y0) return {0, 180};
  return {90, 270};
}

// The usable rectangle's far sides, exactly: length - margin, width - margin.
struct Usable {
  double margin = 0.0;
  ExactFT x1;
  ExactFT y1;
};

bool within(const Bounds& b, const Usable& u) {
  return b.x0 >= u.margin && b.y0 >= u.margin && ExactFT(b.x1) <= u.x1 && ExactFT(b.y1) <= u.y1;
}

// The placement of `t` with its box's lower-left corner at (x, y) (or an ulp
// beyond), as place_point writes it.
Placement place_at(const Item& item, const Turned& t, double x, double y, std::size_t slab,
                   const std::vector<Vec2>& design) {
  Placement p;
  p.piece = item.piece;
  p.slab = slab;
  p.rotation_deg = t.rotation;
  p.offset = Vec2(offset_for(t.box.x0, x), offset_for(t.box.y0, y));
  p.outer.reserve(design.size());
  for (const Vec2& q : design) p.outer.push_back(place_point(q, t.rotation, p.offset));
  return p;
}

struct SlabState {
  std::vector<Outline> placed;
  double area = 0.0;  // of the pieces on it
};

// The first feasible placement of `item` on `slab` (lowest y, then x, then
// turn), or nullopt.
std::optional<Placement> first_fit(const Item& item, const std::vector<Vec2>& design, const SlabState& slab,
                                   std::size_t slab_index, const std::vector<Obstacle>& obstacles,
                                   const SlabStock& stock, const Usable& usable) {
  std::vector<double> xs = {stock.margin};
  std::vector<double> ys = {stock.margin};
  const auto add = [&](const Bounds& b) {
    xs.push_back(next_start(b.x1, stock.spacing));
    ys.push_back(next_start(b.y1, stock.spacing));
  };
  for (const Obstacle& o : obstacles) add(o.outline.box);
  for (const Outline& o : slab.placed) add(o.box);
  for (auto* v : {&xs, &ys}) {
    std::sort(v->begin(), v->end());
    v->erase(std::unique(v->begin(), v->end()), v->end());
  }
  const double far_x = stock.length - stock.margin;
  const double far_y = stock.width - stock.margin;
  const double slack = tolerance(std::max(std::abs(stock.length), std::abs(stock.width)));
  for (const double y : ys) {
    if (y < stock.margin) continue;
    for (const double x : xs) {
      if (x < stock.margin) continue;
      for (const Turned& t : item.turns) {
        if (x + (t.box.x1 - t.box.x0) > far_x + slack || y + (t.box.y1 - t.box.y0) > far_y + slack) continue;
        Placement p = place_at(item, t, x, y, slab_index, design);
        const Outline candidate = outline_of(p.outer);
        if (!within(candidate.box, usable)) continue;
        const bool clear =
            std::all_of(slab.placed.begin(), slab.placed.end(),
                        [&](const Outline& o) { return loops_clear(candidate, o, stock.spacing); }) &&
            std::all_of(obstacles.begin(), obstacles.end(),
                        [&](const Obstacle& o) { return clear_of(candidate, o, stock.spacing); });
        if (clear) return p;
      }
    }
  }
  return std::nullopt;
}

[[noreturn]] void throw_too_large(const std::vector<NestPiece>& pieces, std::size_t i, const Item& item,
                                  const SlabStock& stock) {
  const double uw = stock.length - 2.0 * stock.margin;
  const double uh = stock.width - 2.0 * stock.margin;
  const Bounds& b = item.turns.front().box;
  const std::string size = fmt::format("{} x {}", num(b.x1 - b.x0), num(b.y1 - b.y0));
  if (stock.grain_along) {
    throw GeometryError("slab",
                        fmt::format("{} is {} after turning for the grain; a slab's usable area is {} x {}",
                                    label(pieces, i), size, num(uw), num(uh)));
  }
  throw GeometryError("slab",
                      fmt::format("{} is {} and fits in no quarter turn; a slab's usable area is {} x {}",
                                  label(pieces, i), size, num(uw), num(uh)));
}

// --- verification -----------------------------------------------------------

// A placed loop with its exact points.
struct Checked {
  const std::vector<Vec2>* points = nullptr;
  std::vector<ExactPoint> exact;
  Bounds box;
  std::string name;
};

Checked checked_of(const std::vector<Vec2>& points, std::string name) {
  Checked c;
  c.points = &points;
  c.exact.reserve(points.size());
  for (const Vec2& p : points) c.exact.push_back(exact(p));
  c.box = bounds_of(points);
  c.name = std::move(name);
  return c;
}

ExactSegment exact_edge(const Checked& c, std::size_t i) {
  return ExactSegment(c.exact[i], c.exact[(i + 1) % c.exact.size()]);
}

// Throws unless `a` and `b` are at least `spacing` apart exactly (no edges
// meet, no pair of edges nearer) and neither lies inside the other. Edge
// pairs are found by box intersection (a's edge boxes grown by the spacing).
void require_apart(const Checked& a, const Checked& b, double spacing, std::size_t slab) {
  if (boxes_apart(a.box, b.box, spacing)) return;
  const auto& pa = *a.points;
  const auto& pb = *b.points;
  std::vector<Box> boxes_a;
  std::vector<Box> boxes_b;
  const Bounds near_b = grown(b.box, spacing);
  const Bounds near_a = grown(a.box, spacing);
  for (std::size_t i = 0; i < pa.size(); ++i) {
    const Bounds e = edge_bounds(pa[i], pa[(i + 1) % pa.size()]);
    if (!meet(e, near_b)) continue;
    const Bounds g = grown(e, spacing);
    std::array<double, 2> lo = {g.x0, g.y0};
    std::array<double, 2> hi = {g.x1, g.y1};
    boxes_a.emplace_back(lo.data(), hi.data(), i);
  }
  for (std::size_t j = 0; j < pb.size(); ++j) {
    const Bounds e = edge_bounds(pb[j], pb[(j + 1) % pb.size()]);
    if (!meet(e, near_a)) continue;
    std::array<double, 2> lo = {e.x0, e.y0};
    std::array<double, 2> hi = {e.x1, e.y1};
    boxes_b.emplace_back(lo.data(), hi.data(), j);
  }
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  CGAL::box_intersection_d(boxes_a.begin(), boxes_a.end(), boxes_b.begin(), boxes_b.end(),
                           [&](const Box& x, const Box& y) { pairs.emplace_back(x.info(), y.info()); });
  std::sort(pairs.begin(), pairs.end());
  const ExactFT s(spacing);
  const ExactFT s2 = s * s;
  for (const auto& [i, j] : pairs) {
    const ExactSegment ea = exact_edge(a, i);
    const ExactSegment eb = exact_edge(b, j);
    if (CGAL::do_intersect(ea, eb)) {
      throw GeometryError("slab",
                          fmt::format("slab {}: {} and {} overlap: edge {} of {} (from {}) meets edge {} of "
                                      "{} (from {})",
                                      slab + 1, a.name, b.name, i, a.name, at(pa[i]), j, b.name, at(pb[j])));
    }
    const ExactFT d2 = CGAL::squared_distance(ea, eb);
    if (d2 < s2) {
      throw GeometryError(
          "slab", fmt::format("slab {}: {} and {} are {} apart (edge {} of {} from {}, edge {} of {} "
                              "from {}), less than the spacing {}",
                              slab + 1, a.name, b.name, num(std::sqrt(CGAL::to_double(d2))), i, a.name,
                              at(pa[i]), j, b.name, at(pb[j]), num(spacing)));
    }
  }
  const auto holds = [](const Checked& outer, const Checked& in) {
    return CGAL::bounded_side_2(outer.exact.begin(), outer.exact.end(), in.exact.front(), Exact()) !=
           CGAL::ON_UNBOUNDED_SIDE;
  };
  for (const auto& [outer, in] : {std::pair<const Checked*, const Checked*>{&a, &b}, {&b, &a}}) {
    if (holds(*outer, *in)) {
      throw GeometryError("slab", fmt::format("slab {}: {} lies inside {} (its point {})", slab + 1, in->name,
                                              outer->name, at(in->points->front())));
    }
  }
}

void require_clear_of_circle(const Checked& c, const SlabDefect& defect, const std::string& defect_name,
                             double spacing, std::size_t slab) {
  const Bounds near =
      grown(grown(Bounds{defect.center.x(), defect.center.y(), defect.center.x(), defect.center.y()},
                  defect.radius),
            spacing);
  if (!meet(c.box, near)) return;
  const ExactPoint center = exact(defect.center);
  const ExactFT reach = ExactFT(defect.radius) + ExactFT(spacing);
  const ExactFT reach2 = reach * reach;
  const auto& pts = *c.points;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (!meet(edge_bounds(pts[i], pts[(i + 1) % pts.size()]), near)) continue;
    const ExactFT d2 = CGAL::squared_distance(exact_edge(c, i), center);
    if (d2 < reach2) {
      throw GeometryError("slab",
                          fmt::format("slab {}: {} comes within {} of the centre of {} (edge {} from {}); it "
                                      "must keep the radius plus the spacing {}",
                                      slab + 1, c.name, num(std::sqrt(CGAL::to_double(d2))), defect_name, i,
                                      at(pts[i]), num(spacing)));
    }
  }
  if (CGAL::bounded_side_2(c.exact.begin(), c.exact.end(), center, Exact()) != CGAL::ON_UNBOUNDED_SIDE) {
    throw GeometryError("slab", fmt::format("slab {}: {} lies inside {}", slab + 1, defect_name, c.name));
  }
}

}  // namespace

Vec2 place_point(const Vec2& p, int rotation_deg, const Vec2& offset) {
  switch (rotation_deg) {
    case 0:
      return Vec2(p.x() + offset.x(), p.y() + offset.y());
    case 90:
      return Vec2(-p.y() + offset.x(), p.x() + offset.y());
    case 180:
      return Vec2(-p.x() + offset.x(), -p.y() + offset.y());
    case 270:
      return Vec2(p.y() + offset.x(), -p.x() + offset.y());
    default:
      throw RangeError(
          "rotation_deg", rotation_deg,
          fmt::format("rotation_deg = {} is not a quarter turn (0, 90, 180 or 270)", rotation_deg),
          ErrorLocation{"rotation_deg"});
  }
}

std::vector<Vec2> place_loop(const std::vector<Vec2>& loop, const Placement& at) {
  std::vector<Vec2> placed;
  placed.reserve(loop.size());
  for (const Vec2& q : loop) placed.push_back(place_point(q, at.rotation_deg, at.offset));
  return placed;
}

SlabNesting nest_pieces(const std::vector<NestPiece>& pieces, const SlabStock& stock) {
  require_stock(stock);
  require_pieces(pieces);
  const Usable usable{stock.margin, ExactFT(stock.length) - ExactFT(stock.margin),
                      ExactFT(stock.width) - ExactFT(stock.margin)};
  const double usable_area = (stock.length - 2.0 * stock.margin) * (stock.width - 2.0 * stock.margin);
  const std::vector<Obstacle> obstacles = obstacles_of(stock);

  std::vector<Item> items;
  items.reserve(pieces.size());
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    Item item;
    item.piece = i;
    item.area = std::abs(area_of(pieces[i].outer));
    for (const int r : allowed_turns(pieces[i].outer, stock.grain_along)) {
      Turned t;
      t.rotation = r;
      for (const Vec2& q : pieces[i].outer) t.points.push_back(place_point(q, r, Vec2(0.0, 0.0)));
      t.box = bounds_of(t.points);
      item.turns.push_back(std::move(t));
    }
    // Fits an empty slab's usable rectangle in some turn (defects aside)?
    const bool fits = std::any_of(item.turns.begin(), item.turns.end(), [&](const Turned& t) {
      const Placement p = place_at(item, t, stock.margin, stock.margin, 0, pieces[i].outer);
      return within(bounds_of(p.outer), usable);
    });
    if (!fits) throw_too_large(pieces, i, item, stock);
    items.push_back(std::move(item));
  }
  std::sort(items.begin(), items.end(), [](const Item& a, const Item& b) {
    return a.area > b.area || (a.area == b.area && a.piece < b.piece);
  });

  SlabNesting out;
  out.placements.resize(pieces.size());
  std::vector<SlabState> slabs;
  for (const Item& item : items) {
    const auto& design = pieces[item.piece].outer;
    std::optional<Placement> found;
    for (std::size_t s = 0; s <= slabs.size() && !found; ++s) {
      const bool fresh = s == slabs.size();
      if (fresh) slabs.emplace_back();
      // No room left by area alone: skip the slab (the pieces cannot overlap).
      if (!fresh && item.area > usable_area - slabs[s].area + tolerance(usable_area)) continue;
      found = first_fit(item, design, slabs[s], s, obstacles, stock, usable);
      if (!found && fresh) {
        const Bounds& b = item.turns.front().box;
        throw GeometryError(
            "slab", fmt::format("{} ({} x {}) fits on no empty slab at least {} clear of its {}",
                                label(pieces, item.piece), num(b.x1 - b.x0), num(b.y1 - b.y0),
                                num(stock.spacing), count(stock.defects.size(), "defect", "defects")));
      }
    }
    slabs[found->slab].placed.push_back(outline_of(found->outer));
    slabs[found->slab].area += item.area;
    out.placements[item.piece] = std::move(*found);
  }

  out.slabs = slabs.size();
  double total = 0.0;
  for (const SlabState& s : slabs) {
    total += s.area;
    out.utilisation.push_back(std::clamp(s.area / usable_area, 0.0, 1.0));
  }
  if (total > 0.0) {
    // The least k with k slabs' usable area >= the pieces' area.
    auto k = static_cast<std::size_t>(std::ceil(total / usable_area));
    while (k > 1 && static_cast<double>(k - 1) * usable_area >= total) --k;
    while (static_cast<double>(k) * usable_area < total) ++k;
    out.lower_bound = k;
  }
  try {
    out.proof = verify_nesting(pieces, stock, out.placements);
  } catch (const GeometryError& e) {
    throw std::logic_error(
        fmt::format("nest_pieces made a layout that fails its verification: {}", e.what()));
  }
  return out;
}

std::string verify_nesting(const std::vector<NestPiece>& pieces, const SlabStock& stock,
                           const std::vector<Placement>& placements) {
  require_stock(stock);
  require_pieces(pieces);
  if (placements.size() != pieces.size()) {
    throw GeometryError(
        "slab", fmt::format("the layout has {} for {}", count(placements.size(), "placement", "placements"),
                            count(pieces.size(), "piece", "pieces")));
  }
  std::vector<bool> seen(pieces.size(), false);
  std::size_t slab_count = 0;
  for (std::size_t k = 0; k < placements.size(); ++k) {
    const Placement& p = placements[k];
    if (p.piece >= pieces.size()) {
      throw GeometryError("slab", fmt::format("placement {} names piece {}, but there are {}", k, p.piece,
                                              count(pieces.size(), "piece", "pieces")));
    }
    const std::string name = label(pieces, p.piece);
    if (seen[p.piece]) throw GeometryError("slab", fmt::format("{} is placed twice", name));
    seen[p.piece] = true;
    if (p.slab >= pieces.size()) {
      throw GeometryError("slab", fmt::format("{} is on slab {}, but {} never need more than {}", name,
                                              p.slab + 1, count(pieces.size(), "piece", "pieces"),
                                              count(pieces.size(), "slab", "slabs")));
    }
    slab_count = std::max(slab_count, p.slab + 1);
    if (std::find(kQuarterTurns.begin(), kQuarterTurns.end(), p.rotation_deg) == kQuarterTurns.end()) {
      throw GeometryError("slab", fmt::format("slab {}: {} is turned {} degrees, not a quarter turn",
                                              p.slab + 1, name, p.rotation_deg));
    }
    const auto& design = pieces[p.piece].outer;
    if (p.outer.size() != design.size()) {
      throw GeometryError("slab", fmt::format("slab {}: {}'s placed loop has {}, its design {}", p.slab + 1,
                                              name, count(p.outer.size(), "point", "points"), design.size()));
    }
    for (std::size_t i = 0; i < design.size(); ++i) {
      if (!finite(p.outer[i])) {
        throw GeometryError("slab",
                            fmt::format("slab {}: {}'s placed point {} is not finite", p.slab + 1, name, i));
      }
      const Vec2 expected = place_point(design[i], p.rotation_deg, p.offset);
      if (!(p.outer[i].x() == expected.x() && p.outer[i].y() == expected.y())) {
        throw GeometryError("slab",
                            fmt::format("slab {}: {}'s placed point {} is {}, not its design point {} turned "
                                        "{} degrees and moved by {} (which is {})",
                                        p.slab + 1, name, i, at(p.outer[i]), at(design[i]), p.rotation_deg,
                                        at(p.offset), at(expected)));
      }
    }
  }

  const Usable usable{stock.margin, ExactFT(stock.length) - ExactFT(stock.margin),
                      ExactFT(stock.width) - ExactFT(stock.margin)};
  const ExactFT margin(stock.margin);
  std::vector<std::vector<Checked>> by_slab(slab_count);
  for (std::size_t k = 0; k < placements.size(); ++k) {
    const Placement& p = placements[k];
    Checked c = checked_of(p.outer, label(pieces, p.piece));
    const Bounds& b = c.box;
    if (!(ExactFT(b.x0) >= margin && ExactFT(b.y0) >= margin && ExactFT(b.x1) <= usable.x1 &&
          ExactFT(b.y1) <= usable.y1)) {
      throw GeometryError(
          "slab", fmt::format("slab {}: {} reaches outside the usable area [{}, {}] x [{}, {}] (it spans "
                              "[{}, {}] x [{}, {}])",
                              p.slab + 1, c.name, num(stock.margin), num(stock.length - stock.margin),
                              num(stock.margin), num(stock.width - stock.margin), num(b.x0), num(b.x1),
                              num(b.y0), num(b.y1)));
    }
    by_slab[p.slab].push_back(std::move(c));
  }

  std::vector<Checked> defects;
  for (std::size_t d = 0; d < stock.defects.size(); ++d) {
    defects.push_back(checked_of(stock.defects[d].polygon, defect_label(stock, d)));
  }
  for (std::size_t s = 0; s < by_slab.size(); ++s) {
    const auto& on = by_slab[s];
    for (std::size_t i = 0; i < on.size(); ++i) {
      for (std::size_t j = i + 1; j < on.size(); ++j) require_apart(on[i], on[j], stock.spacing, s);
      for (std::size_t d = 0; d < stock.defects.size(); ++d) {
        if (stock.defects[d].radius > 0.0) {
          require_clear_of_circle(on[i], stock.defects[d], defects[d].name, stock.spacing, s);
        } else {
          require_apart(on[i], defects[d], stock.spacing, s);
        }
      }
    }
  }
  return fmt::format(
      "verified exactly: {} on {} inside margins of {}, at least {} apart and clear of {} (CGAL "
      "exact predicates on the written coordinates)",
      count(pieces.size(), "piece", "pieces"), count(slab_count, "slab", "slabs"), num(stock.margin),
      num(stock.spacing), count(stock.defects.size(), "defect", "defects"));
}

}  // namespace fabmesh
