#include "geometry/kitchen/pieces.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>

#include "geometry/core/errors.h"
#include "geometry/section/simple_polygon.h"

namespace fabmesh {
namespace {

std::string at_text(const Vec2& p) { return fmt::format("({:.6g}, {:.6g})", p.x(), p.y()); }

// Where the seam line crosses a piece's outer loop: at vertex `i`, or inside
// edge i (from vertex i to i + 1) at `p`; `s` is the position along the line.
struct Crossing {
  std::size_t i = 0;
  bool at_vertex = false;
  Vec2 p{0.0, 0.0};
  double s = 0.0;
  double along = std::numeric_limits<double>::quiet_NaN();  ///< on the exact outline
};

// A place where the loop passes from one side of the line to the other: a
// point, or a run of the loop along the line (from `lo` to `hi` along it).
struct Passage {
  Crossing lo, hi;
};

double segment_distance(const Vec2& a, const Vec2& b, const Vec2& p) {
  const Vec2 d = b - a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (a + t * d - p).norm();
}

bool segments_cross(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const int s1 = side_of_line(a, b, c), s2 = side_of_line(a, b, d);
  const int s3 = side_of_line(c, d, a), s4 = side_of_line(c, d, b);
  return s1 * s2 <= 0 && s3 * s4 <= 0;
}

// The least distance between the chord a-b and a closed loop (0 when they meet).
double chord_to_loop(const Vec2& a, const Vec2& b, const std::vector<Vec2>& loop) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < loop.size(); ++k) {
    const Vec2& c = loop[k];
    const Vec2& d = loop[(k + 1) % loop.size()];
    if (segments_cross(a, b, c, d)) return 0.0;
    best = std::min({best, segment_distance(c, d, a), segment_distance(c, d, b), segment_distance(a, b, c),
                     segment_distance(a, b, d)});
  }
  return best;
}

// Where the line through `at` along `dir` passes through `loop`, sorted
// along the line. A vertex on the line, or a run of the loop along it,
// counts when the loop goes on to the other side; one that touches the line
// and turns back does not.
std::vector<Passage> line_passages(const std::vector<Vec2>& loop, const Vec2& at, const Vec2& dir,
                                   const std::string& key) {
  const std::size_t n = loop.size();
  const Vec2 ahead = at + dir;
  std::vector<int> side(n);
  for (std::size_t k = 0; k < n; ++k) side[k] = side_of_line(at, ahead, loop[k]);
  const auto start = std::find_if(side.begin(), side.end(), [](int x) { return x != 0; });
  if (start == side.end()) {
    throw GeometryError(ErrorLocation{key}, fmt::format("{}: the whole top lies on the seam's line", key));
  }
  const Vec2 normal(-dir.y(), dir.x());
  auto along = [&](std::size_t k) { return Crossing{k, true, loop[k], (loop[k] - at).dot(dir)}; };
  std::vector<Passage> out;
  const std::size_t first = static_cast<std::size_t>(start - side.begin());
  for (std::size_t step = 0; step < n; ++step) {
    const std::size_t k = (first + step) % n;
    if (side[k] == 0) continue;
    std::size_t next = (k + 1) % n;
    if (side[next] != 0) {
      if (side[next] == side[k]) continue;
      const double dk = normal.dot(loop[k] - at), dn = normal.dot(loop[next] - at);
      const double t = std::clamp(dk / (dk - dn), 0.0, 1.0);
      Crossing c{k, false, loop[k] + t * (loop[next] - loop[k]), 0.0};
      if (c.p == loop[k] || c.p == loop[next]) c = along(c.p == loop[k] ? k : next);  // rounded onto a vertex
      c.s = (c.p - at).dot(dir);
      out.push_back({c, c});
      continue;
    }
    // A run of vertices on the line, from `next` on.
    Crossing lo = along(next), hi = lo;
    std::size_t j = next;
    while (side[j] == 0) {
      const Crossing c = along(j);
      if (c.s < lo.s) lo = c;
      if (c.s > hi.s) hi = c;
      j = (j + 1) % n;
    }
    if (side[j] != side[k]) out.push_back({lo, hi});
  }
  std::sort(out.begin(), out.end(), [](const Passage& x, const Passage& y) { return x.lo.s < y.lo.s; });
  return out;
}

