// The fast self-intersection test: a Morton-sorted BVH over the triangle
// boxes (triangle_bvh.h) enumerates the pairs whose boxes overlap; a
// floating-point filter with proven error bounds (face_pair_filter.h)
// dismisses the pairs that certainly do not intersect, which is nearly all
// of them in a valid mesh (mostly neighbours sharing a vertex or an edge);
// the few it cannot decide go to the exact test of the reference
// implementation (faces_intersect_exact). The answer is therefore exactly
// the reference's. The search is split into fixed tasks (pairs of subtrees),
// each run by one thread, and their findings combined in task order, so the result
// does not depend on the thread count.
//
// The faces around a vertex of high degree (the apex of a fan, a pole) are
// not in the hierarchy: their boxes all overlap at that vertex, and a fan's
// long faces have boxes overlapping much of the mesh around it. Their pairs
// come from the vertex's star instead (vertex_star.h), after the tasks, star
// by star in vertex order: the pairs within the star by their arcs, then
// the pairs with the faces around it (found by box queries on a hierarchy
// of the other faces and one of the stars' faces) by arcs against cones.
// O(d log d) for d faces around a vertex rather than d^2 / 2 pairs. Each
// pair is tested once: a pair sharing star centres by the smallest shared
// one, any other pair with a star's face by the smallest centre of the two.

#include "geometry/validation/detail/self_intersect.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <optional>

#include "geometry/core/errors.h"
#include "geometry/validation/detail/face_pair_filter.h"
#include "geometry/validation/detail/planar_patch.h"
#include "geometry/validation/detail/self_intersect_reference.h"
#include "geometry/validation/detail/sliver_pieces.h"
#include "geometry/validation/detail/triangle_bvh.h"
#include "geometry/validation/detail/vertex_star.h"

namespace fabmesh {
namespace {

using Pair = std::pair<std::uint32_t, std::uint32_t>;

constexpr std::size_t kLeavesPerTask = 64;         ///< the unit of parallel work: 256 triangles
constexpr std::size_t kTasksPerBatch = 4096;       ///< tasks in flight (memory bound on piles of faces)
constexpr std::size_t kPairsPerClockCheck = 4096;  ///< candidate pairs between two looks at the deadline
constexpr std::size_t kFacesPerUnit = 256;         ///< faces per unit of the patches' search

/// A certified plane group (planar_patch.h) out of the box search: its
/// faces (in no star) as pieces (sliver_pieces.h) in a hierarchy of their own.
struct Patch {
  std::vector<std::uint32_t> faces;  ///< ascending
  std::vector<std::size_t> offsets;  ///< face i has pieces offsets[i] .. offsets[i + 1] of boxes
  std::vector<BoxF> boxes;
  BoxF box;                        ///< of all its pieces
  std::optional<TriangleBvh> bvh;  ///< over the pieces
};

/// A unit of the patches' search: the faces [first, last) of the main
/// hierarchy (patch == none) against every patch, or of patch `patch`
/// against the patches after it.
struct PatchUnit {
  std::size_t patch, first, last;
};
constexpr std::size_t kMainFaces = static_cast<std::size_t>(-1);

/// The smallest `keep` pairs of those added.
class SmallestPairs {
 public:
  explicit SmallestPairs(std::size_t keep) : keep_(keep) {}
  void add(const Pair& p) {
    pairs_.push_back(p);
    if (pairs_.size() >= 2 * keep_ + 1024) trim();
  }
  void add(const SmallestPairs& other) {
    for (const Pair& p : other.pairs_) add(p);
  }
  /// The kept pairs, ascending.
  std::vector<Pair> take() {
    trim();
    std::sort(pairs_.begin(), pairs_.end());
    return std::move(pairs_);
  }

