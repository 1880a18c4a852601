#include "io/design/dxf_loops.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <string_view>
#include <utility>

#include "geometry/core/errors.h"
#include "geometry/core/units.h"
#include "geometry/curves/segment.h"
#include "io/design/number_limits.h"
#include "io/dxf/dxf_chains.h"
#include "io/dxf/dxf_reader.h"
#include "io/dxf/dxf_spline.h"
#include "io/file.h"

namespace fabmesh {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegree = 180.0 / kPi;
constexpr std::size_t kMaxDxfBytes = 64u << 20;

// The $INSUNITS codes a drawing may carry: metres per unit.
struct DxfUnit {
  int code;
  const char* name;
  double metres;
};
constexpr DxfUnit kDxfUnits[] = {
    {1, "in", 0.0254}, {2, "ft", 0.3048}, {4, "mm", 1e-3}, {5, "cm", 1e-2}, {6, "m", 1.0},
};

// A polyline as read: vertices (x, y) with the bulge of the span after each.
struct Polyline {
  std::string entity;
  std::size_t order = 0;
  bool closed = false;
  bool mirrored = false;
  std::vector<std::array<double, 3>> vertices;
};

// An entity's largest |z| (drawing units), checked once the drawing's size is known.
struct Height {
  std::string entity;
  std::size_t line = 0;
  double z = 0.0;
};

std::string fmt_point(const Vec2& p) { return fmt::format("({:.10g}, {:.10g})", p.x(), p.y()); }

// Start and end of an exact arc, as the segment evaluates them.
void arc_ends(DxfPiece& piece) {
  const Segment s = Segment::ellipse_arc(piece.ellipse);
  piece.start = s.point(0.0);
  piece.end = s.point(1.0);
}

bool finite_arc(const DxfPiece& p) {
  const EllipseArcParams& e = p.ellipse;
  return std::isfinite(e.center.x()) && std::isfinite(e.center.y()) && std::isfinite(e.a) &&
         std::isfinite(e.b) && std::isfinite(e.from_deg) && std::isfinite(e.to_deg);
}

// The entities a loop may be made of, on the wanted layer in model space
// (drawing units): lines, arcs and splines as pieces, polylines as read; and
// what the report says about the rest. Refuses what no loop can be made of.
class Collector {
 public:
  Collector(std::string layer, std::string path, std::string where)
      : layer_(std::move(layer)), path_(std::move(path)), where_(std::move(where)) {}

  std::vector<DxfPiece> pieces;
  std::vector<Polyline> polylines;
  std::vector<Height> heights;                  // entities not at z = 0
  std::map<std::string, std::size_t> left_out;  // entity type -> count, on the wanted layer
  std::set<std::string> layers;                 // layers with loop entities in model space
  std::size_t paper_space = 0;                  // loop entities on the wanted layer in paper space

  void take(const DxfEntity& e) {
    static const std::set<std::string_view> left_out_kinds = {"POINT", "TEXT", "MTEXT",  "HATCH",    "SOLID",
                                                              "XLINE", "RAY",  "LEADER", "DIMENSION"};
    static const std::set<std::string_view> loop_kinds = {"LINE",       "ARC",      "CIRCLE", "ELLIPSE",
                                                          "LWPOLYLINE", "POLYLINE", "SPLINE", "INSERT"};
    if (left_out_kinds.count(e.type) > 0) {
      if (!e.paper_space && on_layer(e)) ++left_out[e.type];
      return;
    }
    if (loop_kinds.count(e.type) == 0 || !wanted(e)) return;
    if (e.type == "LINE") return line(e);
    if (e.type == "ARC" || e.type == "CIRCLE") return arc(e);
    if (e.type == "ELLIPSE") return ellipse(e);
    if (e.type == "SPLINE") return spline(e);
    if (e.type == "INSERT")
      fail(e, "a block reference on the layer: explode it so its lines and arcs are in the layer");
    polyline(e);
  }

