#pragma once
// A bounding-volume hierarchy over the axis-aligned boxes of a soup's
// triangles: the broad phase of the self-intersection test. Triangles are
// sorted along a Morton curve of their box centres and grouped kLeafSize to
// a leaf; the tree over the leaves is a perfect binary tree stored as an
// array (node 1 the root, node i with children 2i and 2i + 1, leaf l at node
// leaf_base + l). Boxes are floats rounded outwards, so every pair of
// triangles whose exact (closed) boxes overlap is reported; a few pairs whose
// exact boxes only nearly touch may be reported too.
//
// Besides the search of all overlapping pairs, the hierarchy answers box
// queries: the triangles whose boxes overlap a given box.
//
// Internal to geometry/validation (validate.h is the public entry); the
// tests and the benchmarks include it to check and time this part alone.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/core/soup.h"

namespace fabmesh {

/// A closed axis-aligned box in single precision. An empty box has lo > hi.
struct BoxF {
  float lo[3];
  float hi[3];
};

/// Whether two closed boxes overlap (touching counts). One branch, not six:
/// the outcome is hard to predict in the hierarchy's inner loops.
inline bool overlap(const BoxF& a, const BoxF& b) {
  return static_cast<bool>(static_cast<int>(a.lo[0] <= b.hi[0]) & static_cast<int>(b.lo[0] <= a.hi[0]) &
                           static_cast<int>(a.lo[1] <= b.hi[1]) & static_cast<int>(b.lo[1] <= a.hi[1]) &
                           static_cast<int>(a.lo[2] <= b.hi[2]) & static_cast<int>(b.lo[2] <= a.hi[2]));
}

/// The box of face f of `soup`, its coordinates rounded outwards.
/// \pre indices in range.
BoxF triangle_box(const TriangleSoup& soup, std::uint32_t f);

/// The box from lo to hi (doubles), its coordinates rounded outwards to floats.
BoxF rounded_box(const Vec3& lo, const Vec3& hi);

class TriangleBvh {
 public:
  static constexpr std::size_t kLeafSize = 4;  ///< triangles per leaf: one lane each

  /// Builds the hierarchy over the triangles f of `soup` with skip[f] == 0
  /// (all of them when `skip` is empty), using all cores when `parallel`.
  /// The result does not depend on the number of threads.
  /// \pre indices in range, coordinates finite.
  TriangleBvh(const TriangleSoup& soup, const std::vector<char>& skip, bool parallel);

  /// Builds the hierarchy over given boxes, box i standing for face ids[i]
  /// (ids may repeat: pieces of one face), using all cores when `parallel`.
  /// The result does not depend on the number of threads.
  /// \pre boxes.size() == ids.size(), every box finite and not empty.
  TriangleBvh(std::vector<BoxF> boxes, const std::vector<std::uint32_t>& ids, bool parallel);

  /// Number of triangles in the hierarchy.
  std::size_t size() const { return faces_.size(); }
  /// Number of (non-empty) leaves: ceil(size() / kLeafSize).
  std::size_t leaf_count() const { return (faces_.size() + kLeafSize - 1) / kLeafSize; }

  /// A unit of the search: the pairs within one subtree (b == a) or between
  /// two disjoint subtrees a < b, as node numbers.
  struct Task {
    std::size_t a, b;
  };

  /// The search split into tasks of about `leaves_per_task` leaves each, in
  /// a fixed order, a batch at a time (a pile of overlapping faces has
  /// quadratically many): over all tasks, run() visits every pair of
  /// triangles whose boxes overlap exactly once.
  class TaskCursor {
   public:
    TaskCursor(const TriangleBvh& bvh, std::size_t leaves_per_task);
    /// Replaces `out` with the next (at most) `n` tasks; false when none are left.
    bool next(std::size_t n, std::vector<Task>& out);

   private:
    const TriangleBvh& bvh_;
    std::size_t level_;        ///< first node of the depth at which tasks stop splitting
    std::vector<Task> stack_;  ///< pending subproblems, the next on top (a == b: within a)
  };

  /// Calls visit(i, j) for each pair of sorted positions i < j in `task`
  /// whose boxes overlap, in an order that depends only on the soup.
  template <class Visit>
  void run(const Task& task, Visit&& visit) const {
    if (task.a == task.b) {
      self(task.a, visit);
    } else {
      pair(task.a, task.b, visit);
    }
  }

