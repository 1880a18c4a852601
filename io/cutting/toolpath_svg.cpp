#include "io/cutting/toolpath_svg.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/core/errors.h"
#include "io/file.h"

namespace fabmesh {
namespace {

std::string num(double v) { return fmt::format("{}", v == 0.0 ? 0.0 : v); }
std::string pt(const Vec2& p) { return num(p.x()) + " " + num(-p.y()); }

// Exact part arcs as A commands of at most 120 degrees (as svg.cpp draws them).
void append_part_arc(std::string& d, const EllipseArcParams& a) {
  const double span = a.to_deg - a.from_deg;
  const int pieces = std::max(1, static_cast<int>(std::ceil(std::abs(span) / 120.0)));
  const int sweep = span > 0.0 ? 0 : 1;
  for (int i = 1; i <= pieces; ++i) {
    const Vec2 end = arc_point(a, a.from_deg + span * i / pieces);
    d += fmt::format(" A {} {} {} 0 {} {}", num(a.a), num(a.b), num(-a.rotation_deg), sweep, pt(end));
  }
}

// A path piece as L or A commands (arcs in pieces of at most 120 degrees).
void append_piece(std::string& d, const PathPiece& p) {
  if (p.kind == PieceKind::Line) {
    d += " L " + pt(p.to);
    return;
  }
  const double r = piece_radius(p);
  const int pieces = std::max(1, static_cast<int>(std::ceil(std::abs(p.sweep) / (2.0 * M_PI / 3.0))));
  const double a0 = std::atan2(p.from.y() - p.center.y(), p.from.x() - p.center.x());
  for (int i = 1; i <= pieces; ++i) {
    const Vec2 end = i == pieces ? p.to
                                 : p.center + r * Vec2(std::cos(a0 + p.sweep * i / pieces),
                                                       std::sin(a0 + p.sweep * i / pieces));
    d += fmt::format(" A {} {} 0 0 {} {}", num(r), num(r), p.sweep > 0.0 ? 0 : 1, pt(end));
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
  std::string d = "M " + pt(pieces.front().from);
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
  const double m = options.margin;
  const double w = box.hi.x() - box.lo.x() + 2 * m, h = box.hi.y() - box.lo.y() + 2 * m;
  const double scale = options.units == "m" ? 1000.0 : 1.0;
  const std::string unit = options.units == "m" ? "mm" : options.units;
  const double stroke = std::max(w, h) / 1500.0;
  std::string out = fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}{}\" height=\"{}{}\" viewBox=\"{} {} {} {}\">\n"
      "  <title>toolpath: tool diameter {}, {} passes, {} cutting</title>\n",
      num(w * scale), unit, num(h * scale), unit, num(box.lo.x() - m), num(-(box.hi.y() + m)), num(w), num(h),
      num(path.options.tool_diameter), path.pass_z.size(), to_string(path.options.direction));
  std::string d;
  for (const CutLoop& loop : part) {
    for (const CutEntity& e : loop.entities) {
      if (&e == &loop.entities.front()) d += (d.empty() ? "M " : " M ") + pt(e.points.front());
      if (e.kind == CutKind::Arc) {
        append_part_arc(d, e.arc);
      } else {
        for (std::size_t i = 1; i < e.points.size(); ++i) d += " L " + pt(e.points[i]);
      }
    }
    d += " Z";
  }
  if (!d.empty()) {
    out += fmt::format(
        "  <path id=\"part\" d=\"{}\" fill=\"#e8e2d6\" fill-rule=\"evenodd\" stroke=\"black\" "
        "stroke-width=\"{}\"/>\n",
        d, num(2 * stroke));
  }
  for (std::size_t i = 0; i < path.loops.size(); ++i) {
    const LoopPath& lp = path.loops[i];
    out += fmt::format(
        "  <path id=\"path-{}\" d=\"{} Z\" fill=\"none\" stroke=\"#1f5fbf\" stroke-width=\"{}\" "
        "stroke-dasharray=\"{} {}\"/>\n",
        i, chain(lp.pieces), num(stroke), num(8 * stroke), num(4 * stroke));
    if (lp.lead) {
      out += fmt::format(
          "  <path id=\"lead-{}\" d=\"{}\" fill=\"none\" stroke=\"#1a9a3a\" stroke-width=\"{}\"/>\n", i,
          chain({*lp.lead}), num(2 * stroke));
    }
    const Vec2 plunge = lp.lead ? lp.lead->from : lp.pieces.front().from;
    out += fmt::format(
        "  <circle id=\"plunge-{}\" cx=\"{}\" cy=\"{}\" r=\"{}\" fill=\"none\" stroke=\"#d02020\" "
        "stroke-width=\"{}\"/>\n",
        i, num(plunge.x()), num(-plunge.y()), num(r), num(stroke));
    for (std::size_t j = 0; j < lp.tabs.size(); ++j) {
      out += fmt::format(
          "  <path id=\"tab-{}-{}\" d=\"{}\" fill=\"none\" stroke=\"#f08000\" stroke-width=\"{}\"/>\n", i, j,
          chain(sub_path(lp.pieces, lp.tabs[j].first, lp.tabs[j].second)), num(r));
    }
    // A dog-bone is a run X -> D and back: draw the run and the tool's disc at D (the overcut).
    std::size_t k = 0;
    for (std::size_t j = 0; j + 1 < lp.pieces.size(); ++j) {
      const PathPiece& p = lp.pieces[j];
      if (p.role != PieceRole::Dogbone || lp.pieces[j + 1].role != PieceRole::Dogbone) continue;
      out += fmt::format(
          "  <g id=\"dogbone-{}-{}\" fill=\"none\" stroke=\"#b000b0\" stroke-width=\"{}\">"
          "<path d=\"M {} L {}\"/><circle cx=\"{}\" cy=\"{}\" r=\"{}\"/></g>\n",
          i, k++, num(stroke), pt(p.from), pt(p.to), num(p.to.x()), num(-p.to.y()), num(r));
      ++j;
    }
  }
  out += "</svg>\n";
  return out;
}

void write_toolpath_svg(const std::string& file, const std::vector<CutLoop>& part, const Toolpath& path,
                        const ToolpathSvgOptions& options) {
  write_file_atomically(file, encode_toolpath_svg(part, path, options));
}

}  // namespace fabmesh
