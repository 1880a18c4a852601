#pragma once
// The undirected edges of a triangle soup and the faces around each: what the
// repair steps read the connectivity from (borders, non-manifold edges,
// neighbours across an edge).

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/core/soup.h"

namespace fabmesh {

/// One side of a face: the face, the directed edge from -> to it traverses.
struct FaceSide {
  std::uint32_t face;
  std::uint32_t from;
  std::uint32_t to;
};

/// The edges of a soup: sides grouped by undirected edge, edges sorted by
/// (smaller vertex, larger vertex), sides of an edge by face.
struct EdgeTable {
  std::vector<FaceSide> sides;      ///< 3 per face whose corners differ
  std::vector<std::size_t> starts;  ///< edge e's sides are sides[starts[e] .. starts[e + 1])
  std::size_t edges() const { return starts.empty() ? 0 : starts.size() - 1; }
  std::size_t faces_of(std::size_t e) const { return starts[e + 1] - starts[e]; }
  const FaceSide& side(std::size_t e, std::size_t k) const { return sides[starts[e] + k]; }
};

/// The edge table of `soup` (faces with a repeated corner contribute no side).
EdgeTable edge_table(const TriangleSoup& soup);

/// Per vertex: whether it lies on a border edge (an edge of one face).
std::vector<bool> border_vertices(const TriangleSoup& soup, const EdgeTable& edges);

/// Per face, for each corner k, the edge index of its side (corner k to k+1),
/// or SIZE_MAX for a face with a repeated corner.
std::vector<std::array<std::size_t, 3>> face_edges(const TriangleSoup& soup, const EdgeTable& edges);

}  // namespace fabmesh
