#pragma once
// The halfedge mesh type (OpenMesh), for the builders that need connectivity
// while they build (slab, thicken, a surface's tessellation) and the writers
// that take one. Kept out of geometry/core/types.h, which every header
// includes: only the files that use a Mesh read OpenMesh's headers. Meshes
// that cross the library's surface are TriangleSoups (geometry/core/soup.h);
// this header converts between the two.

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <cstddef>

#include "geometry/core/soup.h"

namespace fabmesh {

/// OpenMesh traits: double precision points, no per-element attributes by default.
struct MeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};

/// The halfedge triangle mesh: shared vertices, halfedge connectivity.
using Mesh = OpenMesh::TriMesh_ArrayKernelT<MeshTraits>;

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

}  // namespace fabmesh
