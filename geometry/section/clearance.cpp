#include "geometry/section/clearance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

namespace fabmesh {
namespace {

constexpr std::size_t kChunk = 16;

// One (sub)piece with what its bound needs.
struct Sub {
  const ExactArc* arc;
  double s0, s1;
  Vec2 p0, p1;
  ChordBound::Ends e0, e1;
  double dev;  // chord bound
};

Sub make_sub(const ExactArc* arc, double s0, double s1, const Vec2& p0, const Vec2& p1,
             const ChordBound::Ends& e0, const ChordBound::Ends& e1) {
  return {arc, s0, s1, p0, p1, e0, e1, arc->chord_bound().bound(s0, s1, e0, e1)};
}

// Closest points of segments ab and cd (2D): distance and the points.
double segment_distance(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, Vec2* pa, Vec2* pc) {
  const auto orient = [](const Vec2& p, const Vec2& q, const Vec2& r) { return cross2(q - p, r - p); };
  const double o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) {
    const double t = o3 / (o3 - o4);
    *pa = *pc = a + t * (b - a);
    return 0.0;
  }
  double best = std::numeric_limits<double>::infinity();
  const auto project = [&](const Vec2& p, const Vec2& s, const Vec2& e, bool p_on_first) {
    const Vec2 se = e - s;
    const double len2 = se.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((p - s).dot(se) / len2, 0.0, 1.0) : 0.0;
    const Vec2 q = s + t * se;
    const double dist = (p - q).norm();
    if (dist < best) {
      best = dist;
      *pa = p_on_first ? p : q;
      *pc = p_on_first ? q : p;
    }
  };
  project(a, c, d, true);
  project(b, c, d, true);
  project(c, a, b, false);
  project(d, a, b, false);
  return best;
}

struct Pair {
  double lower;
  Sub x, y;
  int gx, gy;
  std::size_t order;  // ties broken by creation order: deterministic
};

struct LowerFirst {
  bool operator()(const Pair& p, const Pair& q) const {
    return p.lower != q.lower ? p.lower > q.lower : p.order > q.order;
  }
};

class Search {
 public:
  explicit Search(const ClearanceOptions& options) : options_(options) {}

  // Measures a pair: updates the best upper bound, returns its lower bound.
  double measure(const Sub& x, const Sub& y, int gx, int gy) {
    Vec2 px, py;
    const double d = segment_distance(x.p0, x.p1, y.p0, y.p1, &px, &py);
    const double upper = d + x.dev + y.dev;
    if (upper < best_.upper) {
      best_.upper = upper;
      best_.a = px;
      best_.b = py;
      best_.group_a = gx;
      best_.group_b = gy;
    }
    return d - x.dev - y.dev;
  }

  void push(const Sub& x, const Sub& y, int gx, int gy) {
    const double lower = measure(x, y, gx, gy);
    if (lower < best_.upper) queue_.push({lower, x, y, gx, gy, count_++});
  }

  Sub half(const Sub& s, bool first) const {
    const double mid = 0.5 * (s.s0 + s.s1);
    const Vec2 pm = s.arc->point(mid);
    const ChordBound::Ends em = s.arc->chord_bound().at(mid);
    return first ? make_sub(s.arc, s.s0, mid, s.p0, pm, s.e0, em)
                 : make_sub(s.arc, mid, s.s1, pm, s.p1, em, s.e1);
  }

