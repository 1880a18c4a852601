#pragma once
// The library's meshes to and from the pipeline's triangle soups.

#include <string>

#include "fabmesh/mesh.h"
#include "geometry/core/soup.h"

namespace fabmesh::api::detail {

/// The public arrays of `soup`.
Mesh public_mesh(const fabmesh::TriangleSoup& soup);

/// `mesh` as a view of its own arrays (valid while it lives).
MeshView view_of(const Mesh& mesh);

/// A copy of the viewed arrays as a soup: the one copy a call makes.
/// \throw InputError at "vertices" (no array given for rows promised) or
///        "triangles" (an index negative or not below the vertex count)
fabmesh::TriangleSoup internal_soup(const MeshView& view);

}  // namespace fabmesh::api::detail
