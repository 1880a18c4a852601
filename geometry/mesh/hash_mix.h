#pragma once
// The hash mixing step of the welds (private to weld.cpp and weld_grid.cpp).

#include <cstdint>

namespace fabmesh {

/// murmur3's 64-bit finalizer: every bit of `h` affects every bit of the
/// result. The welds fold in one coordinate at a time: h = mix64(h ^ bits).
inline std::uint64_t mix64(std::uint64_t h) {
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdULL;
  h ^= h >> 33;
  h *= 0xc4ceb9fe1a85ec53ULL;
  h ^= h >> 33;
  return h;
}

}  // namespace fabmesh