 private:
  bool on_layer(const DxfEntity& e) const { return layer_.empty() || e.layer == layer_; }
  // An entity of a loop kind: on the wanted layer, in model space.
  bool wanted(const DxfEntity& e) {
    if (e.paper_space) {
      if (on_layer(e)) ++paper_space;
      return false;
    }
    if (layers.size() < 64) layers.insert(e.layer);
    return on_layer(e);
  }
  [[noreturn]] void fail(const DxfEntity& e, const std::string& why) const {
    throw FileError(path_, static_cast<int>(e.line), 1,
                    fmt::format("{}: {}: {}", where_, dxf_entity_name(e), why));
  }
  static bool mirrored(const DxfEntity& e) { return e.extrusion.z() < 0.0; }
  // Arcs, circles, ellipses and polylines are in the entity's own
  // coordinates: only those of the drawing's plane (extrusion +-Z) are read.
  void in_plane(const DxfEntity& e) const {
    const Vec3& dir = e.extrusion;
    if (std::abs(dir.x()) > 1e-9 || std::abs(dir.y()) > 1e-9 || !(std::abs(dir.z()) > 0.0)) {
      fail(e, fmt::format("its plane (extrusion ({}, {}, {})) is not the drawing's XY plane", dir.x(),
                          dir.y(), dir.z()));
    }
  }
  void height(const DxfEntity& e, double z) {
    if (z != 0.0) heights.push_back({dxf_entity_name(e), e.line, z});
  }
  DxfPiece piece(const DxfEntity& e) const {
    DxfPiece p;
    p.entity = dxf_entity_name(e);
    p.order = e.line;
    return p;
  }

