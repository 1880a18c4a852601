#pragma once
// DXF texts with rational SPLINEs (NURBS) as CAD programs save circles, arcs
// and conics, for the tests that read, mesh, cut and export them.

#include <fmt/format.h>

#include <cmath>
#include <string>
#include <vector>

#include "geometry/core/types.h"

namespace fabmesh::test {

/// A DXF drawing in millimetres ($INSUNITS 4) of the given entities.
inline std::string dxf_drawing(const std::string& entities) {
  return "0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n" + entities +
         "0\nENDSEC\n0\nEOF\n";
}

/// A LINE from a to b on `layer`.
inline std::string dxf_line(const char* handle, const char* layer, const Vec2& a, const Vec2& b) {
  return fmt::format(
      "0\nLINE\n5\n{}\n8\n{}\n10\n{:.17g}\n20\n{:.17g}\n30\n0\n11\n{:.17g}\n21\n{:.17g}\n31\n0\n", handle,
      layer, a.x(), a.y(), b.x(), b.y());
}

/// A rational quadratic SPLINE through 2n + 1 control points with their
/// weights: n spans, the knots doubled between them (0 0 0 1 1 ... n n n).
inline std::string dxf_nurbs(const char* handle, const char* layer, const std::vector<Vec2>& points,
                             const std::vector<double>& weights) {
  const std::size_t spans = (points.size() - 1) / 2;
  std::vector<double> knots{0, 0, 0};
  for (std::size_t i = 1; i < spans; ++i) knots.insert(knots.end(), 2, static_cast<double>(i));
  knots.insert(knots.end(), 3, static_cast<double>(spans));
  std::string text = fmt::format("0\nSPLINE\n5\n{}\n8\n{}\n70\n8\n71\n2\n72\n{}\n73\n{}\n74\n0\n", handle,
                                 layer, knots.size(), points.size());
  for (const double k : knots) text += fmt::format("40\n{}\n", k);
  for (std::size_t i = 0; i < points.size(); ++i) {
    text += fmt::format("10\n{:.17g}\n20\n{:.17g}\n30\n0\n41\n{:.17g}\n", points[i].x(), points[i].y(),
                        weights[i]);
  }
  return text;
}

/// An ellipse with semi-axes a (along x) and b about c as a NURBS: the 9
/// control points on the rectangle round it, corner weights sqrt(2)/2
/// (`corner_weight` in their place when given). a = b is a circle.
inline std::string dxf_nurbs_ellipse(const char* handle, const char* layer, const Vec2& c, double a, double b,
                                     double corner_weight = std::sqrt(0.5)) {
  std::vector<Vec2> points;
  std::vector<double> weights;
  for (int i = 0; i <= 8; ++i) {
    const double angle = (i % 8) * M_PI / 4, reach = i % 2 == 0 ? 1.0 : std::sqrt(2.0);
    points.emplace_back(c.x() + a * reach * std::cos(angle), c.y() + b * reach * std::sin(angle));
    weights.push_back(i % 2 == 0 ? 1.0 : corner_weight);
  }
  return dxf_nurbs(handle, layer, points, weights);
}

}  // namespace fabmesh::test
