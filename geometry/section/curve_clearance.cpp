#include "geometry/section/curve_clearance.h"

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

double box_distance(const Vec2& alo, const Vec2& ahi, const Vec2& blo, const Vec2& bhi) {
  const Vec2 gap = (alo - bhi).cwiseMax(blo - ahi).cwiseMax(Vec2::Zero());
  return gap.norm();
}

// Runs of up to kChunk consecutive pieces of one group, boxed.
std::vector<Chunk> make_chunks(const std::vector<ArcPiece>& pieces, const std::vector<Sub>& subs) {
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
  return chunks;
}

// A hierarchy of boxes over the chunks: each run of one group's consecutive
// chunks (near each other along a curve) merged two by two up to the run's
// root; a group may have several runs. The runs' roots are then merged into
// one top by halving them at the median of their centres along the wider
// axis (near roots under one node), so that a search starts from one pair
// whatever the number of loops. Nodes [0, chunks) are the chunks themselves.
class ChunkTree {
 public:
  static constexpr std::size_t kLeaf = std::numeric_limits<std::size_t>::max();
  static constexpr int kMixed = -1;  ///< the group of a node over runs of several groups
  struct Node {
    Vec2 lo, hi;
    std::size_t left = kLeaf, right = kLeaf;  ///< children, or kLeaf for a chunk
    int group = 0;
  };

  explicit ChunkTree(const std::vector<Chunk>& chunks) {
    for (const Chunk& c : chunks) nodes_.push_back({c.lo, c.hi, kLeaf, kLeaf, c.group});
    std::vector<std::size_t> roots;
    for (std::size_t first = 0; first < chunks.size();) {
      std::size_t last = first;
      while (last < chunks.size() && chunks[last].group == chunks[first].group) ++last;
      roots.push_back(merge_run(first, last));
      first = last;
    }
    if (!roots.empty()) top_ = merge_near(roots.begin(), roots.end());
  }
  const Node& operator[](std::size_t i) const { return nodes_[i]; }
  /// The node over every chunk (kLeaf when there are none).
  std::size_t top() const { return top_; }
  bool leaf(std::size_t i) const { return nodes_[i].left == kLeaf; }
  /// Whether every chunk under a and b is of one group (no pair of them is measured).
  bool one_group(std::size_t a, std::size_t b) const {
    return nodes_[a].group != kMixed && nodes_[a].group == nodes_[b].group;
  }
  double distance(std::size_t a, std::size_t b) const {
    return box_distance(nodes_[a].lo, nodes_[a].hi, nodes_[b].lo, nodes_[b].hi);
  }
  double extent(std::size_t i) const { return (nodes_[i].hi - nodes_[i].lo).squaredNorm(); }

 private:
  std::size_t join(std::size_t a, std::size_t b) {
    const Node& l = nodes_[a];
    const Node& r = nodes_[b];
    nodes_.push_back({l.lo.cwiseMin(r.lo), l.hi.cwiseMax(r.hi), a, b, l.group == r.group ? l.group : kMixed});
    return nodes_.size() - 1;
  }
  // The root over the chunks [first, last), merging neighbours level by level.
  std::size_t merge_run(std::size_t first, std::size_t last) {
    std::vector<std::size_t> level(last - first);
    for (std::size_t i = 0; i < level.size(); ++i) level[i] = first + i;
    while (level.size() > 1) {
      std::vector<std::size_t> up;
      for (std::size_t i = 0; i + 1 < level.size(); i += 2) up.push_back(join(level[i], level[i + 1]));
      if (level.size() % 2 == 1) up.push_back(level.back());
      level = std::move(up);
    }
    return level.front();
  }
  // The node over the roots [first, last): halved at the median centre along
  // the wider axis of their centres (ties by node number: deterministic).
  std::size_t merge_near(std::vector<std::size_t>::iterator first, std::vector<std::size_t>::iterator last) {
    if (last - first == 1) return *first;
    Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (auto it = first; it != last; ++it) {
      lo = lo.cwiseMin(centre(*it));
      hi = hi.cwiseMax(centre(*it));
    }
    const int axis = hi.x() - lo.x() >= hi.y() - lo.y() ? 0 : 1;
    const auto middle = first + (last - first) / 2;
    std::nth_element(first, middle, last, [&](std::size_t a, std::size_t b) {
      const double ca = centre(a)[axis], cb = centre(b)[axis];
      return ca != cb ? ca < cb : a < b;
    });
    const std::size_t left = merge_near(first, middle);
    const std::size_t right = merge_near(middle, last);
    return join(left, right);
  }
  Vec2 centre(std::size_t i) const { return 0.5 * (nodes_[i].lo + nodes_[i].hi); }

