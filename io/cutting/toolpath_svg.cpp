#include "io/cutting/toolpath_svg.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/core/error_checks.h"
#include "io/cutting/svg_writing.h"
#include "io/file.h"

namespace fabmesh {
namespace {

// A path piece as L or A commands (arcs in pieces of at most 120 degrees).
void append_piece(std::string& d, const PathPiece& p) {
  if (p.kind == PieceKind::Line) {
    d += " L " + svg_point(p.to);
    return;
  }
  const double r = piece_radius(p);
  const int pieces = std::max(1, static_cast<int>(std::ceil(std::abs(p.sweep) / (2.0 * M_PI / 3.0))));
  const double a0 = std::atan2(p.from.y() - p.center.y(), p.from.x() - p.center.x());
  for (int i = 1; i <= pieces; ++i) {
    const Vec2 end = i == pieces ? p.to
                                 : p.center + r * Vec2(std::cos(a0 + p.sweep * i / pieces),
                                                       std::sin(a0 + p.sweep * i / pieces));
    d += fmt::format(" A {} {} 0 0 {} {}", svg_number(r), svg_number(r), p.sweep > 0.0 ? 0 : 1,
                     svg_point(end));
  }
}

// The sub-chain of a closed path between distances a < b from its start.
std::vector<PathPiece> sub_path(const std::vector<PathPiece>& pieces, double a, double b) {
  std::vector<PathPiece> out;
  double u = 0.0;
  for (const PathPiece& p : pieces) {
    const double len = piece_length(p);
    const double lo = std::max(a, u), hi = std::min(b, u + len);
    if (hi > lo) {
      PathPiece part = p;
      if (hi < u + len) part = split_piece(part, hi - u).first;
      if (lo > u) part = split_piece(part, lo - u).second;
      out.push_back(part);
    }
    u += len;
  }
  return out;
}

struct Bounds {
  Vec2 lo = Vec2::Constant(INFINITY), hi = Vec2::Constant(-std::numeric_limits<double>::infinity());
  void add(const Vec2& p) { lo = lo.cwiseMin(p), hi = hi.cwiseMax(p); }
  void add(const PathPiece& p) {
    for (const Vec2& q : piece_polyline(p, 1e-3 * (1.0 + piece_radius(p)))) add(q);
  }
};

std::string chain(const std::vector<PathPiece>& pieces) {
  std::string d = "M " + svg_point(pieces.front().from);
  for (const PathPiece& p : pieces) append_piece(d, p);
  return d;
}

}  // namespace

std::string encode_toolpath_svg(const std::vector<CutLoop>& part, const Toolpath& path,
                                const ToolpathSvgOptions& options) {
  require_in_range("margin", options.margin, 0.0, INFINITY);
  const double r = 0.5 * path.options.tool_diameter;
  Bounds box;
  if (!part.empty()) {
    const auto [lo, hi] = cut_bounds(part);
    box.add(lo), box.add(hi);
  }
  for (const LoopPath& lp : path.loops) {
    for (const PathPiece& p : lp.pieces) box.add(p);
    if (lp.lead) box.add(*lp.lead);
    const Vec2 plunge = lp.lead ? lp.lead->from : lp.pieces.front().from;
    box.add(plunge - Vec2(r, r)), box.add(plunge + Vec2(r, r));
  }
  for (const DrillHole& h : path.drills) {
    const Vec2 half(0.5 * h.diameter, 0.5 * h.diameter);
    box.add(h.center - half), box.add(h.center + half);
  }
  const double m = options.margin;
  const double w = box.hi.x() - box.lo.x() + 2 * m, h = box.hi.y() - box.lo.y() + 2 * m;
  const double stroke = std::max(w, h) / 1500.0;
  std::string out = svg_start(box.lo, box.hi, m, options.units);
  out += fmt::format("  <title>toolpath: tool diameter {}, {} passes, {} cutting</title>\n",
                     svg_number(path.options.tool_diameter), path.pass_z.size(),
                     to_string(path.options.direction));
  std::string d;
  for (const CutLoop& loop : part) {
    append_svg_loop(d, loop);
    d += " Z";
  }
  if (!d.empty()) {
    out += fmt::format(
        "  <path id=\"part\" d=\"{}\" fill=\"#e8e2d6\" fill-rule=\"evenodd\" stroke=\"black\" "
        "stroke-width=\"{}\"/>\n",
        d, svg_number(2 * stroke));
  }
  for (std::size_t i = 0; i < path.loops.size(); ++i) {
    const LoopPath& lp = path.loops[i];
    out += fmt::format(
        "  <path id=\"path-{}\" d=\"{} Z\" fill=\"none\" stroke=\"#1f5fbf\" stroke-width=\"{}\" "
        "stroke-dasharray=\"{} {}\"/>\n",
        i, chain(lp.pieces), svg_number(stroke), svg_number(8 * stroke), svg_number(4 * stroke));
    if (lp.lead) {
      out += fmt::format(
          "  <path id=\"lead-{}\" d=\"{}\" fill=\"none\" stroke=\"#1a9a3a\" stroke-width=\"{}\"/>\n", i,
          chain({*lp.lead}), svg_number(2 * stroke));
    }
    const Vec2 plunge = lp.lead ? lp.lead->from : lp.pieces.front().from;
    out += fmt::format(
        "  <circle id=\"plunge-{}\" cx=\"{}\" cy=\"{}\" r=\"{}\" fill=\"none\" stroke=\"#d02020\" "
        "stroke-width=\"{}\"/>\n",
        i, svg_number(plunge.x()), svg_number(-plunge.y()), svg_number(r), svg_number(stroke));
    for (std::size_t j = 0; j < lp.tabs.size(); ++j) {
      out += fmt::format(
          "  <path id=\"tab-{}-{}\" d=\"{}\" fill=\"none\" stroke=\"#f08000\" stroke-width=\"{}\"/>\n", i, j,
          chain(sub_path(lp.pieces, lp.tabs[j].first, lp.tabs[j].second)), svg_number(r));
    }
    // A dog-bone is a run X -> D and back: draw the run and the tool's disc at D (the overcut).
    std::size_t k = 0;
    for (std::size_t j = 0; j + 1 < lp.pieces.size(); ++j) {
      const PathPiece& p = lp.pieces[j];
      if (p.role != PieceRole::Dogbone || lp.pieces[j + 1].role != PieceRole::Dogbone) continue;
      out += fmt::format(
          "  <g id=\"dogbone-{}-{}\" fill=\"none\" stroke=\"#b000b0\" stroke-width=\"{}\">"
          "<path d=\"M {} L {}\"/><circle cx=\"{}\" cy=\"{}\" r=\"{}\"/></g>\n",
          i, k++, svg_number(stroke), svg_point(p.from), svg_point(p.to), svg_number(p.to.x()),
          svg_number(-p.to.y()), svg_number(r));
      ++j;
    }
  }
  // A drilled hole: the drill's circle and a cross through its centre.
  for (std::size_t k = 0; k < path.drills.size(); ++k) {
    const DrillHole& drill = path.drills[k];
    const double hr = 0.5 * drill.diameter;
    const Vec2 c = drill.center;
    out += fmt::format(
        "  <g id=\"drill-{}\" fill=\"none\" stroke=\"#d02020\" stroke-width=\"{}\"><title>T{} drill "
        "{}</title>"
        "<circle cx=\"{}\" cy=\"{}\" r=\"{}\"/><path d=\"M {} L {} M {} L {}\"/></g>\n",
        k, svg_number(stroke), drill.tool, svg_number(drill.diameter), svg_number(c.x()), svg_number(-c.y()),
        svg_number(hr), svg_point(c - Vec2(hr, 0.0)), svg_point(c + Vec2(hr, 0.0)),
        svg_point(c - Vec2(0.0, hr)), svg_point(c + Vec2(0.0, hr)));
  }
  out += "</svg>\n";
  return out;
}

void write_toolpath_svg(const std::string& file, const std::vector<CutLoop>& part, const Toolpath& path,
                        const ToolpathSvgOptions& options) {
  write_file_atomically(file, encode_toolpath_svg(part, path, options));
}

}  // namespace fabmesh