 private:
  void trim() {
    if (pairs_.size() <= keep_) return;
    std::nth_element(pairs_.begin(), pairs_.begin() + static_cast<std::ptrdiff_t>(keep_), pairs_.end());
    pairs_.resize(keep_);
  }
  std::size_t keep_;
  std::vector<Pair> pairs_;
};

/// What one task found.
struct TaskResult {
  std::size_t count = 0;   ///< intersecting pairs counted (at most the task's limit)
  SmallestPairs smallest;  ///< the smallest max_pairs of them
  bool complete = false;   ///< false when the search gave up before starting
  bool timed_out = false;  ///< the deadline passed: some pairs of the task were not tested
  std::size_t tested = 0;  ///< candidate pairs decided
};

/// Whether the deadline of `options` has passed.
bool past_deadline(const SelfIntersectOptions& options) {
  return options.deadline && std::chrono::steady_clock::now() >= *options.deadline;
}

/// Whether the exact (closed) boxes of faces f and g overlap: the reference
/// never tests other pairs, so neither may we (it matters only for
/// degenerate faces, on which CGAL's tests are not defined).
bool boxes_overlap(const TriangleSoup& soup, std::uint32_t f, std::uint32_t g) {
  const auto& a = soup.triangles[f];
  const auto& b = soup.triangles[g];
  for (int k = 0; k < 3; ++k) {
    const double a0 = soup.vertices[a[0]][k], a1 = soup.vertices[a[1]][k], a2 = soup.vertices[a[2]][k];
    const double b0 = soup.vertices[b[0]][k], b1 = soup.vertices[b[1]][k], b2 = soup.vertices[b[2]][k];
    if (std::max({a0, a1, a2}) < std::min({b0, b1, b2}) || std::max({b0, b1, b2}) < std::min({a0, a1, a2})) {
      return false;
    }
  }
  return true;
}

class Search {
 public:
  Search(const TriangleSoup& soup, const TriangleBvh& bvh, const TriangleBvh* star_bvh,
         const detail::VertexStars& stars, const std::vector<Patch>& patches,
         const detail::FacePairFilter& filter, const SelfIntersectOptions& options)
      : soup_(soup),
        bvh_(bvh),
        star_bvh_(star_bvh),
        stars_(stars),
        patches_(patches),
        filter_(filter),
        options_(options) {
    // What the filter needs beyond the corners, in the hierarchy's order:
    // 16 bytes a face, the corners read from the vertices when a pair is
    // tested (a copy of them would be 88 bytes a face, the largest array of
    // `check` on a large mesh).
    face_.resize(bvh.size());
    auto body = [&](std::size_t i) {
      const detail::FaceData d = detail::face_data(soup, bvh.face(i));
      face_[i] = {d.v, d.certified};
    };
    if (options.parallel) {
      tbb::parallel_for(std::size_t{0}, face_.size(), body);
    } else {
      for (std::size_t i = 0; i < face_.size(); ++i) body(i);
    }
  }

  /// Searches the pairs of one task, counting at most `limit`. With
  /// `total`, adds what it counts there and gives up (complete = false) when
  /// the total has already reached count_limit.
  TaskResult run(const TriangleBvh::Task& task, std::size_t limit, std::atomic<std::size_t>* total) const {
    TaskResult r{0, SmallestPairs(options_.max_pairs), false};
    if (total && total->load(std::memory_order_relaxed) >= options_.count_limit) return r;
    if (past_deadline(options_)) {
      r.timed_out = true;
      return r;
    }
    bvh_.run(task, [&](std::size_t i, std::size_t j) {
      if (r.count >= limit || r.timed_out) return;
      if (++r.tested % kPairsPerClockCheck == 0 && past_deadline(options_)) {
        --r.tested;
        r.timed_out = true;
        return;
      }
      if (filter_.disjoint(corners(face_[i]), corners(face_[j]))) return;
      // The smaller index first: on degenerate faces (not skipped) CGAL's
      // tests are undefined and may depend on the order.
      const std::uint32_t f = std::min(bvh_.face(i), bvh_.face(j));
      const std::uint32_t g = std::max(bvh_.face(i), bvh_.face(j));
      if (!boxes_overlap(soup_, f, g) || !faces_intersect_exact(soup_, f, g)) return;
      ++r.count;
      r.smallest.add({f, g});
    });
    if (total && r.count > 0) total->fetch_add(r.count);
    r.complete = !r.timed_out;
    return r;
  }

