#include "io/cutting/sheet.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/core/units.h"
#include "io/cutting/svg_writing.h"
#include "io/pictures/markup.h"

namespace fabmesh {
namespace {

Vec2 direction(double deg) {
  const double r = deg * M_PI / 180.0;
  // Quarter turns exactly: a vertical dimension's points keep their x.
  if (deg == 0.0) return {1.0, 0.0};
  if (deg == 90.0) return {0.0, 1.0};
  return {std::cos(r), std::sin(r)};
}

void grow(Vec2& lo, Vec2& hi, const Vec2& p) {
  lo = lo.cwiseMin(p);
  hi = hi.cwiseMax(p);
}

std::string svg_text(const Vec2& at, double height, double angle_deg, bool centred, const std::string& text,
                     const std::string& colour) {
  const std::string turn = angle_deg == 0.0
                               ? std::string()
                               : fmt::format(" transform=\"rotate({} {})\"", svg_number(-angle_deg),
                                             svg_number(at.x()) + " " + svg_number(-at.y()));
  return fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"{}\" fill=\"{}\" stroke=\"none\"{}{}>{}</text>\n",
                     svg_number(at.x()), svg_number(-at.y()), svg_number(height), colour,
                     centred ? " text-anchor=\"middle\"" : "", turn, escape_markup(text));
}

}  // namespace

CutLoop polygon_loop(const std::vector<Vec2>& points, const std::string& label, bool outer) {
  CutLoop loop;
  loop.label = label;
  loop.outer = outer;
  loop.closed = true;
  CutEntity chain;
  chain.kind = CutKind::Polyline;
  chain.points = points;
  chain.points.push_back(points.front());
  loop.entities.push_back(std::move(chain));
  return loop;
}

std::string shop_number(double v) {
  std::string s = fmt::format("{:.3f}", v);
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  return s == "-0" ? "0" : s;
}

DimensionGraphic dimension_graphic(const SheetDimension& d, double text_height) {
  const double h = text_height;
  const Vec2 u = direction(d.angle_deg);
  const Vec2 n(-u.y(), u.x());
  const double t = d.through.dot(n);
  // The dimension line's ends: the measured points projected onto it.
  const Vec2 a = d.from + (t - d.from.dot(n)) * n;
  const Vec2 b = d.to + (t - d.to.dot(n)) * n;
  DimensionGraphic g;
  g.value = std::abs((d.to - d.from).dot(u));
  g.text = shop_number(g.value);
  for (const auto& [p, end] : {std::pair<Vec2, Vec2>{d.from, a}, std::pair<Vec2, Vec2>{d.to, b}}) {
    const Vec2 away = end - p;
    const double gap = away.norm();
    if (gap <= 0.5 * h) continue;  // the point is on the dimension line
    const Vec2 w = away / gap;
    g.lines.push_back({p + 0.5 * h * w, end + 0.5 * h * w});
  }
  g.lines.push_back({a, b});
  const double span = (b - a).norm();
  if (span > 0.0) {
    const Vec2 in = (b - a) / span;  // from a towards b
    for (const auto& [tip, dir] : {std::pair<Vec2, Vec2>{a, in}, std::pair<Vec2, Vec2>{b, Vec2(-in)}}) {
      const Vec2 side(-dir.y(), dir.x());
      g.arrows.push_back({tip, tip + h * dir + (h / 6.0) * side, tip + h * dir - (h / 6.0) * side});
    }
  }
  // Text reads left to right or bottom to top: above the line, on the side of n.
  g.text_angle_deg = d.angle_deg;
  g.text_at = 0.5 * (a + b) + 0.4 * h * n;
  return g;
}

