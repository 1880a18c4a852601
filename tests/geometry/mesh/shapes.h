#pragma once
// Test shapes built in code: closed, outward-oriented soups with shared
// vertices, and helpers to break them in precise ways.

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <tuple>
#include <vector>

#include "geometry/core/soup.h"

namespace fabmesh::test {

/// Appends `other` to `soup` (indices shifted; no vertex shared).
inline void append(TriangleSoup& soup, const TriangleSoup& other) {
  const auto base = static_cast<std::uint32_t>(soup.vertices.size());
  soup.vertices.insert(soup.vertices.end(), other.vertices.begin(), other.vertices.end());
  for (const auto& t : other.triangles) soup.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
}

/// The axis-aligned box [lo, hi]: 8 vertices, 12 outward triangles.
inline TriangleSoup box(const Vec3& lo = Vec3(0, 0, 0), const Vec3& hi = Vec3(1, 1, 1)) {
  TriangleSoup s;
  for (int i = 0; i < 8; ++i) {
    s.vertices.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
  }
  // Vertex i has x from bit 0, y from bit 1, z from bit 2.
  s.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6},   // z = lo, z = hi
                 {0, 1, 4}, {1, 5, 4}, {2, 6, 3}, {3, 6, 7},   // y = lo, y = hi
                 {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};  // x = lo, x = hi
  return s;
}

/// A tetrahedron with one vertex at `apex` and the others on the side
/// `direction` (+1 above, -1 below), outward oriented.
inline TriangleSoup tetrahedron(const Vec3& apex, double size, double direction) {
  TriangleSoup s;
  s.vertices = {apex, apex + Vec3(size, 0, direction * size), apex + Vec3(0, size, direction * size),
                apex + Vec3(-size, -size, direction * size)};
  s.triangles = {{0, 2, 1}, {0, 3, 2}, {0, 1, 3}, {1, 2, 3}};
  const Vec3& a = s.vertices[0];
  const double volume6 = (s.vertices[1] - a).cross(s.vertices[2] - a).dot(s.vertices[3] - a);
  if (volume6 < 0) {  // face {1, 2, 3} points towards the apex: flip all
    for (auto& t : s.triangles) std::swap(t[1], t[2]);
  }
  return s;
}

/// A torus about the z axis (radii R > r), nu x nv quads split in two.
inline TriangleSoup torus(double R, double r, int nu, int nv) {
  TriangleSoup s;
  const double pi = std::acos(-1.0);
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * pi * i / nu;
      const double v = 2 * pi * j / nv;
      s.vertices.emplace_back((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u),
                              r * std::sin(v));
    }
  }
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>((i % nu) * nv + (j % nv)); };
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      s.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return s;
}

/// A UV sphere of radius r with single pole vertices (no zero-area faces).
inline TriangleSoup sphere(double r, int slices, int stacks) {
  TriangleSoup s;
  const double pi = std::acos(-1.0);
  s.vertices.emplace_back(0, 0, -r);  // south pole: 0
  for (int k = 1; k < stacks; ++k) {
    const double phi = -pi / 2 + pi * k / stacks;
    for (int i = 0; i < slices; ++i) {
      const double u = 2 * pi * i / slices;
      s.vertices.emplace_back(r * std::cos(phi) * std::cos(u), r * std::cos(phi) * std::sin(u),
                              r * std::sin(phi));
    }
  }
  s.vertices.emplace_back(0, 0, r);  // north pole
  const auto north = static_cast<std::uint32_t>(s.vertices.size() - 1);
  auto id = [&](int k, int i) { return static_cast<std::uint32_t>(1 + (k - 1) * slices + (i % slices)); };
  for (int i = 0; i < slices; ++i) {
    s.triangles.push_back({0, id(1, i + 1), id(1, i)});
    s.triangles.push_back({north, id(stacks - 1, i), id(stacks - 1, i + 1)});
    for (int k = 1; k + 1 < stacks; ++k) {
      s.triangles.push_back({id(k, i), id(k, i + 1), id(k + 1, i + 1)});
      s.triangles.push_back({id(k, i), id(k + 1, i + 1), id(k + 1, i)});
    }
  }
  return s;
}

/// The closed surface of a union of unit voxels (cells (x, y, z) in `cells`),
/// vertices shared by integer position. Voxels must not touch only along an
/// edge or at a corner (that surface would be non-manifold).
inline TriangleSoup voxels(const std::set<std::tuple<int, int, int>>& cells) {
  TriangleSoup s;
  std::map<std::tuple<int, int, int>, std::uint32_t> index;
  auto vertex = [&](int x, int y, int z) {
    const auto key = std::make_tuple(x, y, z);
    const auto it = index.find(key);
    if (it != index.end()) return it->second;
    const auto id = static_cast<std::uint32_t>(s.vertices.size());
    s.vertices.emplace_back(x, y, z);
    index.emplace(key, id);
    return id;
  };
  for (const auto& [x, y, z] : cells) {
    for (int axis = 0; axis < 3; ++axis) {
      for (int side = -1; side <= 1; side += 2) {
        int n[3] = {x, y, z};
        n[axis] += side;
        if (cells.count({n[0], n[1], n[2]})) continue;
        // The face at coordinate c along `axis`, spanned by the two other axes.
        const int c = (axis == 0 ? x : axis == 1 ? y : z) + (side > 0 ? 1 : 0);
        const int a1 = (axis + 1) % 3;
        const int a2 = (axis + 2) % 3;
        int base[3] = {x, y, z};
        base[axis] = c;
        auto corner = [&](int d1, int d2) {
          int p[3] = {base[0], base[1], base[2]};
          p[a1] += d1;
          p[a2] += d2;
          return vertex(p[0], p[1], p[2]);
        };
        // (a1, a2, axis) is right-handed: counter-clockwise in (a1, a2) faces +axis.
        const std::uint32_t q[4] = {corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)};
        if (side > 0) {
          s.triangles.push_back({q[0], q[1], q[2]});
          s.triangles.push_back({q[0], q[2], q[3]});
        } else {
          s.triangles.push_back({q[0], q[2], q[1]});
          s.triangles.push_back({q[0], q[3], q[2]});
        }
      }
    }
  }
  return s;
}

/// A flat slab of width x 3 x 1 voxels with `holes` square holes through it
/// (genus = holes).
inline TriangleSoup slab_with_holes(int holes) {
  std::set<std::tuple<int, int, int>> cells;
  const int width = 2 * holes + 1;
  for (int x = 0; x < width; ++x) {
    for (int y = 0; y < 3; ++y) {
      if (y == 1 && x % 2 == 1) continue;  // a hole
      cells.insert({x, y, 0});
    }
  }
  return voxels(cells);
}

/// `soup` rotated by `angle` (radians) about `axis` (need not be unit).
inline TriangleSoup rotated(TriangleSoup soup, const Vec3& axis, double angle) {
  const Vec3 k = axis.normalized();
  for (Vec3& p : soup.vertices) {
    p = p * std::cos(angle) + k.cross(p) * std::sin(angle) + k * k.dot(p) * (1 - std::cos(angle));
  }
  return soup;
}

/// Every triangle with its own three vertices, as an STL file would hold it.
inline TriangleSoup unwelded(const TriangleSoup& soup) {
  TriangleSoup s;
  for (const auto& t : soup.triangles) {
    const auto b = static_cast<std::uint32_t>(s.vertices.size());
    for (const std::uint32_t v : t) s.vertices.push_back(soup.vertices[v]);
    s.triangles.push_back({b, b + 1, b + 2});
  }
  return s;
}

}  // namespace fabmesh::test