  void line(const DxfEntity& e) {
    DxfPiece p = piece(e);  // LINE is in world coordinates
    p.start = e.points[0].head<2>();
    p.end = e.points[1].head<2>();
    height(e, std::max(std::abs(e.points[0].z()), std::abs(e.points[1].z())));
    pieces.push_back(std::move(p));
  }
  void arc(const DxfEntity& e) {
    in_plane(e);
    height(e, std::abs(e.points[0].z()));
    if (e.type == "CIRCLE") return add_circle_arc(e, 0.0, 360.0, true);
    double sweep = std::fmod(e.end - e.start, 360.0);
    if (sweep <= 0.0) sweep += 360.0;
    add_circle_arc(e, std::fmod(e.start, 360.0), sweep, false);
  }
  void add_circle_arc(const DxfEntity& e, double from_deg, double sweep_deg, bool whole) {
    DxfPiece p = piece(e);
    Vec2 center = e.points[0].head<2>();
    p.arc = true;
    p.closed = whole;
    if (mirrored(e)) {
      // x -> -x: the arc runs clockwise from the mirrored start angle.
      center.x() = -center.x();
      from_deg = 180.0 - from_deg;
      sweep_deg = -sweep_deg;
    }
    p.ellipse.center = center;
    p.ellipse.a = p.ellipse.b = e.radius;
    p.ellipse.from_deg = from_deg;
    p.ellipse.to_deg = from_deg + sweep_deg;
    if (!finite_arc(p) || !(e.radius > 0.0)) fail(e, fmt::format("radius {} is not > 0", e.radius));
    pieces.push_back(std::move(p));
  }
  void ellipse(const DxfEntity& e) {
    in_plane(e);
    // Centre and major axis are in world coordinates; a mirrored extrusion
    // turns the minor axis, so the parameter runs clockwise.
    const Vec3& c = e.points[0];
    const Vec3& m = e.points[1];
    height(e, std::max(std::abs(c.z()), std::abs(c.z() + m.z())));
    const double a = std::hypot(m.x(), m.y());
    double sweep = std::fmod(e.end - e.start, 2.0 * kPi);
    if (sweep <= 0.0) sweep += 2.0 * kPi;
    const bool whole = std::abs(e.end - e.start - 2.0 * kPi) < 1e-12 || sweep >= 2.0 * kPi;
    if (whole) sweep = 2.0 * kPi;
    const double from = std::fmod(e.start, 2.0 * kPi) * kDegree;
    const double sign = mirrored(e) ? -1.0 : 1.0;
    DxfPiece p = piece(e);
    p.arc = true;
    p.closed = whole;
    p.ellipse.center = c.head<2>();
    p.ellipse.a = a;
    p.ellipse.b = a * e.radius;
    p.ellipse.rotation_deg = std::atan2(m.y(), m.x()) * kDegree;
    p.ellipse.from_deg = sign * from;
    p.ellipse.to_deg = sign * (from + sweep * kDegree);
    if (!finite_arc(p) || !(a > 0.0) || !(e.radius > 0.0)) fail(e, "a degenerate ellipse");
    pieces.push_back(std::move(p));
  }
  void polyline(const DxfEntity& e) {
    in_plane(e);
    if ((e.flags & (16 | 64)) != 0) fail(e, "a polygon mesh or polyface, not a curve");
    Polyline pl;
    pl.entity = dxf_entity_name(e);
    pl.order = e.line;
    pl.closed = (e.flags & 1) != 0;
    pl.mirrored = mirrored(e);
    double z = 0.0;
    for (std::size_t i = 0; i < e.points.size(); ++i) {
      pl.vertices.push_back({e.points[i].x(), e.points[i].y(), e.bulges[i]});
      z = std::max(z, std::abs(e.points[i].z()));
    }
    height(e, z);
    polylines.push_back(std::move(pl));
  }
  // A SPLINE of degree 1 to 3 with positive weights as exact cubic pieces
  // (rational where the SPLINE is a NURBS).
  void spline(const DxfEntity& e) {
    if (e.points.empty()) {
      fail(e, e.fit_points > 0 ? "a SPLINE given by fit points only; save it with its control points"
                               : "a SPLINE without control points");
    }
    if (e.degree < 1 || e.degree > 3)
      fail(e, fmt::format("degree {}; fabmesh reads splines of degree 1, 2 or 3", e.degree));
    const std::size_t n = e.points.size(), p = static_cast<std::size_t>(e.degree);
    if (n < p + 1) fail(e, fmt::format("{} control points for degree {}", n, p));
    if (e.knots.size() != n + p + 1)
      fail(e,
           fmt::format("{} knots; {} control points of degree {} take {}", e.knots.size(), n, p, n + p + 1));
    for (std::size_t i = 1; i < e.knots.size(); ++i) {
      if (e.knots[i] < e.knots[i - 1])
        fail(e, fmt::format("knot {} ({}) is not finite and non-decreasing", i + 1, e.knots[i]));
    }
    std::vector<Vec2> points;
    std::vector<double> weights;
    double z = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double w = e.weights.empty() ? 1.0 : e.weights[i];
      if (!(w > 0.0))
        fail(e,
             fmt::format("control point {} has weight {}: a NURBS weight must be finite and > 0", i + 1, w));
      points.push_back(e.points[i].head<2>());
      weights.push_back(w);
      z = std::max(z, std::abs(e.points[i].z()));
    }
    if (!(e.knots[n] > e.knots[p])) fail(e, "its knots leave no domain to draw");
    DxfPiece piece = this->piece(e);
    piece.spline = true;
    piece.beziers = bezier_spans(e.knots, points, weights, e.degree);
    if (piece.beziers.empty()) fail(e, "its knots leave no domain to draw");
    piece.start = piece.beziers.front().points[0];
    piece.end = piece.beziers.back().points[3];
    height(e, z);
    pieces.push_back(std::move(piece));
  }

  std::string layer_, path_, where_;
};