  /// Searches the pairs of one unit of the patches' search (PatchUnit):
  /// faces of the main hierarchy with the patches' faces whose pieces' boxes
  /// overlap theirs, or a patch's faces with the later patches' faces.
  /// (Pairs within a patch need no test: the patch is certified.) Counts
  /// and gives up as run does.
  TaskResult run_patches(const PatchUnit& unit, std::size_t limit, std::atomic<std::size_t>* total) const {
    TaskResult r{0, SmallestPairs(options_.max_pairs), false};
    if (total && total->load(std::memory_order_relaxed) >= options_.count_limit) return r;
    std::vector<std::uint32_t> found;
    for (std::size_t i = unit.first; i < unit.last && r.count < limit && !r.timed_out; ++i) {
      if (past_deadline(options_)) {
        r.timed_out = true;
        break;
      }
      found.clear();
      std::uint32_t f = 0;
      if (unit.patch == kMainFaces) {
        f = bvh_.face(i);
        const BoxF box = triangle_box(soup_, f);
        for (const Patch& q : patches_) {
          if (overlap(q.box, box))
            q.bvh->for_each_overlapping(box, [&](std::uint32_t g) { found.push_back(g); });
        }
      } else {
        const Patch& p = patches_[unit.patch];
        f = p.faces[i];
        for (std::size_t k = p.offsets[i]; k < p.offsets[i + 1]; ++k) {
          for (std::size_t q = unit.patch + 1; q < patches_.size(); ++q) {
            if (!overlap(patches_[q].box, p.boxes[k])) continue;
            patches_[q].bvh->for_each_overlapping(p.boxes[k], [&](std::uint32_t g) { found.push_back(g); });
          }
        }
      }
      std::sort(found.begin(), found.end());
      found.erase(std::unique(found.begin(), found.end()), found.end());
      const detail::FaceData a = detail::face_data(soup_, f);
      for (const std::uint32_t g : found) {
        if (r.count >= limit) break;
        ++r.tested;
        if (filter_.disjoint(a, detail::face_data(soup_, g))) continue;
        const std::uint32_t lo = std::min(f, g);
        const std::uint32_t hi = std::max(f, g);
        if (!boxes_overlap(soup_, lo, hi) || !faces_intersect_exact(soup_, lo, hi)) continue;
        ++r.count;
        r.smallest.add({lo, hi});
      }
    }
    if (total && r.count > 0) total->fetch_add(r.count);
    r.complete = !r.timed_out;
    return r;
  }

  /// Tests the candidate pairs of every star in order, adding to `counted`
  /// (at most count_limit) and `smallest`; sets capped or incomplete.
  void run_stars(std::size_t& counted, SmallestPairs& smallest, SelfIntersections& result) const {
    const auto test = [&](std::uint32_t a, std::uint32_t b) {
      if (++result.candidates_tested % kPairsPerClockCheck == 0 && past_deadline(options_)) {
        --result.candidates_tested;
        result.incomplete = true;
        return false;
      }
      const std::uint32_t f = std::min(a, b);
      const std::uint32_t g = std::max(a, b);
      if (filter_.disjoint(detail::face_data(soup_, f), detail::face_data(soup_, g))) return true;
      if (!boxes_overlap(soup_, f, g) || !faces_intersect_exact(soup_, f, g)) return true;
      ++counted;
      smallest.add({f, g});
      result.capped = counted >= options_.count_limit;
      return !result.capped;
    };
    for (std::size_t s = 0; s < stars_.centres.size() && !result.capped && !result.incomplete; ++s) {
      detail::for_each_star_candidate(soup_, stars_, s, test);
      if (result.capped || result.incomplete) break;
      detail::for_each_star_neighbour_candidate(soup_, stars_, s, neighbours(s), test);
    }
  }

 private:
  /// The faces whose boxes overlap the box of the faces whose smallest star
  /// centre is that of star s, with a greater smallest centre (or none),
  /// ascending.
  std::vector<std::uint32_t> neighbours(std::size_t s) const {
    const std::uint32_t v = stars_.centres[s];
    const float inf = std::numeric_limits<float>::infinity();
    BoxF box{{inf, inf, inf}, {-inf, -inf, -inf}};
    for (std::size_t i = stars_.offsets[s]; i < stars_.offsets[s + 1]; ++i) {
      if (stars_.group[stars_.faces[i]] != v) continue;
      const BoxF b = triangle_box(soup_, stars_.faces[i]);
      for (int k = 0; k < 3; ++k) {
        box.lo[k] = std::min(box.lo[k], b.lo[k]);
        box.hi[k] = std::max(box.hi[k], b.hi[k]);
      }
    }
    std::vector<std::uint32_t> found;
    const auto keep = [&](std::uint32_t g) {
      if (stars_.group[g] > v) found.push_back(g);
    };
    bvh_.for_each_overlapping(box, keep);
    if (star_bvh_) star_bvh_->for_each_overlapping(box, keep);
    for (const Patch& p : patches_) {
      if (overlap(p.box, box)) p.bvh->for_each_overlapping(box, keep);  // a face once per piece
    }
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
    return found;
  }

