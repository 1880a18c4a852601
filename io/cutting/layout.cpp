#include "io/cutting/layout.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>

#include "io/cutting/svg_writing.h"

namespace fabmesh {
namespace {

// The gap between two slabs drawn one above the other, model units.
double slab_gap(const SlabStock& stock) { return 0.1 * stock.width; }

// Path data of a closed loop moved by `shift`.
std::string loop_path(const std::vector<Vec2>& loop, const Vec2& shift) {
  std::string d;
  for (std::size_t k = 0; k < loop.size(); ++k) d += (k == 0 ? "M " : " L ") + svg_point(loop[k] + shift);
  return d + " Z";
}

std::array<Vec2, 2> box_of(const std::vector<Vec2>& loop) {
  Vec2 lo = loop.front(), hi = loop.front();
  for (const Vec2& p : loop) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return {lo, hi};
}

std::string number(double v) { return svg_number(v); }

std::string slab_caption(std::size_t s, const SlabStock& stock, const SlabNesting& nesting, double free_area,
                         const std::string& units) {
  return fmt::format("slab {} of {}: {} x {} {}, {:.1f}% of the usable area used, {:.4g} {}^2 free", s + 1,
                     nesting.slabs, number(stock.length), number(stock.width), units,
                     100.0 * (s < nesting.utilisation.size() ? nesting.utilisation[s] : 0.0), free_area,
                     units);
}

std::string piece_caption(const KitchenPiece& piece, const Placement& p, const std::string& units) {
  const auto box = box_of(p.outer);
  return fmt::format("{} ({} x {} {}, turned {})", piece.name, shop_number(box[1].x() - box[0].x()),
                     shop_number(box[1].y() - box[0].y()), units, p.rotation_deg);
}

double used_area(const std::vector<KitchenPiece>& pieces, const SlabNesting& nesting, std::size_t s) {
  double used = 0.0;
  for (const Placement& p : nesting.placements) used += p.slab == s ? pieces[p.piece].area : 0.0;
  return used;
}

CutLoop moved(const CutLoop& loop, const Vec2& shift) {
  Placement at;
  at.offset = shift;
  return placed_loop(loop, at);
}

}  // namespace

std::string encode_layout_svg(const std::vector<KitchenPiece>& pieces, const SlabStock& stock,
                              const SlabNesting& nesting, const LayoutOptions& options) {
  const double gap = slab_gap(stock);
  const double step = stock.width + gap;
  const double n = static_cast<double>(std::max<std::size_t>(nesting.slabs, 1));
  // Slab s (0-based) lies at y from (n - 1 - s) * step: slab 1 at the top.
  const Vec2 lo(0.0, 0.0), hi(stock.length, n * step - gap);
  const double text = std::max(stock.width / 40.0, 1e-9);
  std::string svg = svg_start(lo, hi, 2.0 * text, options.units);
  svg += fmt::format("<title>{} slab layout</title>\n", options.title);
  const double usable = (stock.length - 2.0 * stock.margin) * (stock.width - 2.0 * stock.margin);
  for (std::size_t s = 0; s < nesting.slabs; ++s) {
    const Vec2 shift(0.0, static_cast<double>(nesting.slabs - 1 - s) * step);
    const double used = used_area(pieces, nesting, s);
    svg += fmt::format("<g id=\"slab-{}\">\n", s + 1);
    const std::vector<Vec2> rect{
        {0.0, 0.0}, {stock.length, 0.0}, {stock.length, stock.width}, {0.0, stock.width}};
    svg +=
        fmt::format("<path class=\"free\" d=\"{}\" fill=\"#e8e4dc\" stroke=\"black\" stroke-width=\"{}\"/>\n",
                    loop_path(rect, shift), number(text / 8.0));
    const std::vector<Vec2> inner{{stock.margin, stock.margin},
                                  {stock.length - stock.margin, stock.margin},
                                  {stock.length - stock.margin, stock.width - stock.margin},
                                  {stock.margin, stock.width - stock.margin}};
    svg += fmt::format(
        "<path class=\"margin\" d=\"{}\" fill=\"none\" stroke=\"#777\" stroke-width=\"{}\" "
        "stroke-dasharray=\"{} {}\"/>\n",
        loop_path(inner, shift), number(text / 12.0), number(text / 2.0), number(text / 3.0));
    for (const SlabDefect& d : stock.defects) {
      if (d.radius > 0.0) {
        const Vec2 c = d.center + shift;
        svg += fmt::format(
            "<circle class=\"defect\" cx=\"{}\" cy=\"{}\" r=\"{}\" fill=\"#d33\" fill-opacity=\"0.5\" "
            "stroke=\"#d33\"/>\n",
            number(c.x()), number(-c.y()), number(d.radius));
      } else {
        svg += fmt::format(
            "<path class=\"defect\" d=\"{}\" fill=\"#d33\" fill-opacity=\"0.5\" stroke=\"#d33\"/>\n",
            loop_path(d.polygon, shift));
      }
    }
    for (const Placement& p : nesting.placements) {
      if (p.slab != s) continue;
      const KitchenPiece& piece = pieces[p.piece];
      std::string d = loop_path(p.outer, shift);
      for (const auto& hole : piece.holes) {
        d += " " + loop_path(place_loop(hole, p), shift);
      }
      svg += fmt::format(
          "<path class=\"piece\" id=\"{}\" d=\"{}\" fill=\"white\" fill-rule=\"evenodd\" stroke=\"black\" "
          "stroke-width=\"{}\"/>\n",
          piece.name, d, number(text / 8.0));
      // Seam edges heavier: where the pieces join.
      for (std::size_t e = 0; e < p.outer.size(); ++e) {
        if (piece.edges[e] != EdgeKind::Seam) continue;
        const Vec2 a = p.outer[e] + shift, b = p.outer[(e + 1) % p.outer.size()] + shift;
        svg += fmt::format("<path class=\"seam\" d=\"M {} L {}\" stroke=\"#06c\" stroke-width=\"{}\"/>\n",
                           svg_point(a), svg_point(b), number(text / 3.0));
      }
      const auto box = box_of(p.outer);
      const Vec2 mid = 0.5 * (box[0] + box[1]) + shift;
      svg += fmt::format(
          "<text x=\"{}\" y=\"{}\" font-size=\"{}\" text-anchor=\"middle\" "
          "font-family=\"sans-serif\">{}</text>\n",
          number(mid.x()), number(-mid.y()), number(text), piece_caption(piece, p, options.units));
    }
    svg += fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"{}\" font-family=\"sans-serif\">{}</text>\n",
                       number(0.0), number(-(shift.y() + stock.width + 0.4 * text)), number(text),
                       slab_caption(s, stock, nesting, usable - used, options.units));
    svg += "</g>\n";
  }
  return svg + "</svg>\n";
}