// The factor from the drawing's units into the design's, noted.
double drawing_scale(const DxfHeader& header, const std::string& path, const std::string& units,
                     std::vector<std::string>& notes) {
  if (!header.insunits || *header.insunits == 0) {
    notes.push_back(fmt::format("{} gives no units ($INSUNITS {}): read in the design's units ({})", path,
                                header.insunits ? "0, unitless" : "missing", units));
    return 1.0;
  }
  const DxfUnit* unit = nullptr;
  for (const DxfUnit& u : kDxfUnits) {
    if (u.code == *header.insunits) unit = &u;
  }
  if (unit == nullptr) {
    throw FileError(path, 0, 0,
                    fmt::format("{}: $INSUNITS {} is not a unit fabmesh reads (1 in, 2 ft, 4 mm, 5 cm, 6 m)",
                                path, *header.insunits));
  }
  const double scale = unit->metres / metres_per_unit(units);
  notes.push_back(scale == 1.0 ? fmt::format("{}: $INSUNITS {} ({})", path, unit->code, unit->name)
                               : fmt::format("{}: $INSUNITS {} ({}), scaled by {:.12g} into {}", path,
                                             unit->code, unit->name, scale, units));
  return scale;
}

// The drawing's size (drawing units): its largest coordinate, at least 1e-300.
double drawing_size(const std::vector<DxfPiece>& pieces, const std::vector<Polyline>& polylines) {
  double size = 0.0;
  auto reach = [&](const Vec2& v) { size = std::max({size, std::abs(v.x()), std::abs(v.y())}); };
  for (const DxfPiece& p : pieces) {
    reach(p.start);
    reach(p.end);
    if (p.arc) size = std::max(size, p.ellipse.center.norm() + std::max(p.ellipse.a, p.ellipse.b));
    for (const BezierSpan& z : p.beziers) {
      for (const Vec2& v : z.points) reach(v);
    }
  }
  for (const Polyline& pl : polylines) {
    for (const auto& v : pl.vertices) reach(Vec2(v[0], v[1]));
  }
  return size > 0.0 ? size : 1.0;
}

// Each polyline's spans as pieces: straight, or the exact arc of its bulge.
// A bulge whose arc is within kFlatness of the drawing's size of its chord
// (CAD's rounding noise) is a straight span; returns how many were.
std::size_t add_polyline_pieces(const std::vector<Polyline>& polylines, double size,
                                std::vector<DxfPiece>& pieces) {
  std::size_t flattened = 0;
  for (const Polyline& pl : polylines) {
    const std::size_t n = pl.vertices.size();
    const std::size_t spans = pl.closed ? n : (n == 0 ? 0 : n - 1);
    for (std::size_t i = 0; i < spans; ++i) {
      const auto& v = pl.vertices[i];
      const auto& w = pl.vertices[(i + 1) % n];
      const double sx = pl.mirrored ? -1.0 : 1.0;
      const Vec2 a(sx * v[0], v[1]), b(sx * w[0], w[1]);
      const double bulge = pl.mirrored ? -v[2] : v[2];
      DxfPiece p;
      p.entity = fmt::format("{} vertex {}", pl.entity, i + 1);
      p.order = pl.order;
      p.start = a;
      p.end = b;
      const double chord = (b - a).norm();
      const double sagitta = 0.5 * std::abs(bulge) * chord;  // the arc's height over its chord
      if (bulge != 0.0 && chord > 0.0 && sagitta <= kDxfFlatness * size) ++flattened;
      if (bulge != 0.0 && chord > 0.0 && sagitta > kDxfFlatness * size) {
        const double theta = 4.0 * std::atan(bulge);
        const Vec2 left(-(b - a).y() / chord, (b - a).x() / chord);
        const Vec2 centre = 0.5 * (a + b) + left * (0.5 * chord / std::tan(0.5 * theta));
        p.arc = true;
        p.ellipse.center = centre;
        p.ellipse.a = p.ellipse.b = 0.5 * chord / std::sin(0.5 * std::abs(theta));
        p.ellipse.from_deg = std::atan2(a.y() - centre.y(), a.x() - centre.x()) * kDegree;
        p.ellipse.to_deg = p.ellipse.from_deg + theta * kDegree;
      }
      pieces.push_back(std::move(p));
    }
  }
  return flattened;
}

