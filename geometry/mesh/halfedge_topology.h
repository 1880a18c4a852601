#pragma once
// Combinatorial analysis of a halfedge mesh in linear time.

#include <cstddef>

#include "geometry/core/types.h"
#include "geometry/mesh/topology.h"

namespace fabmesh {

/// The same facts as analyse_topology(to_soup(mesh)), in O(V + E + F)
/// instead of a sort: OpenMesh already guarantees at most two faces per edge
/// and opposite directions on them, so what is left to find is boundary
/// edges, vertices with more than one fan, duplicate face pairs (two faces
/// on the same three edges) and the components with their Euler
/// characteristics. Deleted elements must have been garbage-collected.
Topology analyse_topology(const Mesh& mesh, std::size_t max_examples = 5);

}  // namespace fabmesh
