#pragma once
// The halfedge mesh type (OpenMesh), for the builders that need connectivity
// while they build (slab, thicken, a surface's tessellation) and the writers
// that take one. Kept out of geometry/core/types.h, which every header
// includes: only the files that use a Mesh read OpenMesh's headers. Meshes
// that cross the library's surface are TriangleSoups (geometry/mesh/soup.h).

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

namespace fabmesh {

/// OpenMesh traits: double precision points, no per-element attributes by default.
struct MeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};

/// The halfedge triangle mesh: shared vertices, halfedge connectivity.
using Mesh = OpenMesh::TriMesh_ArrayKernelT<MeshTraits>;

}  // namespace fabmesh