  /// A face's vertices and whether the filter may reason about it.
  struct FaceRef {
    std::array<std::uint32_t, 3> v;
    char certified;
  };

  detail::FaceData corners(const FaceRef& r) const {
    return {r.v, r.certified, {soup_.vertices[r.v[0]], soup_.vertices[r.v[1]], soup_.vertices[r.v[2]]}};
  }

  const TriangleSoup& soup_;
  const TriangleBvh& bvh_;
  const TriangleBvh* star_bvh_;  ///< the stars' faces (null when there are none)
  const detail::VertexStars& stars_;
  const std::vector<Patch>& patches_;
  const detail::FacePairFilter& filter_;
  const SelfIntersectOptions& options_;
  std::vector<FaceRef> face_;
};

/// Checks the input.
void check_input(const TriangleSoup& soup) {
  require_indices_in_range(soup);
  for (const Vec3& p : soup.vertices) {
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z())) {
      throw InputError(
          fmt::format("self-intersection test: vertex ({}, {}, {}) is not finite", p.x(), p.y(), p.z()));
    }
  }
}

/// Runs a batch of units of the search in parallel, then combines their
/// results in unit order into `counted`, `smallest` and `result`: once the
/// count reaches count_limit, units not yet started give up (those before
/// the capping point are redone), so the first count_limit pairs in search
/// order count, whatever the threads did.
template <class Unit, class Run>
void run_batch(const std::vector<Unit>& batch, const Run& run, const SelfIntersectOptions& options,
               std::size_t& counted, SmallestPairs& smallest, SelfIntersections& result) {
  const std::size_t limit = options.count_limit;
  std::vector<TaskResult> done(batch.size(), TaskResult{0, SmallestPairs(0), false});
  std::atomic<std::size_t> total{counted};
  auto body = [&](std::size_t c) { done[c] = run(batch[c], limit, &total); };
  if (options.parallel) {
    tbb::parallel_for(std::size_t{0}, batch.size(), body);
  } else {
    for (std::size_t c = 0; c < batch.size(); ++c) body(c);
  }
  for (std::size_t c = 0; c < batch.size() && !result.capped && !result.incomplete; ++c) {
    const std::size_t quota = limit - counted;
    TaskResult& r = done[c];
    if (!r.timed_out && (!r.complete || r.count > quota)) r = run(batch[c], quota, nullptr);
    counted += r.count;
    result.candidates_tested += r.tested;
    smallest.add(r.smallest);
    result.capped = counted >= limit;
    result.incomplete = r.timed_out;
  }
}

/// The certified plane groups of the faces with outside[f] == 0 (the
/// others are skipped), their faces taken out of the box search (outside[f]
/// set) into a hierarchy of pieces per group.
std::vector<Patch> patch_hierarchies(const TriangleSoup& soup, std::vector<char>& outside, bool parallel) {
  const detail::PlanarPatches certified = detail::certify_planar_patches(soup, outside);
  std::vector<Patch> patches(certified.axis.size());
  if (patches.empty()) return patches;
  for (Patch& p : patches) p.offsets.push_back(0);
  std::vector<std::vector<std::uint32_t>> owners(patches.size());
  for (std::uint32_t f = 0; f < soup.triangles.size(); ++f) {
    const std::uint32_t id = certified.patch[f];
    if (id == detail::kNoPatch || outside[f]) continue;
    Patch& p = patches[id];
    outside[f] = 1;
    p.faces.push_back(f);
    owners[id].resize(owners[id].size() + detail::append_pieces(soup, f, p.boxes), f);
    p.offsets.push_back(p.boxes.size());
  }
  std::vector<Patch> kept;
  for (std::size_t id = 0; id < patches.size(); ++id) {
    Patch& p = patches[id];
    if (p.faces.empty()) continue;
    p.box = p.boxes.front();
    for (const BoxF& b : p.boxes) {
      for (int k = 0; k < 3; ++k) {
        p.box.lo[k] = std::min(p.box.lo[k], b.lo[k]);
        p.box.hi[k] = std::max(p.box.hi[k], b.hi[k]);
      }
    }
    p.bvh.emplace(p.boxes, owners[id], parallel);
    kept.push_back(std::move(p));
  }
  return kept;
}