// The part of `piece`'s outer loop from crossing a to crossing b (forward),
// closed by the chord b -> a, with its edges' kinds.
void walk(const KitchenPiece& piece, const Crossing& a, const Crossing& b, KitchenPiece& into) {
  const std::size_t n = piece.outer.size();
  into.outer = {a.p};
  into.along = {a.along};
  into.edges.clear();
  std::size_t last_edge = a.i;
  std::size_t k = (a.i + 1) % n;
  const std::size_t stop = b.at_vertex ? b.i : (b.i + 1) % n;
  while (k != stop) {
    into.edges.push_back(piece.edges[last_edge]);
    into.outer.push_back(piece.outer[k]);
    into.along.push_back(piece.along[k]);
    last_edge = k;
    k = (k + 1) % n;
  }
  into.edges.push_back(piece.edges[last_edge]);
  into.outer.push_back(b.p);
  into.along.push_back(b.along);
  into.edges.push_back(EdgeKind::Seam);
}

// Where the exact outline crosses the seam's line between the parameters of
// an edge's ends (which lie on the outline, on either side of the line):
// bisection to the last bit, along the shorter way round between them.
double exact_crossing(const CompositeCurve& outline, double ga, double gb, const Vec2& at, const Vec2& dir) {
  const double n = static_cast<double>(outline.size());
  double d = std::fmod(gb - ga + n, n);
  double from = ga, length = d;
  if (d > 0.5 * n) {  // the edge runs against the outline
    from = gb;
    length = n - d;
  }
  const Vec2 normal(-dir.y(), dir.x());
  auto side = [&](double t) {
    double g = from + t * length;
    if (g >= n) g -= n;
    return normal.dot(outline.point(g) - at);
  };
  double lo = 0.0, hi = 1.0;
  const double f_lo = side(lo);
  if (f_lo == 0.0) return from;
  for (int i = 0; i < 200 && hi - lo > 0.0; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    ((side(mid) > 0.0) == (f_lo > 0.0) ? lo : hi) = mid;
  }
  double g = from + 0.5 * (lo + hi) * length;
  if (g >= n) g -= n;
  return g;
}

// The outline's parameter of a crossing: a vertex's own, or the exact
// crossing between an edge's ends.
void set_along(Crossing& c, const KitchenPiece& piece, const Vec2& at, const Vec2& dir,
               const SplitOptions& options) {
  if (c.at_vertex) {
    c.along = piece.along[c.i];
    return;
  }
  const double ga = piece.along[c.i], gb = piece.along[(c.i + 1) % piece.along.size()];
  if (options.outline == nullptr || !std::isfinite(ga) || !std::isfinite(gb)) return;
  c.along = exact_crossing(*options.outline, ga, gb, at, dir);
}

double loop_area(const std::vector<Vec2>& loop) { return 0.5 * signed_area2(loop); }

void set_area(KitchenPiece& piece) {
  piece.area = loop_area(piece.outer);
  for (const auto& h : piece.holes) piece.area += loop_area(h);  // holes run clockwise
}

