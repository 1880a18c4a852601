#pragma once
// Union-find over the dense indices 0..n-1: the one implementation the
// topology analyses, the welds and the tessellation share.

#include <algorithm>
#include <cstddef>
#include <numeric>
#include <vector>

namespace fabmesh {

/// Disjoint sets of the indices 0..n-1 with path halving. The smallest index
/// of a set represents it, so representatives are independent of the order
/// of the unions (results stay deterministic).
template <class Index = std::size_t>
class DisjointSets {
 public:
  explicit DisjointSets(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), Index{0}); }

  std::size_t size() const { return parent_.size(); }

  /// The representative (smallest member) of the set holding `i`.
  Index find(Index i) {
    while (parent_[i] != i) {
      parent_[i] = parent_[parent_[i]];
      i = parent_[i];
    }
    return i;
  }

  /// Merges the sets of `a` and `b`; returns false when they were one set already.
  bool unite(Index a, Index b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    parent_[std::max(a, b)] = std::min(a, b);
    return true;
  }

 private:
  std::vector<Index> parent_;
};

}  // namespace fabmesh