/// The units of the patches' search: the main hierarchy's faces against the
/// patches, then each patch's faces against the later patches.
std::vector<PatchUnit> patch_units(std::size_t main_faces, const std::vector<Patch>& patches) {
  std::vector<PatchUnit> units;
  if (patches.empty()) return units;
  for (std::size_t i = 0; i < main_faces; i += kFacesPerUnit)
    units.push_back({kMainFaces, i, std::min(main_faces, i + kFacesPerUnit)});
  for (std::size_t p = 0; p + 1 < patches.size(); ++p) {
    for (std::size_t i = 0; i < patches[p].faces.size(); i += kFacesPerUnit)
      units.push_back({p, i, std::min(patches[p].faces.size(), i + kFacesPerUnit)});
  }
  return units;
}

}  // namespace

SelfIntersections find_self_intersections(const TriangleSoup& soup, const std::vector<char>& skip,
                                          const SelfIntersectOptions& options) {
  check_input(soup);
  if (!skip.empty() && skip.size() != soup.triangles.size()) {
    throw InputError(fmt::format("self-intersection test: {} skip flags for {} triangles", skip.size(),
                                 soup.triangles.size()));
  }
  SelfIntersections result;
  if (options.count_limit == 0) return result;
  const detail::FacePairFilter filter;
  // Certified plane groups first: their faces need no star (their pairs are
  // settled) and are searched as pieces; then the stars of the other faces.
  std::vector<char> outside(skip);
  outside.resize(soup.triangles.size(), 0);
  const std::vector<Patch> patches = patch_hierarchies(soup, outside, options.parallel);
  const detail::VertexStars stars = detail::find_vertex_stars(soup, outside);
  // The hierarchy of the faces in no star and no patch; when there are
  // stars, another of theirs.
  std::optional<TriangleBvh> star_bvh;
  if (!stars.centres.empty()) {
    std::vector<char> inside(soup.triangles.size(), 1);
    for (std::size_t f = 0; f < soup.triangles.size(); ++f) {
      const bool member = stars.group[f] != detail::kNoStar;
      outside[f] = static_cast<char>(outside[f] || member);
      inside[f] = static_cast<char>(!member);
    }
    star_bvh.emplace(soup, inside, options.parallel);
  }
  const TriangleBvh bvh(soup, outside, options.parallel);
  const Search search(soup, bvh, star_bvh ? &*star_bvh : nullptr, stars, patches, filter, options);
  SmallestPairs smallest(options.max_pairs);
  std::size_t counted = 0;
  // The box search's tasks, then the patches' units, then the stars.
  TriangleBvh::TaskCursor cursor(bvh, kLeavesPerTask);
  std::vector<TriangleBvh::Task> batch;
  const auto run_task = [&](const TriangleBvh::Task& t, std::size_t limit, std::atomic<std::size_t>* total) {
    return search.run(t, limit, total);
  };
  while (!result.capped && !result.incomplete && cursor.next(kTasksPerBatch, batch))
    run_batch(batch, run_task, options, counted, smallest, result);
  const std::vector<PatchUnit> units = patch_units(bvh.size(), patches);
  const auto run_unit = [&](const PatchUnit& u, std::size_t limit, std::atomic<std::size_t>* total) {
    return search.run_patches(u, limit, total);
  };
  for (std::size_t first = 0; first < units.size() && !result.capped && !result.incomplete;
       first += kTasksPerBatch) {
    const std::vector<PatchUnit> unit_batch(
        units.begin() + static_cast<std::ptrdiff_t>(first),
        units.begin() + static_cast<std::ptrdiff_t>(std::min(units.size(), first + kTasksPerBatch)));
    run_batch(unit_batch, run_unit, options, counted, smallest, result);
  }
  if (!result.capped && !result.incomplete) search.run_stars(counted, smallest, result);
  result.count = counted;
  result.pairs = smallest.take();
  return result;
}

}  // namespace fabmesh
