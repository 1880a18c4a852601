#include "io/cutting/read_dxf.h"

#include <dxflib/dl_creationadapter.h>
#include <dxflib/dl_dxf.h>
#include <fmt/format.h>

#include <cmath>
#include <sstream>

#include "geometry/core/errors.h"

namespace fabmesh {
namespace {

class Collector : public DL_CreationAdapter {
 public:
  std::vector<DxfEntity> entities;

  void addLine(const DL_LineData& d) override { add("LINE", {Vec2(d.x1, d.y1), Vec2(d.x2, d.y2)}); }
  void addArc(const DL_ArcData& d) override {
    auto at = [&](double deg) {
      const double t = deg * M_PI / 180.0;
      return Vec2(d.cx + d.radius * std::cos(t), d.cy + d.radius * std::sin(t));
    };
    add("ARC", {at(d.angle1), at(d.angle2)});
  }
  void addCircle(const DL_CircleData& d) override {
    add("CIRCLE", {Vec2(d.cx + d.radius, d.cy), Vec2(d.cx + d.radius, d.cy)}, true);
  }
  void addEllipse(const DL_EllipseData& d) override {
    // Minor axis: the major axis turned a quarter counter-clockwise, scaled by the ratio.
    auto at = [&](double t) {
      const double c = std::cos(t), s = d.ratio * std::sin(t);
      return Vec2(d.cx + c * d.mx - s * d.my, d.cy + c * d.my + s * d.mx);
    };
    add("ELLIPSE", {at(d.angle1), at(d.angle2)}, std::abs(d.angle2 - d.angle1 - 2.0 * M_PI) < 1e-12);
  }
  void addPolyline(const DL_PolylineData& d) override {
    add("POLYLINE", {}, (d.flags & 1) != 0);  // LWPOLYLINE or POLYLINE
  }
  void addVertex(const DL_VertexData& d) override {
    if (!entities.empty()) entities.back().points.emplace_back(d.x, d.y);
  }
  void addSpline(const DL_SplineData& d) override {
    add("SPLINE", {}, (d.flags & 1) != 0);
    entities.back().degree = static_cast<int>(d.degree);
    entities.back().flags = d.flags;
  }
  void addKnot(const DL_KnotData& d) override {
    if (!entities.empty()) entities.back().knots.push_back(d.k);
  }
  void addControlPoint(const DL_ControlPointData& d) override {
    if (entities.empty()) return;
    entities.back().points.emplace_back(d.x, d.y);
    entities.back().weights.push_back(d.w);
  }

 private:
  void add(const char* type, std::vector<Vec2> points, bool closed = false) {
    DxfEntity e;
    e.type = type;
    e.layer = getAttributes().getLayer();
    e.points = std::move(points);
    e.closed = closed;
    entities.push_back(std::move(e));
  }
};

}  // namespace

std::vector<DxfEntity> parse_dxf(const std::string& bytes, const std::string& what) {
  Collector c;
  DL_Dxf dxf;
  std::istringstream in(bytes);
  if (!dxf.in(in, &c)) throw FileError(what, 0, 0, fmt::format("{}: dxflib cannot parse the DXF", what));
  return c.entities;
}

}  // namespace fabmesh
