#pragma once
// Shards: deterministic slices of a batch's variants for separate processes
// (a Slurm job array). Variant i (0-based, manifest order) belongs to shard i mod N.

#include <cstddef>
#include <string>

namespace fabmesh {

/// The most shards a batch may have (N of --shard I/N).
inline constexpr std::size_t kMaxShards = 1000000;

/// Shard `index` of `count` (0 <= index < count <= kMaxShards).
struct Shard {
  std::size_t index = 0;
  std::size_t count = 1;
  /// True when variant `i` belongs to this shard.
  bool owns(std::size_t i) const { return i % count == index; }
  /// How many of `variants` belong to this shard.
  std::size_t size_of(std::size_t variants) const {
    return variants > index ? (variants - index + count - 1) / count : 0;
  }
  /// "I-of-N", for file names.
  std::string tag() const { return std::to_string(index) + "-of-" + std::to_string(count); }
};

/// Parses "I/N" (0 <= I < N <= kMaxShards). \throw InputError naming the text
Shard parse_shard(const std::string& text);

}  // namespace fabmesh
