#pragma once
// A builder's proof that the mesh it made is embedded.

#include <string>

namespace fabmesh {

/// Why a constructed mesh has no self-intersection (no two faces meet other
/// than at the vertices and edges they share), stated for the report, e.g.
/// "the section loops are simple and disjoint in r >= 0 (exact predicates),
/// so its revolution is embedded". A builder returns one only when its
/// construction proves it; validate_constructed then replaces the 3D test.
struct EmbeddingProof {
  std::string statement;
  /// Moving every vertex by less than this keeps the mesh embedded and its
  /// faces non-degenerate (0: not proven). It lets a moved copy of the mesh (quantized, rounded to float32)
  /// skip the 3D test: see revolution_margin.
  double margin = 0.0;
};

}  // namespace fabmesh
