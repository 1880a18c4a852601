#include "io/cutting/shop_drawing.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/core/units.h"

namespace fabmesh {
namespace {

// Spacing of the rows and columns of dimensions, in text heights.
constexpr double kRow = 2.5;

struct Box {
  Vec2 lo, hi;
};

Box bounds_of(const CutLoop& loop) {
  const auto [lo, hi] = cut_bounds({loop});
  return {lo, hi};
}

std::vector<SheetLayer> shop_layers() {
  return {{"OUTLINE", 7, "black", 2.0}, {"HOLES", 7, "black", 2.0}, {"WALLS", 3, "#070", 6.0},
          {"SEAMS", 5, "#06c", 6.0},    {"DIMENSIONS", 1, "#c00"},  {"LABELS", 7, "black"}};
}

// Piece i drawn with text height h, its box's lower-left corner at the origin.
Sheet draw_piece(const KitchenPiece& piece, const std::vector<CutLoop>& loops, const LayoutOptions& options,
                 double h) {
  Sheet sheet;
  sheet.text_height = h;
  const double row = kRow * h;
  const Box outer = bounds_of(loops.front());
  const std::size_t holes = loops.size() - 1;
  Placement at;
  at.offset = -outer.lo;
  const Vec2 lo(0.0, 0.0), hi = outer.hi - outer.lo;
  for (const CutLoop& loop : loops)
    sheet.loops.push_back({loop.outer ? "OUTLINE" : "HOLES", placed_loop(loop, at)});
  // Walls and seams over the outline: the piece's edges of that kind.
  const std::size_t n = piece.outer.size();
  double left = row, bottom = row;  // the first column and row of the piece's own dimensions
  for (std::size_t e = 0; e < n; ++e) {
    if (piece.edges[e] == EdgeKind::Exposed) continue;
    const Vec2 a = piece.outer[e] + at.offset, b = piece.outer[(e + 1) % n] + at.offset;
    sheet.lines.push_back({piece.edges[e] == EdgeKind::Wall ? "WALLS" : "SEAMS", a, b});
    if (piece.edges[e] != EdgeKind::Seam) continue;
    const Vec2 out = Vec2((b - a).y(), -(b - a).x()).normalized();  // the outer loop runs counter-clockwise
    sheet.texts.push_back({"SEAMS", 0.5 * (a + b) - 2.0 * h * out - Vec2(0.0, 0.4 * h), h, "seam", true});
    // A seam across the whole piece has its length in the piece's length or depth.
    const bool across = (a.x() == b.x() && std::abs(a.y() - b.y()) == hi.y()) ||
                        (a.y() == b.y() && std::abs(a.x() - b.x()) == hi.x());
    if (across) continue;
    // Its length, on the side away from the piece, reading upright; the
    // piece's own dimensions a row further out on that side.
    if (a.x() == 0.0 && b.x() == 0.0) left = 2.0 * row;
    if (a.y() == 0.0 && b.y() == 0.0) bottom = 2.0 * row;
    Vec2 d = b - a;
    if (d.x() < 0.0 || (d.x() == 0.0 && d.y() < 0.0)) d = -d;
    const double angle = std::atan2(d.y(), d.x()) * 180.0 / M_PI;
    sheet.dimensions.push_back({"DIMENSIONS", a, b, 0.5 * (a + b) + row * out, angle});
  }
  // Below: the length, then per cut-out its offset from the left end and its width.
  sheet.dimensions.push_back({"DIMENSIONS", lo, Vec2(hi.x(), lo.y()), Vec2(lo.x(), lo.y() - bottom), 0.0});
  // Left: the depth, then per cut-out its offset from the bottom edge and its height.
  sheet.dimensions.push_back({"DIMENSIONS", lo, Vec2(lo.x(), hi.y()), Vec2(lo.x() - left, lo.y()), 90.0});
  for (std::size_t k = 0; k < holes; ++k) {
    const Box hole = bounds_of(placed_loop(loops[k + 1], at));
    const double y = lo.y() - bottom - static_cast<double>(k + 1) * row;
    sheet.dimensions.push_back({"DIMENSIONS", lo, hole.lo, Vec2(lo.x(), y), 0.0});
    sheet.dimensions.push_back({"DIMENSIONS", hole.lo, Vec2(hole.hi.x(), hole.lo.y()), Vec2(lo.x(), y), 0.0});
    const double x = lo.x() - left - static_cast<double>(k + 1) * row;
    sheet.dimensions.push_back({"DIMENSIONS", lo, hole.lo, Vec2(x, lo.y()), 90.0});
    sheet.dimensions.push_back(
        {"DIMENSIONS", hole.lo, Vec2(hole.lo.x(), hole.hi.y()), Vec2(x, lo.y()), 90.0});
  }
  // The label above the piece (above a seam's dimension there too).
  const std::string kind = piece.strip ? "backsplash strip" : "top piece";
  sheet.texts.push_back({"LABELS", Vec2(0.5 * hi.x(), hi.y() + row + 1.5 * h), 1.4 * h,
                         fmt::format("{} ({}): {} x {} {}", piece.name, kind, shop_number(hi.x()),
                                     shop_number(hi.y()), options.units),
                         true});
  return sheet;
}

// Everything on `from` moved by `shift` onto `to`.
void add_moved(Sheet& to, const Sheet& from, const Vec2& shift) {
  Placement at;
  at.offset = shift;
  for (const SheetLoop& l : from.loops) to.loops.push_back({l.layer, placed_loop(l.loop, at)});
  for (const SheetLine& l : from.lines) to.lines.push_back({l.layer, l.from + shift, l.to + shift});
  for (const SheetText& t : from.texts)
    to.texts.push_back({t.layer, t.at + shift, t.height, t.text, t.centred});
  for (const SheetDimension& d : from.dimensions)
    to.dimensions.push_back({d.layer, d.from + shift, d.to + shift, d.through + shift, d.angle_deg});
}

// The pieces with text height h, `per_row` to a row (rows top to bottom,
// pieces left to right in piece order), a gap of two text heights between
// the rooms, then the legend.
Sheet draw(const std::vector<Sheet>& pieces, const LayoutOptions& options, std::size_t per_row, double h) {
  Sheet sheet;
  sheet.layers = shop_layers();
  sheet.text_height = h;
  double top = 0.0;  // the next row's top
  for (std::size_t first = 0; first < pieces.size(); first += per_row) {
    const std::size_t last = std::min(pieces.size(), first + per_row);
    std::vector<std::pair<Vec2, Vec2>> rooms;
    double above = 0.0, below = 0.0;  // the row's extent about its pieces' baseline
    for (std::size_t i = first; i < last; ++i) {
      rooms.push_back(sheet_bounds(pieces[i]));
      above = std::max(above, rooms.back().second.y());
      below = std::min(below, rooms.back().first.y());
    }
    double x = 0.0;
    for (std::size_t i = first; i < last; ++i) {
      const auto& [lo, hi] = rooms[i - first];
      add_moved(sheet, pieces[i], Vec2(x - lo.x(), top - above));
      x += hi.x() - lo.x() + 2.0 * h;
    }
    top -= above - below + 2.0 * h;
  }
  sheet.texts.push_back(
      {"LABELS", Vec2(0.0, top - h), h,
       fmt::format("{}: shop drawing, {} piece{}, lengths in {}. Edges: exposed black, walls "
                   "green (WALLS), seams blue (SEAMS)",
                   options.title, pieces.size(), pieces.size() == 1 ? "" : "s", options.units)});
  return sheet;
}

// The text height that prints at 3 mm when `sheet` is scaled to A3.
double a3_text_height(const Sheet& sheet, const LayoutOptions& options) {
  const auto [lo, hi] = sheet_bounds(sheet);
  return readable_text_height(lo, hi, options.units, {420.0, 297.0}, 3.0);
}

}  // namespace

Sheet shop_sheet(const std::vector<KitchenPiece>& pieces, const std::vector<std::vector<CutLoop>>& exact,
                 const LayoutOptions& options) {
  std::vector<std::vector<CutLoop>> drawings;
  drawings.reserve(pieces.size());
  for (std::size_t i = 0; i < pieces.size(); ++i) drawings.push_back(piece_drawing(pieces[i], exact[i]));
  const auto draw_all = [&](std::size_t per_row, double h) {
    std::vector<Sheet> each;
    each.reserve(pieces.size());
    for (std::size_t i = 0; i < pieces.size(); ++i)
      each.push_back(draw_piece(pieces[i], drawings[i], options, h));
    return draw(each, options, per_row, h);
  };
  // The text grows with the sheet it is read on, and the sheet with the
  // dimensions' rows: for each number of pieces to a row, grow it until the
  // whole sheet scaled to A3 prints it at 3 mm; keep the rows that need the
  // smallest (the sheet that fills A3 best).
  Sheet best;
  double best_h = std::numeric_limits<double>::infinity();
  for (std::size_t per_row = 1; per_row <= std::max<std::size_t>(pieces.size(), 1); ++per_row) {
    double h = 1.0 / millimetres_per_unit(options.units);  // 1 mm
    Sheet sheet = draw_all(per_row, h);
    for (int i = 0; i < 200; ++i) {
      const double readable = a3_text_height(sheet, options);
      if (readable <= h) break;
      h = std::max(readable, 1.02 * h);
      sheet = draw_all(per_row, h);
    }
    if (h < best_h) {
      best_h = h;
      best = std::move(sheet);
    }
  }
  return best;
}

}  // namespace fabmesh