// Splits pieces[index] at the seam; returns the chord cut.
SeamCut split_piece(std::vector<KitchenPiece>& pieces, std::size_t index, const SeamSpec& seam,
                    const SplitOptions& options) {
  const KitchenPiece piece = pieces[index];
  const Vec2 dir = seam.direction.normalized();
  const std::vector<Passage> passages = line_passages(piece.outer, seam.at, dir, seam.key);
  const double slack = 2.0 * options.deviation + 1e-9 * (1.0 + seam.at.norm());
  // Inside the piece between passages 2k and 2k + 1: the chord runs from the
  // far end of the one to the near end of the other.
  const Crossing* a = nullptr;
  const Crossing* b = nullptr;
  for (std::size_t k = 0; k + 1 < passages.size(); k += 2) {
    if (passages[k].hi.s <= slack && passages[k + 1].lo.s >= -slack) {
      a = &passages[k].hi;
      b = &passages[k + 1].lo;
      break;
    }
  }
  if (a == nullptr) {
    throw GeometryError(ErrorLocation{seam.key + ".at", {}, {seam.at.x(), seam.at.y()}},
                        fmt::format("{}: the point {} is not on the top (or its line along ({:.6g}, {:.6g}) "
                                    "does not cross it there)",
                                    seam.key, at_text(seam.at), seam.direction.x(), seam.direction.y()));
  }
  SeamCut cut{a->p, b->p, seam.key, std::numeric_limits<double>::infinity()};
  Crossing from = *a, to = *b;
  set_along(from, piece, seam.at, dir, options);
  set_along(to, piece, seam.at, dir, options);
  KitchenPiece first, second;
  walk(piece, from, to, first);
  walk(piece, to, from, second);
  for (std::size_t h = 0; h < piece.holes.size(); ++h) {
    const std::size_t design_hole = piece.hole_index[h];
    const double gap = chord_to_loop(a->p, b->p, piece.holes[h]) - options.deviation;
    cut.clearance = std::min(cut.clearance, gap);
    if (gap < options.seam_clearance) {
      const std::string what = gap <= 0.0 ? fmt::format("runs through holes[{}]", design_hole)
                                          : fmt::format("passes {:.6g} from holes[{}]", gap, design_hole);
      throw GeometryError(ErrorLocation{seam.key, {}, {seam.at.x(), seam.at.y()}},
                          fmt::format("{}: the seam from {} to {} {}; seams keep seam_clearance = {:.6g} "
                                      "from every cut-out",
                                      seam.key, at_text(a->p), at_text(b->p), what, options.seam_clearance));
    }
    KitchenPiece& into = point_in_polygon(first.outer, piece.holes[h].front()) > 0 ? first : second;
    into.holes.push_back(piece.holes[h]);
    into.hole_index.push_back(design_hole);
  }
  set_area(first);
  set_area(second);
  for (const KitchenPiece* made : {&first, &second}) {
    std::vector<std::vector<Vec2>> loops{made->outer};
    loops.insert(loops.end(), made->holes.begin(), made->holes.end());
    if (const auto crossing = find_crossing(loops)) {
      throw GeometryError(
          ErrorLocation{seam.key, {}, {crossing->where.x(), crossing->where.y()}},
          fmt::format("{}: the seam from {} to {} leaves a piece that is not a simple polygon "
                      "near {} (too close to a corner or to another seam)",
                      seam.key, at_text(a->p), at_text(b->p), at_text(crossing->where)));
    }
  }
  const double scale = std::max(1.0, std::abs(piece.area));
  if (!(first.area > 1e-12 * scale && second.area > 1e-12 * scale)) {
    throw GeometryError(ErrorLocation{seam.key, {}, {seam.at.x(), seam.at.y()}},
                        fmt::format("{}: the seam from {} to {} leaves a piece of no area", seam.key,
                                    at_text(a->p), at_text(b->p)));
  }
  pieces[index] = std::move(first);
  pieces.insert(pieces.begin() + static_cast<std::ptrdiff_t>(index) + 1, std::move(second));
  return cut;
}

KitchenPiece whole_top(const Region2& region, const std::vector<EdgeKind>& kinds) {
  KitchenPiece top;
  top.outer = region.outer;
  top.edges = kinds.empty() ? std::vector<EdgeKind>(region.outer.size(), EdgeKind::Exposed) : kinds;
  top.along = region.outer_along;
  top.along.resize(region.outer.size(), std::numeric_limits<double>::quiet_NaN());
  top.holes = region.holes;
  top.hole_index.resize(region.holes.size());
  std::iota(top.hole_index.begin(), top.hole_index.end(), std::size_t{0});
  set_area(top);
  return top;
}

// Names the pieces in order of their lowest-leftmost point (a stable order a
// fabricator can follow on the drawing) and proves the partition.
KitchenSplit finish(std::vector<KitchenPiece> pieces, std::vector<SeamCut> seams, const Region2& region) {
  auto corner = [](const KitchenPiece& p) {
    return *std::min_element(p.outer.begin(), p.outer.end(), [](const Vec2& a, const Vec2& b) {
      return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
    });
  };
  std::stable_sort(pieces.begin(), pieces.end(), [&](const KitchenPiece& a, const KitchenPiece& b) {
    const Vec2 ca = corner(a), cb = corner(b);
    return ca.x() < cb.x() || (ca.x() == cb.x() && ca.y() < cb.y());
  });
  double total = 0.0;
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    pieces[k].name = fmt::format("piece-{}", k + 1);
    std::vector<std::vector<Vec2>> loops{pieces[k].outer};
    loops.insert(loops.end(), pieces[k].holes.begin(), pieces[k].holes.end());
    if (const auto crossing = find_crossing(loops)) {
      throw GeometryError(ErrorLocation{"seams", {}, {crossing->where.x(), crossing->where.y()}},
                          fmt::format("seams: {} is not a simple polygon near {} (a seam too close to a "
                                      "corner or to another seam)",
                                      pieces[k].name, at_text(crossing->where)));
    }
    total += pieces[k].area;
  }
  KitchenSplit out;
  out.proof = fmt::format(
      "{} pieces from {} seam{}: each seam a chord splitting one piece in two along a shared edge; every "
      "piece's loops simple (exact predicates); areas sum to the top's within {:.2g}",
      pieces.size(), seams.size(), seams.size() == 1 ? "" : "s", std::abs(total - region.area));
  out.pieces = std::move(pieces);
  out.seams = std::move(seams);
  return out;
}