std::pair<Vec2, Vec2> sheet_bounds(const Sheet& sheet) {
  const double inf = std::numeric_limits<double>::infinity();
  Vec2 lo(inf, inf), hi(-inf, -inf);
  std::vector<CutLoop> loops;
  loops.reserve(sheet.loops.size());
  for (const SheetLoop& l : sheet.loops) loops.push_back(l.loop);
  if (!loops.empty()) {
    const auto [a, b] = cut_bounds(loops);
    grow(lo, hi, a);
    grow(lo, hi, b);
  }
  for (const SheetLine& l : sheet.lines) {
    grow(lo, hi, l.from);
    grow(lo, hi, l.to);
  }
  for (const SheetDimension& d : sheet.dimensions) {
    const DimensionGraphic g = dimension_graphic(d, sheet.text_height);
    for (const auto& line : g.lines) {
      grow(lo, hi, line[0]);
      grow(lo, hi, line[1]);
    }
    const Vec2 u = direction(g.text_angle_deg), n(-u.y(), u.x());
    const double half = 0.3 * sheet.text_height * static_cast<double>(g.text.size());
    grow(lo, hi, g.text_at - half * u);
    grow(lo, hi, g.text_at + half * u + sheet.text_height * n);
  }
  for (const SheetText& t : sheet.texts) {
    const double w = 0.6 * t.height * static_cast<double>(t.text.size());
    const Vec2 start = t.centred ? t.at - Vec2(0.5 * w, 0.0) : t.at;
    grow(lo, hi, start);
    grow(lo, hi, start + Vec2(w, t.height));
  }
  if (lo.x() > hi.x()) return {Vec2(0.0, 0.0), Vec2(0.0, 0.0)};
  return {lo, hi};
}

double readable_text_height(const Vec2& lo, const Vec2& hi, const std::string& units,
                            const std::array<double, 2>& paper, double paper_mm) {
  const double mm = millimetres_per_unit(units);
  const double w = std::max((hi.x() - lo.x()) * mm, 1e-9), h = std::max((hi.y() - lo.y()) * mm, 1e-9);
  const double pw = paper[0] - 20.0, ph = paper[1] - 20.0;
  // Paper millimetres per model millimetre, the sheet upright or turned.
  const double scale = std::max(std::min(pw / w, ph / h), std::min(ph / w, pw / h));
  return paper_mm / (scale * mm);
}

std::string encode_sheet_svg(const Sheet& sheet, const std::string& units, const std::string& title) {
  const auto [lo, hi] = sheet_bounds(sheet);
  const double h = sheet.text_height;
  std::string svg = svg_start(lo, hi, 2.0 * h, units);
  svg += fmt::format("<title>{}</title>\n", escape_markup(title));
  for (const SheetLayer& layer : sheet.layers) {
    std::string body;
    const double stroke = layer.weight * h / 8.0;
    for (const SheetLoop& l : sheet.loops) {
      if (l.layer != layer.name) continue;
      std::string d;
      append_svg_loop(d, l.loop);
      if (l.loop.closed) d += " Z";
      body += fmt::format("<path d=\"{}\" fill=\"none\" stroke-width=\"{}\"/>\n", d, svg_number(stroke));
    }
    for (const SheetLine& l : sheet.lines) {
      if (l.layer != layer.name) continue;
      body += fmt::format("<path d=\"M {} L {}\" stroke-width=\"{}\"/>\n", svg_point(l.from), svg_point(l.to),
                          svg_number(stroke));
    }
    for (const SheetDimension& dim : sheet.dimensions) {
      if (dim.layer != layer.name) continue;
      const DimensionGraphic g = dimension_graphic(dim, h);
      std::string d;
      for (const auto& line : g.lines)
        d += (d.empty() ? "M " : " M ") + svg_point(line[0]) + " L " + svg_point(line[1]);
      body += fmt::format("<g class=\"dimension\"><path d=\"{}\" stroke-width=\"{}\"/>\n", d,
                          svg_number(h / 16.0));
      for (const auto& tri : g.arrows) {
        body += fmt::format("<path d=\"M {} L {} L {} Z\" fill=\"{}\" stroke=\"none\"/>\n", svg_point(tri[0]),
                            svg_point(tri[1]), svg_point(tri[2]), layer.colour);
      }
      body += svg_text(g.text_at, h, g.text_angle_deg, true, g.text, layer.colour) + "</g>\n";
    }
    for (const SheetText& t : sheet.texts) {
      if (t.layer == layer.name) body += svg_text(t.at, t.height, 0.0, t.centred, t.text, layer.colour);
    }
    if (body.empty()) continue;
    svg += fmt::format("<g id=\"{}\" stroke=\"{}\" fill=\"none\" font-family=\"sans-serif\">\n{}</g>\n",
                       layer.name, layer.colour, body);
  }
  return svg + "</svg>\n";
}

}  // namespace fabmesh