std::vector<CutLoop> piece_drawing(const KitchenPiece& piece, const std::vector<CutLoop>& exact) {
  if (!exact.empty()) return exact;
  std::vector<CutLoop> loops{polygon_loop(piece.outer, piece.name, true)};
  for (const auto& hole : piece.holes) loops.push_back(polygon_loop(hole, piece.name + " cut-out", false));
  return loops;
}

CutLoop placed_loop(const CutLoop& loop, const Placement& at) {
  CutLoop out = loop;
  for (CutEntity& e : out.entities) {
    for (Vec2& p : e.points) p = place_point(p, at.rotation_deg, at.offset);
    if (e.kind == CutKind::Arc) {
      e.arc.center = place_point(e.arc.center, at.rotation_deg, at.offset);
      e.arc.rotation_deg += at.rotation_deg;
    }
  }
  return out;
}

Sheet layout_sheet(const std::vector<KitchenPiece>& pieces, const std::vector<std::vector<CutLoop>>& exact,
                   const SlabStock& stock, const SlabNesting& nesting, const LayoutOptions& options) {
  const double gap = slab_gap(stock);
  const double step = stock.width + gap;
  const double n = static_cast<double>(std::max<std::size_t>(nesting.slabs, 1));
  Sheet sheet;
  sheet.layers = {{"SLABS", 8, "#555"},   {"MARGINS", 9, "#999"},    {"DEFECTS", 1, "#d33"},
                  {"PIECES", 7, "black"}, {"SEAMS", 5, "#06c", 3.0}, {"LABELS", 3, "#070"}};
  // Captions below each slab: the sheet's box is the slabs and a gap.
  const double h = readable_text_height(Vec2(0.0, -gap), Vec2(stock.length, n * step - gap), options.units,
                                        {420.0, 297.0}, 3.0);
  sheet.text_height = h;
  const double usable = (stock.length - 2.0 * stock.margin) * (stock.width - 2.0 * stock.margin);
  const double m = stock.margin;
  for (std::size_t s = 0; s < nesting.slabs; ++s) {
    const Vec2 shift(0.0, static_cast<double>(nesting.slabs - 1 - s) * step);
    sheet.loops.push_back(
        {"SLABS",
         moved(
             polygon_loop({{0.0, 0.0}, {stock.length, 0.0}, {stock.length, stock.width}, {0.0, stock.width}},
                          fmt::format("slab {}", s + 1), true),
             shift)});
    sheet.loops.push_back(
        {"MARGINS",
         moved(polygon_loop(
                   {{m, m}, {stock.length - m, m}, {stock.length - m, stock.width - m}, {m, stock.width - m}},
                   "usable area", true),
               shift)});
    for (const SlabDefect& d : stock.defects) {
      CutLoop loop;
      if (d.radius > 0.0) {
        CutEntity circle;
        circle.kind = CutKind::Arc;
        circle.arc = {d.center, d.radius, d.radius, 0.0, 0.0, 360.0};
        circle.points = {arc_point(circle.arc, 0.0), arc_point(circle.arc, 360.0)};
        loop.label = "defect";
        loop.entities = {circle};
      } else {
        loop = polygon_loop(d.polygon, "defect", false);
      }
      sheet.loops.push_back({"DEFECTS", moved(loop, shift)});
    }
    for (const Placement& p : nesting.placements) {
      if (p.slab != s) continue;
      const KitchenPiece& piece = pieces[p.piece];
      Placement at = p;
      at.offset += shift;
      for (const CutLoop& loop : piece_drawing(piece, exact[p.piece]))
        sheet.loops.push_back({"PIECES", placed_loop(loop, at)});
      for (std::size_t e = 0; e < p.outer.size(); ++e) {
        if (piece.edges[e] == EdgeKind::Seam)
          sheet.lines.push_back({"SEAMS", p.outer[e] + shift, p.outer[(e + 1) % p.outer.size()] + shift});
      }
      const auto box = box_of(p.outer);
      sheet.texts.push_back(
          {"LABELS", 0.5 * (box[0] + box[1]) + shift, h, piece_caption(piece, p, options.units), true});
    }
    sheet.texts.push_back(
        {"LABELS", Vec2(0.0, shift.y() - 1.5 * h), h,
         slab_caption(s, stock, nesting, usable - used_area(pieces, nesting, s), options.units)});
  }
  return sheet;
}

std::string encode_cutlist(const std::vector<KitchenPiece>& pieces, const SlabNesting& nesting,
                           const LayoutOptions& options) {
  std::string csv = fmt::format(
      "piece,slab,x_{0},y_{0},rotation_deg,length_{0},width_{0},area_{0}2,exposed_length_{0},wall_length_{0},"
      "seam_length_{0},cutouts\n",
      options.units);
  for (const Placement& p : nesting.placements) {
    const KitchenPiece& piece = pieces[p.piece];
    const auto box = box_of(p.outer);
    const auto lengths = edge_lengths(piece);
    std::string holes;
    for (const std::size_t h : piece.hole_index) holes += (holes.empty() ? "" : " ") + std::to_string(h);
    csv +=
        fmt::format("{},{},{},{},{},{},{},{},{},{},{},{}\n", piece.name, p.slab + 1, shop_number(box[0].x()),
                    shop_number(box[0].y()), p.rotation_deg, shop_number(box[1].x() - box[0].x()),
                    shop_number(box[1].y() - box[0].y()), shop_number(piece.area), shop_number(lengths[0]),
                    shop_number(lengths[1]), shop_number(lengths[2]), holes);
  }
  return csv;
}

}  // namespace fabmesh
