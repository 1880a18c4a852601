#pragma once
// Combinatorial analysis of an indexed triangle soup: edges, fans,
// orientation, components and Euler characteristics. Works on any soup,
// including non-manifold ones (it builds its own edge map; nothing is refused).
//
// Internal to geometry/validation (validate.h is the public entry); the
// tests and the benchmarks include it to check and time this part alone.

#include <cstddef>
#include <vector>

#include "geometry/core/soup.h"
#include "geometry/validation/defect_location.h"

namespace fabmesh {

/// How many times one kind of defect occurs, and where a few of them are.
struct DefectCount {
  std::size_t count = 0;
  std::vector<Vec3> examples;  ///< up to the requested number of locations, model units
  /// The first occurrences as indices, up to the requested number
  /// (ValidationOptions::max_locations), in the order of `examples`.
  std::vector<DefectLocation> locations;

  /// Counts one occurrence at `where`, keeping it as an example while fewer
  /// than `max_examples` are kept.
  void add(const Vec3& where, std::size_t max_examples);

  /// add(where, max_examples), and keeps the location locate() gives while
  /// fewer than `max_locations` are kept (locate is called only then).
  template <class Locate>
  void add(const Vec3& where, std::size_t max_examples, std::size_t max_locations, Locate&& locate) {
    if (locations.size() < max_locations) locations.push_back(locate());
    add(where, max_examples);
  }
};

/// The combinatorial facts of a soup. Index-degenerate triangles (a repeated
/// index) are not triangles and take no part in any count here; duplicate
/// faces do take part (their edges are shared by more than two faces).
struct Topology {
  std::size_t referenced_vertices = 0;  ///< vertices used by at least one counted face
  std::size_t edges = 0;                ///< distinct undirected edges
  DefectCount boundary_edges;           ///< edges with exactly one face (location: midpoint)
  DefectCount non_manifold_edges;       ///< edges with three or more faces (midpoint)
  /// Vertices whose faces form more than one fan, or that lie on a
  /// non-manifold edge (location: the vertex).
  DefectCount non_manifold_vertices;
  /// Two-face edges that both faces traverse in the same direction (midpoint).
  DefectCount inconsistent_edges;
  /// Extra copies of a face with the same three vertices, in either
  /// orientation (location: centroid); a face present k times counts k - 1.
  DefectCount duplicate_faces;
  std::size_t components = 0;  ///< connected components of faces sharing a vertex
  /// V - E + F of each component, in order of each component's lowest vertex.
  std::vector<long> euler_characteristics;
};

/// Which boundary edges are kept as examples: the first by their vertex
/// indices (the lower, then the higher), or the first in face order (by the
/// face, then the side: side k runs from corner k to corner k + 1).
enum class ExampleOrder { ByVertex, ByFace };

/// Analyses the connectivity of `soup` in O(n log n).
/// \param max_examples  how many example locations to keep per defect kind
/// \param order  which boundary edges are the examples (counts do not depend on it)
/// \param max_locations  how many occurrences to keep per kind as indices (DefectLocation)
/// \throw InputError when an index is out of range.
Topology analyse_topology(const TriangleSoup& soup, std::size_t max_examples = 5,
                          ExampleOrder order = ExampleOrder::ByVertex, std::size_t max_locations = 0);

}  // namespace fabmesh
