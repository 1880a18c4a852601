#pragma once
// A builder's proof of its mesh's connectivity.

#include <cstddef>
#include <string>
#include <vector>

namespace fabmesh {

/// What a builder's construction proves about the connectivity of the mesh
/// it made: closed, edge- and vertex-manifold, consistently oriented, no
/// repeated or duplicate faces, with these components and Euler
/// characteristics. A builder returns one only when its index arithmetic
/// proves it; validate_constructed then replaces the connectivity analysis
/// (the test suite checks each proof against that analysis).
struct TopologyProof {
  std::string statement;  ///< why, for the report
  std::size_t components = 0;
  /// V - E + F of each component, in order of each component's lowest vertex
  /// (the order analyse_topology gives).
  std::vector<long> euler_characteristics;
};

}  // namespace fabmesh
