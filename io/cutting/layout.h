#pragma once
// A kitchen's slab layout as files a fabricator reads: an SVG of every slab
// at true size with its pieces, labels, defects and free area, and the cut
// list (CSV) with each piece's slab, position, turn, size, area and the
// lengths of its exposed, wall and seam edges.

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "geometry/core/types.h"
#include "geometry/kitchen/nest.h"
#include "geometry/kitchen/pieces.h"
#include "geometry/sampling/cut_loop.h"
#include "io/cutting/sheet.h"

namespace fabmesh {

struct LayoutOptions {
  std::string units = "mm";  ///< the design's unit (SVG width and height, the cut list's header)
  std::string title;         ///< the design's name
};

/// Slabs one above the other (slab 1 at the top), each a length x width
/// rectangle along x at true size (its lower-left corner at its own origin),
/// its usable area dashed, its defects hatched, every piece on it as placed
/// (outline and cut-outs, seam edges drawn heavier) with its name, and a
/// caption: pieces, utilisation and free area.
std::string encode_layout_svg(const std::vector<KitchenPiece>& pieces, const SlabStock& stock,
                              const SlabNesting& nesting, const LayoutOptions& options);

/// A piece's drawing: `exact` (its exact outline, then its cut-outs in the
/// order of piece.holes) when given, else its loops as polygons.
std::vector<CutLoop> piece_drawing(const KitchenPiece& piece, const std::vector<CutLoop>& exact);

/// `loop` turned and moved as `at` places its piece (place_point): lines,
/// spline points and arc centres moved, arcs turned with them.
CutLoop placed_loop(const CutLoop& loop, const Placement& at);

/// The layout as a sheet (layout_dxf): the slabs as encode_layout_svg draws
/// them, on layers SLABS, MARGINS, DEFECTS, PIECES (each piece's drawing
/// placed: exact where `exact[i]` is given), SEAMS and LABELS (each piece's
/// name, size and turn; each slab's caption); text readable at A3.
Sheet layout_sheet(const std::vector<KitchenPiece>& pieces, const std::vector<std::vector<CutLoop>>& exact,
                   const SlabStock& stock, const SlabNesting& nesting, const LayoutOptions& options);

/// The cut list: a header line, then one line per piece (in piece order):
/// piece, slab (1-based), x, y (its placed bounding box's lower-left corner
/// on the slab), rotation_deg, length, width (its placed bounding box),
/// area, exposed_length, wall_length, seam_length, cutouts (the design's
/// hole indices, space-separated). Lengths in `options.units`, to three
/// decimals (trailing zeros left out).
std::string encode_cutlist(const std::vector<KitchenPiece>& pieces, const SlabNesting& nesting,
                           const LayoutOptions& options);

}  // namespace fabmesh