// Angles into the ranges an ellipse arc takes ([-720, 720] degrees).
void normalise_angles(EllipseArcParams& e) {
  const double shift = 360.0 * std::floor(std::min(e.from_deg, e.to_deg) / 360.0);
  e.from_deg -= shift;
  e.to_deg -= shift;
  e.rotation_deg = std::fmod(e.rotation_deg, 360.0);
}

// The pieces scaled into the design's units, every number within the
// design's limits; returns their extent (largest coordinate, at least 1).
double into_design_units(std::vector<DxfPiece>& pieces, double scale, const std::string& path,
                         const std::string& where) {
  double extent = 0.0;
  for (DxfPiece& p : pieces) {
    const int line = static_cast<int>(p.order);
    p.start *= scale;
    p.end *= scale;
    if (p.arc) {
      p.ellipse.center *= scale;
      p.ellipse.a *= scale;
      p.ellipse.b *= scale;
      normalise_angles(p.ellipse);
    }
    for (BezierSpan& z : p.beziers) {
      for (Vec2& v : z.points) {
        v *= scale;
        if (!v.allFinite() || std::abs(v.x()) > kMaxDesignNumber || std::abs(v.y()) > kMaxDesignNumber) {
          throw FileError(path, line, 1,
                          fmt::format("{}: {}: a control point {} is beyond the design limit {:g}", where,
                                      p.entity, fmt_point(v), kMaxDesignNumber));
        }
        extent = std::max({extent, std::abs(v.x()), std::abs(v.y())});
      }
    }
    for (const double v : {p.start.x(), p.start.y(), p.end.x(), p.end.y(), p.ellipse.center.x(),
                           p.ellipse.center.y(), p.ellipse.a, p.ellipse.b}) {
      if (!std::isfinite(v) || std::abs(v) > kMaxDesignNumber) {
        throw FileError(path, line, 1,
                        fmt::format("{}: {}: the value {} is beyond the design limit {:g}", where, p.entity,
                                    v, kMaxDesignNumber));
      }
    }
    try {
      if (p.arc) arc_ends(p);
    } catch (const InputError& e) {
      throw FileError(path, line, 1, fmt::format("{}: {}: {}", where, p.entity, e.what()));
    }
    extent = std::max({extent, std::abs(p.start.x()), std::abs(p.start.y()), std::abs(p.end.x()),
                       std::abs(p.end.y()), p.arc ? p.ellipse.a + p.ellipse.center.norm() : 0.0});
  }
  return extent > 0.0 ? extent : 1.0;
}

[[noreturn]] void no_loop_entities(const Collector& c, const std::string& path, const std::string& where) {
  if (c.paper_space > 0) {
    throw FileError(path, 0, 0,
                    fmt::format("{}: the layer's {} entities are all in paper space; the outline must be in "
                                "model space",
                                where, c.paper_space));
  }
  std::string layers;
  for (const std::string& l : c.layers) layers += (layers.empty() ? "" : ", ") + l;
  throw FileError(path, 0, 0,
                  fmt::format("{}: no LINE, ARC, CIRCLE, ELLIPSE, polyline or SPLINE in model space{}", where,
                              layers.empty() ? std::string(" (the drawing has none on any layer)")
                                             : fmt::format(" (layers that have them: {})", layers)));
}

}  // namespace

// Distance from p to the segment a-b.
double segment_distance(const Vec2& a, const Vec2& b, const Vec2& p) {
  const Vec2 d = b - a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (a + t * d - p).norm();
}