std::size_t piece_containing(const std::vector<KitchenPiece>& pieces, const Vec2& p, double slack) {
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    if (point_in_polygon(pieces[k].outer, p) >= 0) return k;
  }
  // On the boundary within the sampling's deviation: the nearest piece.
  std::size_t best = pieces.size();
  double best_d = slack;
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const auto& o = pieces[k].outer;
    for (std::size_t e = 0; e < o.size(); ++e) {
      const double d = segment_distance(o[e], o[(e + 1) % o.size()], p);
      if (d <= best_d) {
        best_d = d;
        best = k;
      }
    }
  }
  return best;
}

struct Box2 {
  Vec2 lo, hi;
};

Box2 box_of(const std::vector<Vec2>& pts) {
  Box2 b{pts.front(), pts.front()};
  for (const Vec2& p : pts) {
    b.lo = b.lo.cwiseMin(p);
    b.hi = b.hi.cwiseMax(p);
  }
  return b;
}

// Whether the turn at outer[k] is an inside corner of 30 degrees or more.
bool is_inside_corner(const std::vector<Vec2>& o, std::size_t k) {
  const std::size_t n = o.size();
  const Vec2 in = o[k] - o[(k + n - 1) % n], out = o[(k + 1) % n] - o[k];
  if (in.norm() == 0.0 || out.norm() == 0.0) return false;
  return std::atan2(cross2(in, out), in.dot(out)) <= -M_PI / 6.0;
}

bool inside_corner(const KitchenPiece& piece) {
  for (std::size_t k = 0; k < piece.outer.size(); ++k) {
    if (is_inside_corner(piece.outer, k)) return true;
  }
  return false;
}

// Candidate seams for one piece that does not fit: butt joints at inside
// corners first, then straight cuts across its long and short sides.
std::vector<SeamSpec> candidates(const KitchenPiece& piece, const SlabFit& slab,
                                 const SplitOptions& options) {
  std::vector<SeamSpec> out;
  const auto& o = piece.outer;
  const std::size_t n = o.size();
  for (std::size_t k = 0; k < n; ++k) {
    if (!is_inside_corner(o, k)) continue;
    const Vec2 in = o[k] - o[(k + n - 1) % n], outd = o[(k + 1) % n] - o[k];
    out.push_back({o[k], in.normalized(), "seams (auto)"});
    out.push_back({o[k], outd.normalized(), "seams (auto)"});
  }
  const Box2 box = box_of(o);
  const Vec2 size = box.hi - box.lo;
  const double reach = std::max(slab.length, slab.width);
  for (int axis = 0; axis < 2; ++axis) {
    const double extent = size[axis];
    const double limit = extent >= size[1 - axis] ? (slab.grain_along ? slab.length : reach)
                                                  : (slab.grain_along ? slab.width : reach);
    if (extent <= limit) continue;
    // Forbidden bands around each cut-out, along this axis.
    std::vector<std::pair<double, double>> bands;
    const double keep = options.seam_clearance + options.deviation;
    for (const auto& h : piece.holes) {
      const Box2 hb = box_of(h);
      bands.emplace_back(hb.lo[axis] - keep, hb.hi[axis] + keep);
    }
    const double margin = 1e-6 * std::max(1.0, extent);
    // Balanced cuts first (pieces of equal length, no sliver left over),
    // then as far along as the slab allows, from either end; a cut that falls
    // in a cut-out's band moves out of it toward the end it is measured from.
    const double parts = std::ceil(extent / limit);
    const std::pair<double, bool> starts[] = {{box.lo[axis] + extent / parts, true},
                                              {box.hi[axis] - extent / parts, false},
                                              {box.lo[axis] + limit - margin, true},
                                              {box.hi[axis] - limit + margin, false}};
    for (const auto& [c0, from_low] : starts) {
      double c = c0;
      for (int guard = 0; guard < 64; ++guard) {
        bool moved = false;
        for (const auto& [lo, hi] : bands) {
          if (c > lo && c < hi) {
            c = from_low ? lo : hi;
            moved = true;
          }
        }
        if (!moved) break;
      }
      if (!(c > box.lo[axis] && c < box.hi[axis])) continue;
      Vec2 dir(0.0, 0.0);
      dir[1 - axis] = 1.0;
      // One candidate per chord of the line across the piece.
      Vec2 start = box.lo;
      start[axis] = c;
      std::vector<double> ts;
      for (std::size_t k = 0; k < n; ++k) {
        const Vec2& p = o[k];
        const Vec2& q = o[(k + 1) % n];
        if ((p[axis] - c) * (q[axis] - c) < 0.0) {
          const double t = (c - p[axis]) / (q[axis] - p[axis]);
          ts.push_back(p[1 - axis] + t * (q[1 - axis] - p[1 - axis]));
        }
      }
      std::sort(ts.begin(), ts.end());
      for (std::size_t k = 0; k + 1 < ts.size(); k += 2) {
        Vec2 mid = start;
        mid[1 - axis] = 0.5 * (ts[k] + ts[k + 1]);
        out.push_back({mid, dir, "seams (auto)"});
      }
    }
  }
  return out;
}

