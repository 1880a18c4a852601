#pragma once
// A triangle soup: the indexed, unchecked triangles of a file from elsewhere.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/core/types.h"
#include "geometry/mesh/halfedge_mesh.h"

namespace fabmesh {

/// Indexed triangles with no topological guarantee: edges may be shared by
/// any number of faces, vertices may repeat, faces may be degenerate.
/// Invariant expected by consumers (readers guarantee it): every index is
/// < vertices.size().
struct TriangleSoup {
  std::vector<Vec3> vertices;                           ///< model units
  std::vector<std::array<std::uint32_t, 3>> triangles;  ///< counter-clockwise seen from outside
};

/// The vertices and faces of `mesh` as a soup (deleted elements skipped,
/// remaining vertices renumbered densely). Non-triangular faces are
/// fan-triangulated.
TriangleSoup to_soup(const Mesh& mesh);

/// A Mesh built from a soup, and the faces OpenMesh refused to add.
struct SoupToMesh {
  Mesh mesh;
  /// Faces OpenMesh's add_face refused (complex edge or vertex, or a repeated
  /// index). Each one is a non-manifold defect of the soup; never ignore it.
  std::size_t refused_faces = 0;
};

/// Builds an OpenMesh Mesh from `soup`, keeping every vertex (unreferenced
/// ones too) in order. Faces that cannot be added are counted, not dropped
/// silently. \throw InputError when an index is out of range.
SoupToMesh to_mesh(const TriangleSoup& soup);

/// Throws InputError unless every triangle index of `soup` is < vertices.size().
void require_indices_in_range(const TriangleSoup& soup);

}  // namespace fabmesh
