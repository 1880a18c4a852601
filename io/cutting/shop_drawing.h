#pragma once
// A kitchen's shop drawing (shop_dxf, shop_svg): every piece in the top's
// frame, side by side, with its dimensions (overall length and depth, each
// cut-out's position and size, each seam's length), its label and its edges
// marked by kind, readable when printed on A3.

#include <string>
#include <vector>

#include "geometry/kitchen/pieces.h"
#include "geometry/sampling/cut_loop.h"
#include "io/cutting/layout.h"
#include "io/cutting/sheet.h"

namespace fabmesh {

/// The shop drawing of `pieces` (`exact[i]`: piece i's exact drawing, outline
/// then cut-outs, or empty for its polygons). Pieces left to right in piece
/// order, each moved (not turned) so its box's lower-left corner lies on
/// y = 0, with room for its dimensions between them. Layers: OUTLINE (the
/// piece's outline; exposed edges), HOLES (cut-outs), WALLS and SEAMS (those
/// edges drawn over the outline), DIMENSIONS and LABELS. Dimensions, from
/// the exact curves' bounds where given: below each piece its length and, a
/// row per cut-out, the cut-out's distance from the piece's left end and its
/// width; to its left its depth and, a column per cut-out, the distance from
/// its bottom edge and its height; beside each seam edge its length. The
/// text height prints at 3 mm when the whole sheet is scaled to A3.
Sheet shop_sheet(const std::vector<KitchenPiece>& pieces, const std::vector<std::vector<CutLoop>>& exact,
                 const LayoutOptions& options);

}  // namespace fabmesh
