#pragma once
// Nesting a kitchen's pieces on stone slabs: as few slabs as possible,
// within the margins, at least `spacing` apart, clear of the slabs' defects,
// honouring the grain; then verified with exact predicates on the very
// coordinates the layout, the cut list and the router programs are written
// from.

#include <cstddef>
#include <string>
#include <vector>

#include "geometry/core/types.h"

namespace fabmesh {

/// A flaw on every slab that no piece may cover (key `slab.defects[i]`):
/// a circle (radius > 0) or a simple polygon (radius 0, `polygon` non-empty),
/// in slab coordinates (origin at the slab's lower-left corner).
struct SlabDefect {
  Vec2 center{0.0, 0.0};
  double radius = 0.0;
  std::vector<Vec2> polygon;
};

/// The stock (key `slab`), model units.
struct SlabStock {
  double length = 0.0;   ///< along x
  double width = 0.0;    ///< along y
  double margin = 0.0;   ///< unusable border on every side
  double spacing = 0.0;  ///< least distance between two pieces (and from a piece to a defect)
  /// true: every piece's long axis (its bounding box's longer side in the
  /// design's frame) runs along the slab's length, turned 0 or 180 degrees
  /// only from that; false: any quarter turn.
  bool grain_along = true;
  std::vector<SlabDefect> defects;
};

/// A piece to place: its outer loop counter-clockwise in the design's frame
/// (cut-outs are not used for placing: no piece goes inside another's).
struct NestPiece {
  std::string name;  ///< "piece-1", for messages and labels
  std::vector<Vec2> outer;
};

/// Where a piece lies: slab coordinates = rotate(design point, rotation_deg)
/// + offset, computed once (place_point) and kept in `outer`.
struct Placement {
  std::size_t piece = 0;  ///< index into the pieces given
  std::size_t slab = 0;   ///< 0-based
  int rotation_deg = 0;   ///< 0, 90, 180 or 270, counter-clockwise
  Vec2 offset{0.0, 0.0};
  std::vector<Vec2> outer;  ///< the piece's outer loop in slab coordinates (what is verified)
};

struct SlabNesting {
  std::vector<Placement> placements;  ///< one per piece, in the pieces' order
  std::size_t slabs = 0;
  std::vector<double> utilisation;  ///< per slab: pieces' area / usable area (length-2m)(width-2m), in [0, 1]
  /// ceil(total area of the pieces / usable area of one slab): no layout uses fewer slabs.
  std::size_t lower_bound = 0;
  std::string proof;  ///< what verify_nesting checked, for reports
};

/// A design point in slab coordinates: turned by `rotation_deg` (a quarter
/// turn, so exact) about the origin, then moved by `offset`.
Vec2 place_point(const Vec2& p, int rotation_deg, const Vec2& offset);

/// Every point of `loop` placed as `at` says (place_point): a piece's cut-out
/// on its slab.
std::vector<Vec2> place_loop(const std::vector<Vec2>& loop, const Placement& at);

/// Places `pieces` on as few slabs as the search finds (first fit,
/// largest piece first, bottom-left positions against the slab's margins,
/// the other pieces' and the defects' bounding boxes), then verifies the
/// result (verify_nesting).
/// \throw GeometryError at key `slab`, naming the piece and the dimension,
///        when a piece fits on no empty slab in any allowed turn (never
///        leaves a piece out); RangeError for a stock that leaves no usable
///        area (at `slab.margin`) or a spacing < 0.
SlabNesting nest_pieces(const std::vector<NestPiece>& pieces, const SlabStock& stock);

/// Checks a layout exactly (CGAL's exact predicates and exact squared
/// distances on the double coordinates of each placed loop): each placed loop
/// is the piece's loop turned and moved as its placement says, lies inside
/// the slab's usable rectangle (at least `margin` from every side), is at
/// least `spacing` from every other loop on the same slab (no overlap, no
/// containment) and from every defect (a circle's distance is decided
/// exactly too: squared distance to its centre >= (radius + spacing)^2).
/// Returns a one-line proof; throws GeometryError (key `slab`) naming the
/// first violation and the pieces.
std::string verify_nesting(const std::vector<NestPiece>& pieces, const SlabStock& stock,
                           const std::vector<Placement>& placements);

}  // namespace fabmesh
