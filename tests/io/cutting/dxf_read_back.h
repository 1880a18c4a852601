#pragma once
// The DXF files fabmesh writes, read back by fabmesh's one DXF reader
// (io/dxf/dxf_reader.h) into the entities a cutting outline is made of, with
// their end points, so outlines can be checked after a round trip.

#include <cmath>
#include <string>
#include <vector>

#include "geometry/core/types.h"
#include "io/dxf/dxf_reader.h"

namespace fabmesh {

/// One drawing entity read back from a DXF file, in model units.
struct DrawnEntity {
  std::string type;  ///< LINE, ARC, CIRCLE, ELLIPSE, SPLINE or POLYLINE (an LWPOLYLINE or a POLYLINE)
  std::string layer;
  /// LINE/ARC/ELLIPSE: start and end point (counter-clockwise for arcs);
  /// CIRCLE: one point on it, twice; polylines: their vertices; SPLINE: its
  /// control points (a clamped spline, as fabmesh writes, starts at the first
  /// and ends at the last).
  std::vector<Vec2> points;
  bool closed = false;  ///< a polyline or SPLINE with the closed flag, a CIRCLE, or an ELLIPSE of 2 pi
  /// SPLINE only: its degree, flags (group 70), knots and the control points'
  /// weights (1 where the file gives none).
  int degree = 0;
  int flags = 0;
  std::vector<double> knots;
  std::vector<double> weights;
};

/// `entity` as a cutting outline's entity; its type empty for any other kind.
inline DrawnEntity drawn(const DxfEntity& e) {
  DrawnEntity d;
  d.layer = e.layer;
  const Vec2 c = e.points.empty() ? Vec2(0.0, 0.0) : Vec2(e.points[0].head<2>());
  if (e.type == "LINE") {
    d.type = e.type;
    d.points = {e.points[0].head<2>(), e.points[1].head<2>()};
  } else if (e.type == "ARC") {
    auto at = [&](double deg) {
      const double t = deg * M_PI / 180.0;
      return Vec2(c.x() + e.radius * std::cos(t), c.y() + e.radius * std::sin(t));
    };
    d.type = e.type;
    d.points = {at(e.start), at(e.end)};
  } else if (e.type == "CIRCLE") {
    d.type = e.type;
    d.points = {Vec2(c.x() + e.radius, c.y()), Vec2(c.x() + e.radius, c.y())};
    d.closed = true;
  } else if (e.type == "ELLIPSE") {
    // Minor axis: the major axis turned a quarter counter-clockwise, scaled by the ratio.
    const Vec2 m = e.points[1].head<2>();
    auto at = [&](double t) {
      const double cs = std::cos(t), sn = e.radius * std::sin(t);
      return Vec2(c.x() + cs * m.x() - sn * m.y(), c.y() + cs * m.y() + sn * m.x());
    };
    d.type = e.type;
    d.points = {at(e.start), at(e.end)};
    d.closed = std::abs(e.end - e.start - 2.0 * M_PI) < 1e-12;
  } else if (e.type == "LWPOLYLINE" || e.type == "POLYLINE" || e.type == "SPLINE") {
    d.type = e.type == "SPLINE" ? "SPLINE" : "POLYLINE";
    for (const Vec3& p : e.points) d.points.push_back(p.head<2>());
    d.closed = (e.flags & 1) != 0;
    if (e.type == "SPLINE") {
      d.degree = e.degree;
      d.flags = e.flags;
      d.knots = e.knots;
      d.weights = e.weights.empty() ? std::vector<double>(e.points.size(), 1.0) : e.weights;
    }
  }
  return d;
}

/// The LINE, ARC, CIRCLE, ELLIPSE, SPLINE and polyline entities of a DXF
/// text, in file order; other entities are left out. \throw FileError as read_dxf
inline std::vector<DrawnEntity> parse_dxf(const std::string& bytes, const std::string& what) {
  std::vector<DrawnEntity> out;
  read_dxf(bytes, what, [&](const DxfEntity& e) {
    DrawnEntity d = drawn(e);
    if (!d.type.empty()) out.push_back(std::move(d));
  });
  return out;
}

}  // namespace fabmesh
