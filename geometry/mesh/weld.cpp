// Welding. Both modes first find, for every vertex, the lowest index of the
// vertices at exactly its position (exact_groups: a hash partition into
// cache-sized buckets, then one small hash table per bucket; linear). The
// tolerance mode then unites those positions on a grid (weld_grid.cpp).

#include "geometry/mesh/weld.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

#include "geometry/core/error_checks.h"
#include "geometry/mesh/hash_mix.h"
#include "geometry/mesh/weld_grid.h"

namespace fabmesh {
namespace {

bool finite(const Vec3& p) { return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()); }

/// A vertex in the bucket partition: its coordinates with -0.0 turned into
/// +0.0 (so that equal coordinates have equal bits), its index and hash.
struct Entry {
  double c[3];
  std::uint32_t index;
  std::uint32_t hash;
};

/// The same for a mesh whose coordinates are all floats (every STL): half
/// the size, the hash computed again where it is needed. Floats are equal
/// exactly when the doubles they convert to are.
struct FloatEntry {
  float c[3];
  std::uint32_t index;
};

template <class T>
std::uint64_t coordinate_hash(const T (&c)[3]) {
  std::uint64_t h = 0;
  for (const T x : c) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &x, sizeof x);
    h = mix64(h ^ bits);
  }
  return h;
}

Entry make_entry(const Vec3& p, std::uint32_t index, std::uint64_t& hash, Entry* /*type*/) {
  Entry e{{p.x() + 0.0, p.y() + 0.0, p.z() + 0.0}, index, 0};
  hash = coordinate_hash(e.c);
  e.hash = static_cast<std::uint32_t>(hash);
  return e;
}

FloatEntry make_entry(const Vec3& p, std::uint32_t index, std::uint64_t& hash, FloatEntry* /*type*/) {
  FloatEntry e{
      {static_cast<float>(p.x()) + 0.0F, static_cast<float>(p.y()) + 0.0F, static_cast<float>(p.z()) + 0.0F},
      index};
  hash = coordinate_hash(e.c);
  return e;
}

std::uint32_t slot_hash(const Entry& e) { return e.hash; }
std::uint32_t slot_hash(const FloatEntry& e) { return static_cast<std::uint32_t>(coordinate_hash(e.c)); }

bool same_position(const Entry& a, const Entry& b) {
  return a.hash == b.hash && a.c[0] == b.c[0] && a.c[1] == b.c[1] && a.c[2] == b.c[2];
}
bool same_position(const FloatEntry& a, const FloatEntry& b) {
  return a.c[0] == b.c[0] && a.c[1] == b.c[1] && a.c[2] == b.c[2];
}

constexpr std::size_t kBlock = std::size_t{1} << 16;  ///< vertices per partition block (fixed: determinism)

template <class Body>
void parallel_blocks(std::size_t blocks, const Body& body) {
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) { body(b); });
}

/// Whether every finite coordinate of `vertices` is a float exactly.
bool all_floats(const std::vector<Vec3>& vertices) {
  const std::size_t n = vertices.size();
  const std::size_t blocks = (n + kBlock - 1) / kBlock;
  std::vector<char> ok(blocks, 1);
  parallel_blocks(blocks, [&](std::size_t b) {
    for (std::size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i) {
      const Vec3& p = vertices[i];
      if (!finite(p)) continue;
      for (int k = 0; k < 3; ++k) {
        if (static_cast<double>(static_cast<float>(p[k])) != p[k]) {
          ok[b] = 0;
          return;
        }
      }
    }
  });
  return std::all_of(ok.begin(), ok.end(), [](char c) { return c != 0; });
}

/// Finds equal positions within one bucket: entries arrive in ascending
/// index order, so the first of each position is the lowest index.
template <class E>
void weld_bucket(const E* entries, std::size_t count, std::vector<std::uint32_t>& table,
                 std::vector<std::uint32_t>& rep) {
  std::size_t size = 16;
  while (size < 2 * count) size *= 2;
  table.assign(size, 0);
  const std::size_t mask = size - 1;
  for (std::size_t k = 0; k < count; ++k) {
    const E& e = entries[k];
    for (std::size_t s = slot_hash(e) & mask;; s = (s + 1) & mask) {
      if (table[s] == 0) {
        table[s] = static_cast<std::uint32_t>(k + 1);
        break;
      }
      const E& o = entries[table[s] - 1];
      if (same_position(o, e)) {
        rep[e.index] = o.index;
        break;
      }
    }
  }
}

