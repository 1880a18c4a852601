#pragma once
// Boxes around sets of directions (points of the unit sphere) as seen from
// a vertex v: the directions from v to the points of a face. For a face
// containing v they form a great circle arc (an "arc"); for any other face a
// spherical triangle (a "cone"). Two faces meet at a point x != v only if
// the direction of x - v is in both sets, so boxes around them that do not
// overlap prove that the faces do not meet away from v (vertex_star.h).
//
// The boxes are tight: the extreme coordinates of an arc or a cone are
// found on its edges (the point of a great circle arc farthest along an
// axis) or inside it (an axis direction in the cone), not bounded by the
// hull of the corners pushed outwards, which for a cone spanning tens of
// degrees overlaps a wide band of a fan's arcs. Every box contains the
// exact set (rounding errors are bounded and covered by kDirectionMargin).
//
// Internal to geometry/validation (validate.h is the public entry).

#include <array>
#include <cstdint>
#include <vector>

#include "geometry/core/types.h"

namespace fabmesh::detail {

/// A closed box in direction space (around the unit sphere).
struct DirectionBox {
  double lo[3];
  double hi[3];
};

/// Margin added to every direction box: far above the rounding errors of
/// the bounds (<= 1e-8), far below the arc of a face in any fan that fits
/// in memory (a 10^6-face fan: arcs of about 3e-6).
constexpr double kDirectionMargin = 1e-7;

/// The box of every direction: the unit sphere's box, grown by the margin.
DirectionBox sphere_box();

/// Whether two boxes overlap (touching counts).
bool overlap(const DirectionBox& a, const DirectionBox& b);

/// A box containing the directions from corner k of face `p` to its other
/// points (the sphere's box when the face is too degenerate for a bound).
DirectionBox arc_box(const std::array<Vec3, 3>& p, int k);

/// A box containing the directions from v to the points of face `p`, which
/// may be any face (the sphere's box when one of its corners is v, or too
/// near it or too far around it for a bound).
DirectionBox cone_box(const Vec3& v, const std::array<Vec3, 3>& p);

/// A hierarchy of direction boxes answering box queries: the boxes sorted
/// along a Morton curve of their centres, four to a leaf, a perfect binary
/// tree over the leaves stored as an array (node 1 the root).
class DirectionTree {
 public:
  /// \pre `boxes` outlives the tree.
  explicit DirectionTree(const std::vector<DirectionBox>& boxes);

  /// Calls visit(i) for each box i overlapping `box`, in an order that
  /// depends only on the boxes, until visit returns false; false then.
  template <class Visit>
  bool for_each_overlapping(const DirectionBox& box, Visit&& visit) const {
    std::vector<std::size_t> stack{1};
    while (!stack.empty()) {
      const std::size_t node = stack.back();
      stack.pop_back();
      if (!overlap(nodes_[node], box)) continue;
      if (node < leaf_base_) {
        stack.push_back(2 * node + 1);
        stack.push_back(2 * node);
        continue;
      }
      const std::size_t first = (node - leaf_base_) * kLeaf;
      for (std::size_t k = first; k < first + kLeaf && k < order_.size(); ++k) {
        if (overlap(boxes_[order_[k]], box) && !visit(order_[k])) return false;
      }
    }
    return true;
  }

 private:
  static constexpr std::size_t kLeaf = 4;
  const std::vector<DirectionBox>& boxes_;
  std::vector<std::uint32_t> order_;  ///< box indices in Morton order
  std::vector<DirectionBox> nodes_;   ///< 2 * leaf_base_ node boxes (index 0 unused)
  std::size_t leaf_base_ = 1;         ///< power of two >= the number of leaves
};

}  // namespace fabmesh::detail