  Clearance run() {
    std::size_t refinements = 0;
    // The lowest lower bound of pairs that were settled without splitting (exact or too short).
    double settled = std::numeric_limits<double>::infinity();
    double open = std::numeric_limits<double>::infinity();
    while (!queue_.empty()) {
      const Pair p = queue_.top();
      open = p.lower;
      if (p.lower >= best_.upper - options_.accuracy || best_.upper <= options_.accuracy) break;
      if (++refinements > options_.max_refinements) break;
      queue_.pop();
      open = std::numeric_limits<double>::infinity();
      // Split the side with the larger chord bound (the longer chord on a tie), if it can be split.
      const bool split_x = p.x.dev != p.y.dev
                               ? p.x.dev > p.y.dev
                               : (p.x.p1 - p.x.p0).squaredNorm() >= (p.y.p1 - p.y.p0).squaredNorm();
      const Sub& s = split_x ? p.x : p.y;
      const double mid = 0.5 * (s.s0 + s.s1);
      if (!(mid > s.s0 && mid < s.s1) || (p.x.dev == 0.0 && p.y.dev == 0.0)) {
        settled = std::min(settled, p.lower);
        continue;
      }
      for (bool first : {true, false}) {
        const Sub h = half(s, first);
        if (split_x) {
          push(h, p.y, p.gx, p.gy);
        } else {
          push(p.x, h, p.gx, p.gy);
        }
      }
    }
    best_.lower = std::max(0.0, std::min({settled, open, best_.upper}));
    return best_;
  }

  Clearance& best() { return best_; }

 private:
  ClearanceOptions options_;
  Clearance best_;
  std::priority_queue<Pair, std::vector<Pair>, LowerFirst> queue_;
  std::size_t count_ = 0;
};

struct Chunk {
  std::size_t first, last;  // pieces [first, last)
  int group;
  Vec2 lo, hi;  // bounding box of the chords, grown by the largest chord bound
};

double box_distance(const Chunk& a, const Chunk& b) {
  const Vec2 gap = (a.lo - b.hi).cwiseMax(b.lo - a.hi).cwiseMax(Vec2::Zero());
  return gap.norm();
}

}  // namespace

Clearance exact_clearance(const std::vector<ArcPiece>& pieces, const ClearanceOptions& options) {
  std::vector<Sub> subs;
  subs.reserve(pieces.size());
  for (const ArcPiece& p : pieces) {
    const ChordBound& cb = p.arc->chord_bound();
    subs.push_back(
        make_sub(p.arc, p.s0, p.s1, p.arc->point(p.s0), p.arc->point(p.s1), cb.at(p.s0), cb.at(p.s1)));
  }
  std::vector<Chunk> chunks;
  for (std::size_t i = 0; i < pieces.size();) {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    Chunk c{i, i, pieces[i].group, Vec2::Constant(kInf), Vec2::Constant(-kInf)};
    double grow = 0.0;
    while (c.last < pieces.size() && c.last - c.first < kChunk && pieces[c.last].group == c.group) {
      const Sub& s = subs[c.last];
      c.lo = c.lo.cwiseMin(s.p0).cwiseMin(s.p1);
      c.hi = c.hi.cwiseMax(s.p0).cwiseMax(s.p1);
      grow = std::max(grow, s.dev);
      ++c.last;
    }
    c.lo -= Vec2::Constant(grow);
    c.hi += Vec2::Constant(grow);
    chunks.push_back(c);
    i = c.last;
  }
  struct ChunkPair {
    double distance;
    std::size_t a, b;
  };
  std::vector<ChunkPair> pairs;
  for (std::size_t a = 0; a < chunks.size(); ++a) {
    for (std::size_t b = a + 1; b < chunks.size(); ++b) {
      if (chunks[a].group != chunks[b].group) pairs.push_back({box_distance(chunks[a], chunks[b]), a, b});
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const ChunkPair& x, const ChunkPair& y) {
    return x.distance != y.distance ? x.distance < y.distance : (x.a != y.a ? x.a < y.a : x.b < y.b);
  });
  Search search(options);
  for (const ChunkPair& cp : pairs) {
    if (cp.distance >= search.best().upper) break;
    const Chunk& ca = chunks[cp.a];
    const Chunk& cb = chunks[cp.b];
    for (std::size_t i = ca.first; i < ca.last; ++i) {
      for (std::size_t j = cb.first; j < cb.last; ++j) search.push(subs[i], subs[j], ca.group, cb.group);
    }
  }
  return search.run();
}

}  // namespace fabmesh
