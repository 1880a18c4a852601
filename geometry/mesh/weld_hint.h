#pragma once
// A weld tolerance suggested by the data: an STL whose copies of each vertex
// were written with a little noise (1e-5 of jitter) is open after the exact
// weld, every edge a boundary edge; welding within the noise closes it.

#include <optional>

#include "geometry/core/soup.h"

namespace fabmesh {

/// A tolerance `weld` could close an open mesh with.
struct WeldCandidate {
  /// The least tolerance at which every boundary edge (an edge of one face)
  /// has another boundary edge whose ends are each within it of its own
  /// (or are its own): no smaller tolerance can pair every boundary edge
  /// with another, which closing the mesh needs.
  double closing_distance = 0.0;
  /// closing_distance rounded up to two significant digits: the value to suggest.
  double tolerance = 0.0;
  double mean_edge = 0.0;  ///< mean length of the soup's edges, for scale
};

/// The fraction of the mean edge length below which a tolerance counts as
/// small: welding within it merges noise, not features.
inline constexpr double kWeldHintFraction = 0.05;

/// The weld tolerance (closing_distance) at which every boundary edge of
/// `soup` has a partner edge, when that is at most kWeldHintFraction of the
/// mean edge length; nullopt when the soup has no boundary edge, some
/// boundary edge has no partner that near, or the boundary vertices crowd
/// so densely that looking costs more than a few dozen comparisons each. A
/// candidate only: whether welding with it closes the mesh is for the caller
/// to check (weld, then validate). Time O(n log n).
/// \pre indices in range (a non-finite vertex gives nullopt).
std::optional<WeldCandidate> weld_candidate(const TriangleSoup& soup);

}  // namespace fabmesh