/// rep[i] = the lowest index of the vertices at exactly the position of
/// vertex i (i itself when that position is not finite), through entries
/// of type E.
template <class E>
std::vector<std::uint32_t> exact_groups(const std::vector<Vec3>& vertices) {
  const std::size_t n = vertices.size();
  std::vector<std::uint32_t> rep(n);
  const std::size_t blocks = (n + kBlock - 1) / kBlock;
  int bits = 0;  // 2^bits buckets of 8192 to 16384 vertices: few enough output streams for the scatter
  while (bits < 16 && (n >> bits) > 16384) ++bits;
  const std::size_t buckets = std::size_t{1} << bits;
  auto bucket_of = [bits](std::uint64_t h) {
    return bits == 0 ? std::size_t{0} : std::size_t(h >> (64 - bits));
  };
  E* const type = nullptr;

  // Stable counting sort of the finite vertices by bucket, block by block.
  std::vector<std::size_t> offset(blocks * buckets, 0);
  parallel_blocks(blocks, [&](std::size_t b) {
    std::size_t* count = &offset[b * buckets];
    for (std::size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i) {
      rep[i] = static_cast<std::uint32_t>(i);
      if (!finite(vertices[i])) continue;
      std::uint64_t h = 0;
      make_entry(vertices[i], 0, h, type);
      ++count[bucket_of(h)];
    }
  });
  std::vector<std::size_t> bucket_start(buckets + 1, 0);
  std::size_t total = 0;
  for (std::size_t k = 0; k < buckets; ++k) {
    bucket_start[k] = total;
    for (std::size_t b = 0; b < blocks; ++b) {
      const std::size_t c = offset[b * buckets + k];
      offset[b * buckets + k] = total;
      total += c;
    }
  }
  bucket_start[buckets] = total;
  // Uninitialised: the scatter writes every entry (zeroing them first costs as much).
  const std::unique_ptr<E[]> entries(new E[total]);
  parallel_blocks(blocks, [&](std::size_t b) {
    std::size_t* next = &offset[b * buckets];
    for (std::size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i) {
      if (!finite(vertices[i])) continue;
      std::uint64_t h = 0;
      const E e = make_entry(vertices[i], static_cast<std::uint32_t>(i), h, type);
      entries[next[bucket_of(h)]++] = e;
    }
  });
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, buckets, 16), [&](const tbb::blocked_range<std::size_t>& r) {
        std::vector<std::uint32_t> table;
        for (std::size_t k = r.begin(); k != r.end(); ++k) {
          weld_bucket(entries.get() + bucket_start[k], bucket_start[k + 1] - bucket_start[k], table, rep);
        }
      });
  return rep;
}

/// exact_groups through the smaller entries when every coordinate is a
/// float (16 bytes a vertex instead of 32: 48 MB less for a 1e6-triangle
/// STL's 3e6 vertices); the same groups either way.
std::vector<std::uint32_t> exact_groups(const std::vector<Vec3>& vertices) {
  return all_floats(vertices) ? exact_groups<FloatEntry>(vertices) : exact_groups<Entry>(vertices);
}

}  // namespace

WeldResult weld(const TriangleSoup& soup, const WeldOptions& options) {
  if (options.tolerance != 0.0) require_positive("weld tolerance", options.tolerance);
  require_indices_in_range(soup);
  std::vector<std::uint32_t> rep = exact_groups(soup.vertices);
  if (options.tolerance > 0.0) rep = tolerance_groups(soup.vertices, rep, options.tolerance);
  WeldResult result;
  const std::size_t n = soup.vertices.size();
  // Representatives are numbered in index order, block by block in parallel;
  // rep[i] <= i is a representative, numbered before its members look it up.
  const std::size_t blocks = (n + kBlock - 1) / kBlock;
  std::vector<std::size_t> first(blocks + 1, 0);
  parallel_blocks(blocks, [&](std::size_t b) {
    for (std::size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i) first[b + 1] += rep[i] == i;
  });
  for (std::size_t b = 0; b < blocks; ++b) first[b + 1] += first[b];
  result.soup.vertices.resize(first[blocks]);
  result.representatives.resize(first[blocks]);
  std::vector<std::uint32_t> new_index(n);
  parallel_blocks(blocks, [&](std::size_t b) {
    std::size_t next = first[b];
    for (std::size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i) {
      if (rep[i] != i) continue;
      new_index[i] = static_cast<std::uint32_t>(next);
      result.representatives[next] = static_cast<std::uint32_t>(i);
      result.soup.vertices[next++] = soup.vertices[i];
    }
  });
  parallel_blocks(blocks, [&](std::size_t b) {
    for (std::size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i) {
      if (rep[i] != i) new_index[i] = new_index[rep[i]];
    }
  });
  result.soup.triangles.resize(soup.triangles.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, soup.triangles.size(), 65536),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t f = r.begin(); f != r.end(); ++f) {
                        const auto& t = soup.triangles[f];
                        result.soup.triangles[f] = {new_index[t[0]], new_index[t[1]], new_index[t[2]]};
                      }
                    });
  result.merged_vertices = n - result.soup.vertices.size();
  return result;
}

}  // namespace fabmesh
