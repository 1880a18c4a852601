#pragma once
// A triangle soup being repaired, with where each face and vertex came from
// in the mesh as read: the repair's places are reported in those indices.

#include <cstdint>
#include <vector>

#include "geometry/core/soup.h"
#include "geometry/repair/repair_log.h"

namespace fabmesh {

/// A soup and, per face and vertex, its origin in the mesh as read.
struct TrackedSoup {
  TriangleSoup soup;
  std::vector<std::uint32_t> face_origin;  ///< per triangle: the face read it lies in, or kNoIndex (made)
  std::vector<std::uint32_t>
      vertex_origin;  ///< per vertex: a vertex read at (or welded into) it, or kNoIndex
};

/// `soup` as read: every face and vertex its own origin.
TrackedSoup track(const TriangleSoup& soup);

/// Removes the faces whose `remove` flag is set, keeping the others in order.
void remove_faces(TrackedSoup& mesh, const std::vector<bool>& remove);

/// Removes the vertices no face uses, keeping the others in order.
void compact_vertices(TrackedSoup& mesh);

/// Face `f` as a place: its origin and centroid.
RepairPlace face_place(const TrackedSoup& mesh, std::uint32_t f);

/// Vertex `v` as a place: its origin and position.
RepairPlace vertex_place(const TrackedSoup& mesh, std::uint32_t v);

/// Appends a vertex at `p` whose origin is that of vertex `like` (a copy of
/// it, or kNoIndex for a new point); returns its index.
std::uint32_t add_vertex(TrackedSoup& mesh, const Vec3& p, std::uint32_t like = kNoIndex);

}  // namespace fabmesh