// Splits `pieces[index]` with at most `budget` seams so that every piece made
// fits; appends the seams and the pieces. false when it cannot.
struct Search {
  const Region2& region;
  const SlabFit& slab;
  const SplitOptions& options;
  std::size_t tries = 0;
};

// The most splits the search for the fewest seams tries before the greedy
// split takes over (it bounds the search's time on a large top).
constexpr std::size_t kSearchTries = 6000;

// Splits trial[0] at `seam` unless that fails (too near a cut-out, no chord
// there, not simple) or leaves a sliver: a piece less than seam_clearance across.
bool try_split(std::vector<KitchenPiece>& trial, const SeamSpec& seam, const SplitOptions& options,
               SeamCut& cut) {
  try {
    cut = split_piece(trial, 0, seam, options);
  } catch (const GeometryError&) {
    return false;
  }
  return std::none_of(trial.begin(), trial.end(), [&](const KitchenPiece& p) {
    const Box2 b = box_of(p.outer);
    return std::min(b.hi.x() - b.lo.x(), b.hi.y() - b.lo.y()) < options.seam_clearance;
  });
}

bool fits(const KitchenPiece& p, const SlabFit& slab) {
  return fits_slab(p.outer, slab) && !(slab.no_inside_corners && inside_corner(p));
}

// When the search gives up: each piece that does not fit split at its first
// candidate that works, until all fit (at most 64 seams).
bool greedy_split(const KitchenPiece& top, const Search& search, std::vector<KitchenPiece>& done,
                  std::vector<SeamCut>& seams) {
  std::vector<KitchenPiece> open{top};
  while (!open.empty()) {
    KitchenPiece piece = std::move(open.back());
    open.pop_back();
    if (fits(piece, search.slab)) {
      done.push_back(std::move(piece));
      continue;
    }
    if (seams.size() >= 64) return false;
    bool split = false;
    for (const SeamSpec& seam : candidates(piece, search.slab, search.options)) {
      std::vector<KitchenPiece> trial{piece};
      SeamCut cut;
      if (!try_split(trial, seam, search.options, cut)) continue;
      seams.push_back(cut);
      for (KitchenPiece& p : trial) open.push_back(std::move(p));
      split = true;
      break;
    }
    if (!split) return false;
  }
  return true;
}

bool fit_within(Search& search, std::vector<KitchenPiece> pieces, std::size_t budget,
                std::vector<KitchenPiece>& done, std::vector<SeamCut>& seams) {
  // Pieces that fit are done; the first that does not is split every candidate way.
  std::vector<KitchenPiece> open;
  for (KitchenPiece& p : pieces) (fits(p, search.slab) ? done : open).push_back(std::move(p));
  if (open.empty()) return true;
  if (budget < open.size()) return false;  // each open piece needs a seam at least
  const KitchenPiece first = open.front();
  for (const SeamSpec& seam : candidates(first, search.slab, search.options)) {
    if (++search.tries > kSearchTries) return false;
    std::vector<KitchenPiece> trial{first};
    SeamCut cut;
    if (!try_split(trial, seam, search.options, cut)) continue;
    std::vector<KitchenPiece> rest = trial;
    rest.insert(rest.end(), open.begin() + 1, open.end());
    std::vector<KitchenPiece> done_here = done;
    std::vector<SeamCut> seams_here = seams;
    seams_here.push_back(cut);
    if (fit_within(search, rest, budget - 1, done_here, seams_here)) {
      done = std::move(done_here);
      seams = std::move(seams_here);
      return true;
    }
  }
  return false;
}

}  // namespace

