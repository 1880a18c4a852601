#pragma once
// The repair's operations over CGAL's kernel with exact predicates (Epick):
// exact collinearity, holes filled, and which faces intersect. CGAL stays in
// surface_ops.cpp.

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "geometry/core/soup.h"

namespace fabmesh {

/// True when a, b and c lie on one line (exact predicate).
bool corners_collinear(const Vec3& a, const Vec3& b, const Vec3& c);

/// How holes are filled.
struct HoleFillOptions {
  bool refine_and_fair = true;  ///< refine the patch to the border's density and fair it (smooth blend)
};

/// One hole filled, or not.
struct FilledHole {
  std::size_t border_edges = 0;
  Vec3 centre = Vec3::Zero();       ///< the mean of its border vertices
  std::uint32_t border_vertex = 0;  ///< a vertex of its border (an index into the soup given)
  std::size_t faces_added = 0;
  std::size_t vertices_added = 0;
  bool faired = false;  ///< the fairing succeeded (else the patch is refined only, or flat)
  bool filled = false;  ///< false: no patch free of intersections was found; the hole stays open
};

/// The soup with its holes filled: the faces given, in order, then the
/// patches' faces; the vertices given, then the patches' new vertices.
struct HoleFilling {
  TriangleSoup soup;
  std::vector<FilledHole> holes;
};

/// Fills every hole (border loop) of `soup`, which must be an oriented
/// manifold surface (each edge of at most two faces traversed oppositely,
/// each vertex one fan): CGAL's triangulate_refine_and_fair_hole, each patch
/// verified free of intersections with the rest (CGAL's exact test); a patch
/// that intersects is replaced by the plain minimal-area triangulation, and
/// when that intersects too the hole is left open (FilledHole::filled false).
/// \throw InputError when `soup` is not an oriented manifold surface.
HoleFilling fill_holes(const TriangleSoup& soup, const HoleFillOptions& options = {});

/// The pairs of faces (f, g), f < g, of `soup` that intersect other than at
/// shared vertices and edges (CGAL's exact test; every face non-degenerate).
std::vector<std::pair<std::uint32_t, std::uint32_t>> intersecting_faces(const TriangleSoup& soup);

}  // namespace fabmesh
