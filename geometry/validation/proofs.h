#pragma once
// What a builder's construction proves about the mesh it made. A builder
// returns these only when its construction proves them; validate (through
// ValidationOptions) then uses them in place of the analyses they replace.

#include <cstddef>
#include <string>
#include <vector>

namespace fabmesh {

/// Why a constructed mesh has no self-intersection (no two faces meet other
/// than at the vertices and edges they share), stated for the report, e.g.
/// "the section loops are simple and disjoint in r >= 0 (exact predicates),
/// so its revolution is embedded". It replaces the 3D self-intersection test.
struct EmbeddingProof {
  std::string statement;
  /// Moving every vertex by less than this keeps the mesh embedded and its
  /// faces non-degenerate (0: not proven), model units. It lets a moved copy
  /// of the mesh (quantized, rounded to float32) skip the 3D test: see
  /// revolution_margin and ValidationOptions::moved_from.
  double margin = 0.0;
};

/// What a builder's construction proves about the connectivity of the mesh
/// it made: closed, edge- and vertex-manifold, consistently oriented, no
/// repeated or duplicate faces, with these components and Euler
/// characteristics. A builder returns one only when its index arithmetic
/// proves it; it replaces the connectivity analysis (the test suite checks
/// each proof against that analysis).
struct TopologyProof {
  std::string statement;  ///< why, for the report
  std::size_t components = 0;
  /// V - E + F of each component, in order of each component's lowest vertex
  /// (the order the connectivity analysis gives).
  std::vector<long> euler_characteristics;
};

}  // namespace fabmesh