namespace {

// The part of `seg` from s0 to s1 (0 <= s0 < s1 <= 1) as a segment of its
// own: the segment itself, a line between its points, or the elliptic arc
// between their angles.
Segment sub_segment(const Segment& seg, double s0, double s1, std::size_t index) {
  if (s0 <= 0.0 && s1 >= 1.0) return seg;
  const Vec2 a = seg.point(s0), b = seg.point(s1);
  if (seg.kind() == SegmentKind::Line) return Segment::line(a, b);
  if (seg.kind() == SegmentKind::EllipseArc) {
    EllipseArcParams e = *seg.ellipse();
    const double rot = e.rotation_deg * M_PI / 180.0;
    auto angle = [&](const Vec2& p, double guess) {
      const Vec2 d = p - e.center;
      const Vec2 local(std::cos(rot) * d.x() + std::sin(rot) * d.y(),
                       -std::sin(rot) * d.x() + std::cos(rot) * d.y());
      const double theta = std::atan2(local.y() / e.b, local.x() / e.a) * 180.0 / M_PI;
      return theta + 360.0 * std::round((guess - theta) / 360.0);
    };
    const double from = e.from_deg, to = e.to_deg;
    e.from_deg = angle(a, from + s0 * (to - from));
    e.to_deg = angle(b, from + s1 * (to - from));
    return Segment::ellipse_arc(e);
  }
  throw GeometryError(
      ErrorLocation{"seams", {}, {a.x(), a.y()}},
      fmt::format("a seam ends inside outline segment {} ({}), whose part has no exact form of "
                  "its own: move the seam onto a line or an arc of the outline",
                  index, to_string(seg.kind())));
}

// The exact outline from parameter ga forward to gb (once round when equal).
void append_stretch(const CompositeCurve& outline, double ga, double gb, std::vector<Segment>& out) {
  const double n = static_cast<double>(outline.size());
  if (gb <= ga) gb += n;
  double g = ga;
  while (g < gb) {
    const double base = std::floor(g);
    const double end = std::min(base + 1.0, gb);
    const std::size_t index = static_cast<std::size_t>(base) % outline.size();
    const double s0 = g - base, s1 = end - base;
    if (s1 - s0 > 1e-12) out.push_back(sub_segment(outline.segments()[index], s0, s1, index));
    g = end;
  }
}

}  // namespace

CompositeCurve exact_piece_outline(const KitchenPiece& piece, const CompositeCurve& outline, bool reversed) {
  const std::size_t n = piece.outer.size();
  // The piece's vertices in the outline's direction, with the edge after each.
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::vector<EdgeKind> after(n);
  for (std::size_t k = 0; k < n; ++k) after[k] = piece.edges[k];
  if (reversed) {
    std::reverse(order.begin(), order.end());
    for (std::size_t k = 0; k < n; ++k) after[order[k]] = piece.edges[order[(k + 1) % n]];
  }
  const auto seam =
      std::find_if(order.begin(), order.end(), [&](std::size_t v) { return after[v] == EdgeKind::Seam; });
  if (seam == order.end()) return outline;  // the whole top
  std::vector<Segment> segments;
  const std::size_t start = static_cast<std::size_t>(seam - order.begin());
  for (std::size_t step = 0; step < n;) {
    const std::size_t v = order[(start + step) % n];
    const std::size_t w = order[(start + step + 1) % n];
    if (after[v] == EdgeKind::Seam) {
      // A seam: a line between the exact ends.
      segments.push_back(Segment::line(outline.point(piece.along[v]), outline.point(piece.along[w])));
      ++step;
      continue;
    }
    // A stretch of the outline, up to the next seam.
    std::size_t k = step;
    while (after[order[(start + k) % n]] != EdgeKind::Seam) ++k;
    append_stretch(outline, piece.along[v], piece.along[order[(start + k) % n]], segments);
    step = k;
  }
  return CompositeCurve(std::move(segments), true);
}

const char* to_string(EdgeKind kind) {
  switch (kind) {
    case EdgeKind::Exposed:
      return "exposed";
    case EdgeKind::Wall:
      return "wall";
    case EdgeKind::Seam:
      return "seam";
  }
  return "exposed";
}

