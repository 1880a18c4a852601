#include "geometry/validation/detail/self_intersect_reference.h"

#include "geometry/core/errors.h"

// Parallel box intersection needs this before any CGAL header; TBB is linked
// to fabmesh::geometry.
#ifndef CGAL_LINKED_WITH_TBB
#define CGAL_LINKED_WITH_TBB
#endif
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <fmt/format.h>
#include <tbb/concurrent_vector.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <random>

namespace fabmesh {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Segment = Kernel::Segment_3;
using Triangle = Kernel::Triangle_3;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::uint32_t,
                                                      CGAL::Box_intersection_d::ID_FROM_BOX_ADDRESS>;
using Face = std::array<std::uint32_t, 3>;

/// Thrown from the box callback to stop the search at the count limit.
struct LimitReached {};

/// Exact test of two faces, allowing them to meet at what they share by
/// index (the same case analysis as CGAL's do_faces_intersect, on a soup).
class FacePairTest {
 public:
  explicit FacePairTest(const TriangleSoup& soup) : soup_(soup) {}

  bool operator()(std::uint32_t f, std::uint32_t g) const {
    const Face& a = soup_.triangles[f];
    const Face& b = soup_.triangles[g];
    int shared = 0;
    int ia = -1;
    int ib = -1;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        if (a[i] == b[j]) {
          ++shared;
          ia = i;
          ib = j;
        }
      }
    }
    if (shared >= 3) return false;  // the same face: validation reports duplicates separately
    if (shared == 2) return shared_edge_overlap(a, b);
    if (shared == 1) return shared_vertex_overlap(a, b, ia, ib);
    return CGAL::do_intersect(triangle(a), triangle(b));
  }

 private:
  Point point(std::uint32_t v) const {
    const Vec3& p = soup_.vertices[v];
    return {p.x(), p.y(), p.z()};
  }
  Triangle triangle(const Face& t) const { return {point(t[0]), point(t[1]), point(t[2])}; }

  /// Faces sharing edge pq meet elsewhere iff they are coplanar and their
  /// third vertices lie on the same side of pq.
  bool shared_edge_overlap(const Face& a, const Face& b) const {
    std::uint32_t r = a[0];
    for (const std::uint32_t v : a) {
      if (v != b[0] && v != b[1] && v != b[2]) r = v;
    }
    std::uint32_t s = b[0];
    for (const std::uint32_t v : b) {
      if (v != a[0] && v != a[1] && v != a[2]) s = v;
    }
    std::uint32_t p = 0;
    std::uint32_t q = 0;
    int k = 0;
    for (const std::uint32_t v : a) {
      if (v != r) (k++ == 0 ? p : q) = v;
    }
    const Point pp = point(p), pq = point(q), pr = point(r), ps = point(s);
    return CGAL::coplanar(pp, pq, pr, ps) && CGAL::coplanar_orientation(pp, pq, pr, ps) == CGAL::POSITIVE;
  }

  /// Faces sharing one vertex meet elsewhere iff the edge opposite the shared
  /// vertex in one face touches the other face.
  bool shared_vertex_overlap(const Face& a, const Face& b, int ia, int ib) const {
    const Segment sa(point(a[(ia + 1) % 3]), point(a[(ia + 2) % 3]));
    const Segment sb(point(b[(ib + 1) % 3]), point(b[(ib + 2) % 3]));
    return CGAL::do_intersect(triangle(a), sb) || CGAL::do_intersect(triangle(b), sa);
  }

  const TriangleSoup& soup_;
};

}  // namespace

bool faces_intersect_exact(const TriangleSoup& soup, std::uint32_t f, std::uint32_t g) {
  return FacePairTest(soup)(f, g);
}

SelfIntersections find_self_intersections_reference(const TriangleSoup& soup, const std::vector<char>& skip,
                                                    const SelfIntersectOptions& options) {
  require_indices_in_range(soup);
  for (const Vec3& p : soup.vertices) {
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z())) {
      throw InputError(
          fmt::format("self-intersection test: vertex ({}, {}, {}) is not finite", p.x(), p.y(), p.z()));
    }
  }
  std::vector<Box> boxes;
  boxes.reserve(soup.triangles.size());
  for (std::uint32_t f = 0; f < soup.triangles.size(); ++f) {
    if (!skip.empty() && skip.at(f)) continue;
    CGAL::Bbox_3 bbox;
    for (const std::uint32_t v : soup.triangles[f]) {
      const Vec3& p = soup.vertices[v];
      bbox += CGAL::Bbox_3(p.x(), p.y(), p.z(), p.x(), p.y(), p.z());
    }
    boxes.emplace_back(bbox, f);
  }
  std::vector<const Box*> box_ptr;
  box_ptr.reserve(boxes.size());
  for (const Box& b : boxes) box_ptr.push_back(&b);

  const FacePairTest intersect(soup);
  std::atomic<std::size_t> count{0};
  tbb::concurrent_vector<std::pair<std::uint32_t, std::uint32_t>> found;
  // Keep a bounded number of pairs in memory; count them all.
  const std::size_t keep = std::max<std::size_t>(options.max_pairs, 100000);
  auto callback = [&](const Box* x, const Box* y) {
    std::uint32_t f = x->info();
    std::uint32_t g = y->info();
    if (!intersect(f, g)) return;
    if (f > g) std::swap(f, g);
    const std::size_t before = count.fetch_add(1);
    if (before < keep) found.push_back({f, g});
    if (before + 1 >= options.count_limit) throw LimitReached{};
  };
  const std::ptrdiff_t cutoff = 2000;
  SelfIntersections result;
  if (options.count_limit == 0) return result;
  try {
    if (options.parallel) {
      // A fixed shuffle balances the parallel slices (as CGAL does) and keeps runs reproducible.
      std::mt19937 rng(0);
      std::shuffle(box_ptr.begin(), box_ptr.end(), rng);
      CGAL::box_self_intersection_d<CGAL::Parallel_tag>(box_ptr.begin(), box_ptr.end(), callback, cutoff);
    } else {
      CGAL::box_self_intersection_d<CGAL::Sequential_tag>(box_ptr.begin(), box_ptr.end(), callback, cutoff);
    }
  } catch (const LimitReached&) {
    result.capped = true;
  }
  result.count = std::min(count.load(), options.count_limit);
  result.pairs.assign(found.begin(), found.end());
  std::sort(result.pairs.begin(), result.pairs.end());
  if (result.pairs.size() > options.max_pairs) result.pairs.resize(options.max_pairs);
  return result;
}

}  // namespace fabmesh
