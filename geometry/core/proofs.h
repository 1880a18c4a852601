#pragma once
// What a builder's construction proves about the mesh it made. A builder
// returns these only when its construction proves them; validate (through
// ValidationOptions) then uses them in place of the analyses they replace.

#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace fabmesh {

struct TriangleSoup;

/// Why a constructed mesh has no self-intersection (no two faces meet other
/// than at the vertices and edges they share), stated for the report, e.g.
/// "the section loops are simple and disjoint in r >= 0 (exact predicates),
/// so its revolution is embedded". It replaces the 3D self-intersection test.
struct EmbeddingProof {
  EmbeddingProof() = default;
  explicit EmbeddingProof(std::string why, double proven_margin = 0.0)
      : statement(std::move(why)), margin(proven_margin) {}

  std::string statement;
  /// Moving every vertex by less than this keeps the mesh embedded and its
  /// faces non-degenerate (0: not proven), model units. It lets a moved copy
  /// of the mesh (quantized, rounded to float32) skip the 3D test: see
  /// revolution_margin and ValidationOptions::moved_from.
  double margin = 0.0;
  /// Proves a moved copy of the mesh (same triangles; its vertices rounded
  /// to float32, scaled) embedded again by the construction's own exact
  /// argument, whatever the move; true when it holds. Null: none. Used when
  /// the copy moved as far as `margin` (ValidationOptions::moved_from).
  std::function<bool(const TriangleSoup& moved)> recheck;
  /// What `recheck` proves, for the report.
  std::string recheck_statement;
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