std::vector<EdgeKind> outline_edge_kinds(const Region2& region, const std::vector<bool>& wall_segment) {
  const std::size_t m = region.outer.size();
  std::vector<EdgeKind> kinds(m, EdgeKind::Exposed);
  const double n = static_cast<double>(wall_segment.size());
  if (wall_segment.empty() || region.outer_along.size() != m) return kinds;
  for (std::size_t k = 0; k < m; ++k) {
    const double ga = region.outer_along[k], gb = region.outer_along[(k + 1) % m];
    double d = std::fmod(gb - ga + n, n);
    double from = ga;
    if (d > 0.5 * n) {  // the loop runs against the outline
      from = gb;
      d = n - d;
    }
    const double mid = std::fmod(from + 0.5 * d, n);
    const std::size_t segment = std::min(static_cast<std::size_t>(mid), wall_segment.size() - 1);
    if (wall_segment[segment]) kinds[k] = EdgeKind::Wall;
  }
  return kinds;
}

std::vector<KitchenPiece> backsplash_strips(const std::vector<KitchenPiece>& pieces, double height,
                                            double tolerance, std::vector<std::string>& curved) {
  std::vector<KitchenPiece> strips;
  auto strip = [&](const KitchenPiece& piece, const Vec2& a, const Vec2& b) {
    const double length = (b - a).norm();
    if (length < height) {  // a short return, or a piece of a curved wall
      curved.push_back(fmt::format("{} from {} to {}", piece.name, at_text(a), at_text(b)));
      return;
    }
    KitchenPiece s;
    s.strip = true;
    s.outer = {{0.0, 0.0}, {length, 0.0}, {length, height}, {0.0, height}};
    s.edges = {EdgeKind::Seam, EdgeKind::Exposed, EdgeKind::Exposed, EdgeKind::Exposed};
    s.along.assign(4, std::numeric_limits<double>::quiet_NaN());
    s.area = length * height;
    strips.push_back(std::move(s));
  };
  for (const KitchenPiece& piece : pieces) {
    const std::size_t n = piece.outer.size();
    // Start after an edge that is not a wall (a piece all wall has no run's start).
    std::size_t start = n;
    for (std::size_t k = 0; k < n; ++k) {
      if (piece.edges[k] != EdgeKind::Wall && piece.edges[(k + 1) % n] == EdgeKind::Wall) start = (k + 1) % n;
    }
    if (start == n) continue;
    // Straight runs of wall edges: a run ends where a point would leave its
    // chord by more than `tolerance` (a corner), or at an edge that is no wall.
    auto point = [&](std::size_t step) -> const Vec2& { return piece.outer[(start + step) % n]; };
    auto straight = [&](std::size_t from, std::size_t to) {
      const Vec2& a = point(from);
      const Vec2& b = point(to);
      const double len = (b - a).norm();
      for (std::size_t j = from + 1; j < to; ++j) {
        if (!(len > 0.0) || std::abs(cross2(b - a, point(j) - a)) / len > tolerance) return false;
      }
      return len > 0.0;
    };
    std::optional<std::size_t> first;  // the open run's first point
    std::size_t last = 0;              // and its last
    for (std::size_t step = 0; step < n; ++step) {
      const bool wall = piece.edges[(start + step) % n] == EdgeKind::Wall;
      if (wall && first && straight(*first, step + 1)) {
        last = step + 1;
        continue;
      }
      if (first) strip(piece, point(*first), point(last));
      first.reset();
      if (wall) {
        first = step;
        last = step + 1;
      }
    }
    if (first) strip(piece, point(*first), point(last));
  }
  for (std::size_t i = 0; i < strips.size(); ++i) strips[i].name = fmt::format("backsplash-{}", i + 1);
  return strips;
}

std::array<double, 3> edge_lengths(const KitchenPiece& piece) {
  std::array<double, 3> out{0.0, 0.0, 0.0};
  for (std::size_t e = 0; e < piece.outer.size(); ++e) {
    const double len = (piece.outer[(e + 1) % piece.outer.size()] - piece.outer[e]).norm();
    out[static_cast<std::size_t>(piece.edges[e])] += len;
  }
  return out;
}

bool fits_slab(const std::vector<Vec2>& outer, const SlabFit& slab) {
  const Box2 b = box_of(outer);
  const Vec2 size = b.hi - b.lo;
  const double longer = std::max(size.x(), size.y()), shorter = std::min(size.x(), size.y());
  if (longer <= slab.length && shorter <= slab.width) return true;
  return !slab.grain_along && longer <= slab.width && shorter <= slab.length;
}

