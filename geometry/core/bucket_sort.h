#pragma once
// Sorting by a small integer key first (a vertex index): a counting sort
// into buckets, then each bucket by the rest of the order. Linear where a
// comparison sort of mesh sides or faces is n log n; stable.

#include <algorithm>
#include <cstddef>
#include <iterator>
#include <vector>

namespace fabmesh {

/// Turns counts[b + 1] (the items of bucket b) into the buckets' offsets:
/// bucket b is then [counts[b], counts[b + 1]).
inline void bucket_offsets(std::vector<std::size_t>& counts) {
  for (std::size_t b = 1; b < counts.size(); ++b) counts[b] += counts[b - 1];
}

/// Sorts each bucket [start[b], start[b + 1]) of `items` by `less`, stably:
/// insertion sort for the usual few items, std::stable_sort for a large bucket.
template <class T, class Less>
void sort_buckets(std::vector<T>& items, const std::vector<std::size_t>& start, Less less) {
  constexpr std::ptrdiff_t kInsertion = 32;
  for (std::size_t b = 0; b + 1 < start.size(); ++b) {
    const auto first = items.begin() + static_cast<std::ptrdiff_t>(start[b]);
    const auto last = items.begin() + static_cast<std::ptrdiff_t>(start[b + 1]);
    if (last - first > kInsertion) {
      std::stable_sort(first, last, less);
      continue;
    }
    for (auto i = first + (first == last ? 0 : 1); i < last; ++i) {
      T x = *i;
      auto j = i;
      for (; j > first && less(x, *(j - 1)); --j) *j = *(j - 1);
      *j = x;
    }
  }
}

}  // namespace fabmesh