  /// Calls visit(f) for each face f whose box overlaps `box`, in an order
  /// that depends only on the soup.
  template <class Visit>
  void for_each_overlapping(const BoxF& box, Visit&& visit) const {
    std::vector<std::size_t> stack{1};
    while (!stack.empty()) {
      const std::size_t n = stack.back();
      stack.pop_back();
      if (!overlap(nodes_[n], box)) continue;
      if (n < leaf_base_) {
        stack.push_back(2 * n + 1);
        stack.push_back(2 * n);
        continue;
      }
      const std::size_t first = (n - leaf_base_) * kLeafSize;
      for (std::size_t i = first; i < std::min(first + kLeafSize, faces_.size()); ++i) {
        if (overlap(box_at(i), box)) visit(faces_[i]);
      }
    }
  }

  /// The face at sorted position i.
  std::uint32_t face(std::size_t i) const { return faces_[i]; }

 private:
  template <class Visit>
  void self(std::size_t n, Visit& visit) const {
    if (nodes_[n].lo[0] > nodes_[n].hi[0]) return;  // empty
    if (n >= leaf_base_) {
      leaf_pairs(n - leaf_base_, n - leaf_base_, visit);
      return;
    }
    self(2 * n, visit);
    self(2 * n + 1, visit);
    pair(2 * n, 2 * n + 1, visit);
  }

  template <class Visit>
  void pair(std::size_t a, std::size_t b, Visit& visit) const {
    if (!overlap(nodes_[a], nodes_[b])) return;
    if (a >= leaf_base_) {  // both are leaves: the tree is perfect
      leaf_pairs(a - leaf_base_, b - leaf_base_, visit);
      return;
    }
    pair(2 * a, 2 * b, visit);
    pair(2 * a, 2 * b + 1, visit);
    pair(2 * a + 1, 2 * b, visit);
    pair(2 * a + 1, 2 * b + 1, visit);
  }

  /// Four lanes of floats (GCC/Clang vector extension: SSE on x86-64, NEON on ARM).
  typedef float Lanes __attribute__((vector_size(16)));
  typedef int LaneMask __attribute__((vector_size(16)));

  /// The boxes of one leaf's kLeafSize triangles, one lane each (empty lanes
  /// hold empty boxes), so that a box is tested against a whole leaf at once.
  struct LeafBoxes {
    Lanes lo[3];
    Lanes hi[3];
  };

  template <class Visit>
  void leaf_pairs(std::size_t a, std::size_t b, Visit& visit) const {
    const std::size_t a0 = a * kLeafSize;
    const std::size_t a1 = std::min(a0 + kLeafSize, faces_.size());
    const std::size_t b0 = b * kLeafSize;
    const LeafBoxes& other = leaf_boxes_[b];
    for (std::size_t i = a0; i < a1; ++i) {
      const BoxF x = box_at(i);
      LaneMask m = (other.lo[0] <= x.hi[0]) & (other.hi[0] >= x.lo[0]) & (other.lo[1] <= x.hi[1]) &
                   (other.hi[1] >= x.lo[1]) & (other.lo[2] <= x.hi[2]) & (other.hi[2] >= x.lo[2]);
      unsigned bits = (m[0] & 1u) | (m[1] & 2u) | (m[2] & 4u) | (m[3] & 8u);
      if (a == b) bits &= ~((2u << (i - a0)) - 1);  // within a leaf: only the triangles after i
      for (; bits != 0; bits &= bits - 1) visit(i, b0 + static_cast<std::size_t>(__builtin_ctz(bits)));
    }
  }

  /// The box at sorted position i, from its leaf's lanes (kept once: a
  /// second array of the boxes would be 24 bytes a face).
  BoxF box_at(std::size_t i) const {
    const LeafBoxes& leaf = leaf_boxes_[i / kLeafSize];
    const std::size_t lane = i % kLeafSize;
    return {{leaf.lo[0][lane], leaf.lo[1][lane], leaf.lo[2][lane]},
            {leaf.hi[0][lane], leaf.hi[1][lane], leaf.hi[2][lane]}};
  }

  /// Sorts `box` (box i of face ids[i]) along the Morton curve and builds the tree.
  void build(std::vector<BoxF> box, const std::vector<std::uint32_t>& ids, bool parallel);

  std::vector<std::uint32_t> faces_;   ///< face index at each sorted position
  std::vector<BoxF> nodes_;            ///< 2 * leaf_base_ node boxes (index 0 unused)
  std::vector<LeafBoxes> leaf_boxes_;  ///< the triangle boxes of each leaf, in lanes
  std::size_t leaf_base_ = 1;          ///< power of two >= leaf_count()
};

}  // namespace fabmesh
