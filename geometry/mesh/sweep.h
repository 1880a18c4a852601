#pragma once
// Sweeps: a section in the (radius, height) half-plane carried about the z
// axis through a list of angles, over part of a turn (a partial revolution,
// left open at both ends for caps) or all of it; vertices flagged "on the
// block" follow a given outline instead of a circle (a generalised
// revolution, e.g. a square block whose side is flat between its corners).

#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/core/soup.h"
#include "geometry/core/types.h"

namespace fabmesh {

/// The section swept.
struct SweepSection {
  /// Counter-clockwise loop, x = radius >= 0, y = height (model units). A
  /// vertex with x == 0 is on the axis; the loop meets the axis only along
  /// single axis edges (both ends on it), which produce no lateral faces.
  std::vector<Vec2> loop;
  /// Empty, or one flag per loop vertex: nonzero places the vertex at the
  /// sample's `outline` point (at its own height) instead of on its circle.
  /// An edge from such a vertex to an ordinary one must be horizontal.
  std::vector<char> on_outline;
  /// An edge left open (from loop vertex `open_edge` to the next), or none:
  /// a horizontal edge whose swept face the caller builds itself (a flat
  /// face with holes), between the two rings SweptSurface::open gives.
  static constexpr std::size_t kNoEdge = static_cast<std::size_t>(-1);
  std::size_t open_edge = kNoEdge;
};

/// Where the section goes: one entry per angular sample, in increasing angle.
struct SweepPath {
  std::vector<Vec2> directions;  ///< unit (cos theta, sin theta) of each sample
  std::vector<Vec2> outline;     ///< (x, y) of on_outline vertices at each sample; empty when none
  /// false: a partial sweep from the first sample to the last (span < 2 pi),
  /// open at both ends. true: the samples go all the way round and the last
  /// connects back to the first.
  bool closed = false;
};

/// The lateral surface of a sweep and where its end sections are.
struct SweptSurface {
  TriangleSoup soup;  ///< lateral faces, outward for a counter-clockwise loop
  /// Per loop vertex: its vertex index at the first and at the last sample
  /// (axis vertices: their single pole vertex).
  std::vector<std::uint32_t> first, last;
  /// With an open edge: its two ends' vertices at every sample (from, to).
  std::vector<std::uint32_t> open_from, open_to;
};

/// Triangles of the lateral surface (without caps).
std::size_t swept_triangle_count(const SweepSection& section, std::size_t samples, bool closed);

/// Sweeps `section` along `path`. Between consecutive samples every loop
/// edge gives a quad (two triangles, one when an end is on the axis) between
/// its copies at the two samples, as `revolve` does; a partial sweep leaves
/// the end sections open (the caller caps them with triangulations of the
/// section, sharing `first` and `last`). With at least 2 samples per half
/// turn and every sample step below pi, each face lies in the wedge between
/// its two samples' half-planes.
/// \throw RangeError (fewer than 2 samples, 3 when closed; a negative radius;
///        size mismatches); GeometryError for an axis vertex without exactly
///        one axis neighbour, a non-horizontal edge leaving an outline vertex
///        or an open edge that is not horizontal or has an end on the axis).
SweptSurface sweep_section(const SweepSection& section, const SweepPath& path);

}  // namespace fabmesh
