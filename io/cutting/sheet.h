#pragma once
// A drawing sheet: named layers holding exact loops, lines, texts and
// linear dimensions. A kitchen's shop drawing and slab layout are sheets,
// written as DXF with real DIMENSION entities (encode_dxf_sheet in
// io/cutting/dxf.h) and as SVG (encode_sheet_svg), from the same data.

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "geometry/core/types.h"
#include "geometry/sampling/cut_loop.h"

namespace fabmesh {

struct SheetLayer {
  std::string name;              ///< DXF layer name
  int aci = 7;                   ///< DXF colour (AutoCAD colour index)
  std::string colour = "black";  ///< SVG stroke
  double weight = 1.0;           ///< SVG stroke width, in text heights / 8
};

struct SheetLoop {
  std::string layer;
  CutLoop loop;
};

struct SheetLine {
  std::string layer;
  Vec2 from{0.0, 0.0};
  Vec2 to{0.0, 0.0};
};

struct SheetText {
  std::string layer;
  Vec2 at{0.0, 0.0};  ///< the start of the baseline, or its middle when centred
  double height = 1.0;
  std::string text;
  bool centred = false;
};

/// A linear dimension: the distance from `from` to `to` measured along the
/// direction at `angle_deg` (0: along x, 90: along y), its dimension line
/// through `through`.
struct SheetDimension {
  std::string layer;
  Vec2 from{0.0, 0.0};
  Vec2 to{0.0, 0.0};
  Vec2 through{0.0, 0.0};
  double angle_deg = 0.0;
};

struct Sheet {
  std::vector<SheetLayer> layers;  ///< besides layer 0, in the order written
  std::vector<SheetLoop> loops;
  std::vector<SheetLine> lines;
  std::vector<SheetText> texts;
  std::vector<SheetDimension> dimensions;
  double text_height = 1.0;  ///< the dimensions' text and arrow size, model units
};

/// How a dimension is drawn: its extension lines and dimension line, its
/// arrowheads (filled triangles), and its text (the measured distance as a
/// shop reads it, centred above the dimension line's middle, turned with it).
struct DimensionGraphic {
  double value = 0.0;  ///< the distance measured
  std::vector<std::array<Vec2, 2>> lines;
  std::vector<std::array<Vec2, 3>> arrows;
  Vec2 text_at{0.0, 0.0};  ///< the middle of the text's baseline
  double text_angle_deg = 0.0;
  std::string text;
};

/// `d` drawn with text and arrows of `text_height`: extension lines from half
/// a text height off the measured points to half a height past the
/// dimension line.
DimensionGraphic dimension_graphic(const SheetDimension& d, double text_height);

/// A closed polygon through `points` as one polyline entity (closed by its
/// last point): a piece, a slab, a defect drawn as cut.
CutLoop polygon_loop(const std::vector<Vec2>& points, const std::string& label, bool outer);

/// A length as a shop reads it: at most three decimals, no trailing zeros.
std::string shop_number(double v);

/// The box of everything on the sheet: loops exactly (cut_bounds), lines,
/// dimensions as drawn, texts as 0.6 heights a character wide.
std::pair<Vec2, Vec2> sheet_bounds(const Sheet& sheet);

/// The text height that prints at `paper_mm` on a sheet of paper of
/// `paper` (width, height in mm, less a 10 mm border all round) when the
/// box `lo`..`hi` (in `units`) is scaled to fit it, turned if it fits better.
double readable_text_height(const Vec2& lo, const Vec2& hi, const std::string& units,
                            const std::array<double, 2>& paper, double paper_mm);

/// The SVG of `sheet`: loops, lines and dimensions stroked in their layer's
/// colour (a <g> per layer, id = the layer's name), texts in sans-serif;
/// width and height in `units`, y up as in the model.
std::string encode_sheet_svg(const Sheet& sheet, const std::string& units, const std::string& title);

}  // namespace fabmesh
