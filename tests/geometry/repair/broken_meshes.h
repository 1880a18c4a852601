#pragma once
// Meshes for the repair tests, made in code: closed solids (cubes, spheres)
// and the defects of shared files made from them (docs/repair.md lists the kinds).

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include "geometry/core/soup.h"

namespace fabmesh::testing {

/// An axis-aligned box [lo, lo + size], outward, 8 vertices and 12 triangles
/// (each square split along the diagonal from its lowest corner).
inline TriangleSoup box(const Vec3& lo, const Vec3& size) {
  TriangleSoup s;
  for (int i = 0; i < 8; ++i)
    s.vertices.push_back(lo +
                         Vec3((i & 1) ? size.x() : 0.0, (i & 2) ? size.y() : 0.0, (i & 4) ? size.z() : 0.0));
  // Quads (outward, counter-clockwise seen from outside), split into two triangles.
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    s.triangles.push_back({std::uint32_t(q[0]), std::uint32_t(q[1]), std::uint32_t(q[2])});
    s.triangles.push_back({std::uint32_t(q[0]), std::uint32_t(q[2]), std::uint32_t(q[3])});
  }
  return s;
}

inline TriangleSoup cube(const Vec3& lo, double size) { return box(lo, Vec3::Constant(size)); }

/// A sphere of `radius` about `centre`: an octahedron subdivided `levels`
/// times, its vertices pushed onto the sphere; outward.
inline TriangleSoup sphere(const Vec3& centre, double radius, int levels) {
  TriangleSoup s;
  s.vertices = {Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0, 0, 1), Vec3(0, 0, -1)};
  s.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    auto middle = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      s.vertices.push_back((s.vertices[a] + s.vertices[b]).normalized());
      return mid[key] = static_cast<std::uint32_t>(s.vertices.size() - 1);
    };
    std::vector<std::array<std::uint32_t, 3>> next;
    for (const auto& t : s.triangles) {
      const std::uint32_t ab = middle(t[0], t[1]), bc = middle(t[1], t[2]), ca = middle(t[2], t[0]);
      next.push_back({t[0], ab, ca});
      next.push_back({ab, t[1], bc});
      next.push_back({ca, bc, t[2]});
      next.push_back({ab, bc, ca});
    }
    s.triangles = next;
  }
  for (Vec3& v : s.vertices) v = centre + radius * v.normalized();
  return s;
}

/// `a` and `b` in one soup (b's vertices after a's).
inline TriangleSoup join(const TriangleSoup& a, const TriangleSoup& b) {
  TriangleSoup s = a;
  const auto base = static_cast<std::uint32_t>(a.vertices.size());
  s.vertices.insert(s.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (const auto& t : b.triangles) s.triangles.push_back({base + t[0], base + t[1], base + t[2]});
  return s;
}

/// `s` with every face reversed.
inline TriangleSoup reversed(TriangleSoup s) {
  for (auto& t : s.triangles) std::swap(t[1], t[2]);
  return s;
}

/// `s` as an STL stores it: every triangle with three vertices of its own.
inline TriangleSoup unshared(const TriangleSoup& s) {
  TriangleSoup out;
  for (const auto& t : s.triangles) {
    const auto base = static_cast<std::uint32_t>(out.vertices.size());
    for (const std::uint32_t v : t) out.vertices.push_back(s.vertices[v]);
    out.triangles.push_back({base, base + 1, base + 2});
  }
  return out;
}

/// Every vertex moved by a random offset of at most `amount` per axis (fixed seed).
inline TriangleSoup jittered(TriangleSoup s, double amount, unsigned seed = 7) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> offset(-amount, amount);
  for (Vec3& v : s.vertices) v += Vec3(offset(random), offset(random), offset(random));
  return s;
}

/// `s` without the faces whose index is in `faces`.
inline TriangleSoup without(TriangleSoup s, const std::vector<std::size_t>& faces) {
  std::vector<std::array<std::uint32_t, 3>> kept;
  for (std::size_t f = 0; f < s.triangles.size(); ++f) {
    bool drop = false;
    for (const std::size_t g : faces) drop = drop || g == f;
    if (!drop) kept.push_back(s.triangles[f]);
  }
  s.triangles = kept;
  return s;
}

}  // namespace fabmesh::testing