KitchenSplit split_top(const Region2& region, const std::vector<SeamSpec>& seams, const SplitOptions& options,
                       const std::vector<EdgeKind>& kinds) {
  std::vector<KitchenPiece> pieces{whole_top(region, kinds)};
  std::vector<SeamCut> cuts;
  const double slack = 2.0 * options.deviation + 1e-9;
  for (const SeamSpec& seam : seams) {
    if (!(seam.direction.norm() > 0.0) || !seam.direction.allFinite()) {
      throw GeometryError(ErrorLocation{seam.key + ".direction"},
                          fmt::format("{}.direction must be a non-zero vector", seam.key));
    }
    const std::size_t index = piece_containing(pieces, seam.at, slack);
    if (index == pieces.size()) {
      throw GeometryError(ErrorLocation{seam.key + ".at", {}, {seam.at.x(), seam.at.y()}},
                          fmt::format("{}: the point {} is not on the top", seam.key, at_text(seam.at)));
    }
    cuts.push_back(split_piece(pieces, index, seam, options));
  }
  return finish(std::move(pieces), std::move(cuts), region);
}

namespace {

// The fewest seams (up to 8) that make every piece of `top` fit, or when the
// search gives up, the greedy split; nothing when neither finds one.
std::optional<KitchenSplit> search_split(const KitchenPiece& top, const Region2& region, const SlabFit& slab,
                                         const SplitOptions& options) {
  Search search{region, slab, options};
  for (std::size_t budget = 0; budget <= 8 && search.tries <= kSearchTries; ++budget) {
    std::vector<KitchenPiece> done;
    std::vector<SeamCut> seams;
    if (fit_within(search, {top}, budget, done, seams))
      return finish(std::move(done), std::move(seams), region);
  }
  // Too many seams, or too many ways, for the search: the greedy split.
  std::vector<KitchenPiece> done;
  std::vector<SeamCut> seams;
  if (greedy_split(top, search, done, seams)) return finish(std::move(done), std::move(seams), region);
  return std::nullopt;
}

}  // namespace

KitchenSplit auto_split(const Region2& region, const SlabFit& slab, const SplitOptions& options,
                        const std::vector<EdgeKind>& kinds) {
  const KitchenPiece top = whole_top(region, kinds);
  // A cut-out that no slab holds (with its clearance on both sides) cannot be seamed round.
  for (std::size_t h = 0; h < region.holes.size(); ++h) {
    const Box2 hb = box_of(region.holes[h]);
    const Vec2 size = hb.hi - hb.lo;
    std::vector<Vec2> box{hb.lo, {hb.hi.x(), hb.lo.y()}, hb.hi, {hb.lo.x(), hb.hi.y()}};
    if (!fits_slab(box, slab)) {
      throw GeometryError(
          ErrorLocation{fmt::format("holes[{}]", h)},
          fmt::format("holes[{}] is {:.6g} x {:.6g}: the piece that holds it cannot fit a slab "
                      "whose usable area is {:.6g} x {:.6g}",
                      h, size.x(), size.y(), slab.length, slab.width));
    }
  }
  if (std::optional<KitchenSplit> split = search_split(top, region, slab, options)) return std::move(*split);
  // A router that leaves inside corners round: say so when that is what no seams can satisfy.
  std::string hint;
  if (slab.no_inside_corners) {
    SlabFit relaxed = slab;
    relaxed.no_inside_corners = false;
    if (search_split(top, region, relaxed, options)) {
      hint =
          "; seams that fit a slab exist, but each leaves a piece with a sharp inside corner, which "
          "the router without dog-bones (cnc.relief: none) cannot cut: set cnc.relief: dogbone, keep "
          "the cut-outs far enough from the inside corners for a butt joint there, or give the seams";
    }
  }
  const Box2 b = box_of(region.outer);
  throw GeometryError(
      ErrorLocation{"seams"},
      fmt::format(
          "seams: auto found no seams (neither the fewest, up to 8, nor greedily, up to 64), each {:.6g} "
          "from every cut-out and leaving no piece narrower, "
          "that cuts the {:.6g} x {:.6g} top into pieces of at most {:.6g} x {:.6g} "
          "(the slab's usable area); give the seams (seams: [{{at, direction}}]) or "
          "a larger slab{}",
          options.seam_clearance, b.hi.x() - b.lo.x(), b.hi.y() - b.lo.y(), slab.length, slab.width, hint));
}

}  // namespace fabmesh
