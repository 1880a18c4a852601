#pragma once
// A face as boxes for the broad phase: one box, or for a long sliver lying
// across the axes, the boxes of slabs cut across its longest edge. A face
// 600 mm long and 0.2 mm wide at 45 degrees to x has a box of 420 x 420 mm,
// overlapping nearly every face of its region; cut into k pieces, each
// piece's box is about as large as the piece.
//
// Internal to geometry/validation (validate.h is the public entry).

#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/core/soup.h"
#include "geometry/validation/detail/triangle_bvh.h"

namespace fabmesh::detail {

/// A face is cut when the area of its box (the product of its two largest
/// extents) exceeds this many times its own (at least 2 for any triangle).
constexpr double kSliverExcess = 16.0;

/// Most pieces a face is cut into.
constexpr std::size_t kMaxPieces = 64;

/// Appends the boxes of face f's pieces to `boxes` and returns their number:
/// one (its box) unless it is a sliver (see kSliverExcess), then
/// ceil(excess / 16), at most kMaxPieces. Together the boxes contain the
/// whole triangle: every rounding error of the cut is covered.
/// \pre indices in range, coordinates finite.
std::size_t append_pieces(const TriangleSoup& soup, std::uint32_t f, std::vector<BoxF>& boxes);

}  // namespace fabmesh::detail