  std::vector<Node> nodes_;
  std::size_t top_ = kLeaf;
};

// Pairs of chunks of different groups, nearest boxes first. A pair of nodes
// is opened only when it comes first, and its children are never nearer
// than it, so the chunk pairs come in order of box distance (ties by node
// numbers: deterministic) while memory holds only the open frontier, not
// every pair: a design's thousands of chunks, or of loops, no longer list
// millions. The search starts from the top node paired with itself; a node
// paired with itself opens into its children's pairs.
class NearestChunkPairs {
 public:
  explicit NearestChunkPairs(const ChunkTree& tree) : tree_(tree) {
    const std::size_t top = tree.top();
    if (top != ChunkTree::kLeaf && !tree.one_group(top, top)) push(top, top);
  }

  /// The next pair of chunks whose boxes are nearer than `bound`, or false
  /// when there is none (then no later pair is nearer either).
  bool next(double bound, std::size_t& a, std::size_t& b) {
    while (!queue_.empty() && queue_.top().distance < bound) {
      const NodePair p = queue_.top();
      queue_.pop();
      if (p.a == p.b) {  // a node with itself: its children with themselves and each other
        const std::size_t l = tree_[p.a].left, r = tree_[p.a].right;
        for (const auto& [x, y] : {std::pair{l, l}, std::pair{r, r}, std::pair{l, r}}) {
          if (!tree_.one_group(x, y) && tree_.distance(x, y) < bound) push(x, y);
        }
        continue;
      }
      const bool leaf_a = tree_.leaf(p.a), leaf_b = tree_.leaf(p.b);
      if (leaf_a && leaf_b) {
        a = p.a;
        b = p.b;
        return true;
      }
      // Open the larger node (or the one that is not a chunk).
      const bool open_a = !leaf_a && (leaf_b || tree_.extent(p.a) >= tree_.extent(p.b));
      const std::size_t open = open_a ? p.a : p.b, other = open_a ? p.b : p.a;
      for (const std::size_t child : {tree_[open].left, tree_[open].right}) {
        if (!tree_.one_group(child, other) && tree_.distance(child, other) < bound) push(child, other);
      }
    }
    return false;
  }

 private:
  struct NodePair {
    double distance;
    std::size_t a, b;  // a <= b
  };
  struct FartherLast {
    bool operator()(const NodePair& x, const NodePair& y) const {
      return x.distance != y.distance ? x.distance > y.distance : (x.a != y.a ? x.a > y.a : x.b > y.b);
    }
  };
  void push(std::size_t a, std::size_t b) {
    queue_.push({tree_.distance(a, b), std::min(a, b), std::max(a, b)});
  }

  const ChunkTree& tree_;
  std::priority_queue<NodePair, std::vector<NodePair>, FartherLast> queue_;
};

}  // namespace

Clearance exact_clearance(const std::vector<ArcPiece>& pieces, const ClearanceOptions& options) {
  std::vector<Sub> subs;
  subs.reserve(pieces.size());
  for (const ArcPiece& p : pieces) {
    const ChordBound& cb = p.arc->chord_bound();
    subs.push_back(
        make_sub(p.arc, p.s0, p.s1, p.arc->point(p.s0), p.arc->point(p.s1), cb.at(p.s0), cb.at(p.s1)));
  }
  const std::vector<Chunk> chunks = make_chunks(pieces, subs);
  const ChunkTree tree(chunks);
  NearestChunkPairs nearest(tree);
  Search search(options);
  for (std::size_t a = 0, b = 0; nearest.next(search.best().upper, a, b);) {
    const Chunk& ca = chunks[a];
    const Chunk& cb = chunks[b];
    for (std::size_t i = ca.first; i < ca.last; ++i) {
      for (std::size_t j = cb.first; j < cb.last; ++j) search.push(subs[i], subs[j], ca.group, cb.group);
    }
  }
  return search.run();
}

}  // namespace fabmesh