// Marks the lines of `pieces` that lie on a line of the walls layer (`w`'s
// pieces, in design units): both ends within `near` of it. Every wall line
// must mark one.
void mark_walls(std::vector<DxfPiece>& pieces, const std::vector<DxfPiece>& walls, double near,
                const std::string& path, const std::string& where) {
  for (const DxfPiece& w : walls) {
    if (w.arc || w.spline) {
      throw FileError(
          path, static_cast<int>(w.order), 1,
          fmt::format("{}: {}: walls are straight: draw them as LINEs or polyline spans without bulge", where,
                      w.entity));
    }
    bool marks = false;
    for (DxfPiece& p : pieces) {
      if (p.arc || p.spline) continue;
      if (segment_distance(w.start, w.end, p.start) <= near &&
          segment_distance(w.start, w.end, p.end) <= near) {
        p.wall = true;
        marks = true;
      }
    }
    if (!marks) {
      throw FileError(path, static_cast<int>(w.order), 1,
                      fmt::format("{}: {} from {} to {} lies on no line of the outline (within {:g}): a wall "
                                  "marks the outline's edges along it",
                                  where, w.entity, fmt_point(w.start), fmt_point(w.end), near));
    }
  }
}

DxfLoops parse_dxf_loops(const std::string& bytes, const std::string& path, const DxfLoopQuery& query) {
  const std::string where = query.layer.empty() ? path : fmt::format("{} layer {}", path, query.layer);
  Collector c(query.layer, path, where);
  const std::string walls_where = fmt::format("{} layer {}", path, query.walls);
  Collector w(query.walls, path, walls_where);
  const DxfHeader header = read_dxf(bytes, path, [&](const DxfEntity& e) {
    c.take(e);
    if (!query.walls.empty()) w.take(e);
  });

  DxfLoops out;
  const double scale = drawing_scale(header, path, query.units, out.notes);
  if (!c.left_out.empty()) {
    std::string kinds;
    for (const auto& [type, count] : c.left_out)
      kinds += fmt::format("{}{} {}", kinds.empty() ? "" : ", ", count, type);
    out.notes.push_back(fmt::format("{}: left out {} (no outline in them)", where, kinds));
  }
  // Flat drawings only: every entity at z = 0, within kDxfFlatness of the drawing's size.
  std::vector<DxfPiece>& pieces = c.pieces;
  const double size = drawing_size(pieces, c.polylines);
  for (const Height& h : c.heights) {
    if (h.z > kDxfFlatness * size) {
      throw FileError(
          path, static_cast<int>(h.line), 1,
          fmt::format("{}: {}: at z = {:.10g}, off the drawing's XY plane (z = 0)", where, h.entity, h.z));
    }
  }
  const std::size_t flattened = add_polyline_pieces(c.polylines, size, pieces);
  if (flattened > 0) {
    out.notes.push_back(
        fmt::format("{}: {} polyline span(s) with a bulge of at most {:g} of the drawing's size read "
                    "as straight",
                    where, flattened, kDxfFlatness));
  }
  if (pieces.empty()) no_loop_entities(c, path, where);
  if (!query.walls.empty()) {
    add_polyline_pieces(w.polylines, size, w.pieces);
    if (w.pieces.empty() && query.walls_required) no_loop_entities(w, path, walls_where);
    into_design_units(w.pieces, scale, path, walls_where);
  }

  const double extent = into_design_units(pieces, scale, path, where);
  mark_walls(pieces, w.pieces, std::max(query.max_gap, kDxfFlatness * extent), path, walls_where);
  DxfChains chains;
  try {
    chains = chain_pieces(pieces, query.max_gap, extent, where);
  } catch (const InputError& e) {
    throw FileError(path, 0, 0, e.what());
  }
  if (chains.skipped > 0)
    out.notes.push_back(fmt::format("{}: left out {} line(s) no longer than max_gap", where, chains.skipped));
  for (std::size_t i = 0; i < chains.loops.size(); ++i)
    out.loops.push_back({std::move(chains.loops[i]), chains.first_entities[i]});
  if (chains.bridges > 0) {
    out.notes.push_back(fmt::format("{}: {} gap(s) between arcs, up to max_gap, joined by short lines", where,
                                    chains.bridges));
  }
  return out;
}

DxfLoops read_dxf_loops(const std::string& path, const DxfLoopQuery& query) {
  return parse_dxf_loops(read_file(path, kMaxDxfBytes, "DXF drawing"), path, query);
}

}  // namespace fabmesh
