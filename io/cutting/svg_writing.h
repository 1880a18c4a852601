#pragma once
// What the SVG writers of io/cutting share (svg.cpp, toolpath_svg.cpp): how
// numbers, points, arcs, cut loops and the document's start are written.

#include <string>

#include "geometry/core/types.h"
#include "geometry/curves/segment.h"
#include "geometry/sampling/cut_loop.h"

namespace fabmesh {

/// Shortest round-trip decimal of `v` (-0 written as 0).
std::string svg_number(double v);

/// A model point as SVG coordinates "x y", y negated: the model's y axis
/// points up, SVG's down.
std::string svg_point(const Vec2& p);

/// Appends the exact arc `a` to path data `d` as A commands of at most 120
/// degrees each (a whole ellipse needs at least two; pieces below 180
/// degrees make the flags unambiguous), from the arc's start point.
void append_svg_arc(std::string& d, const EllipseArcParams& a);

/// Appends the chain of `loop` to path data `d`: M at its first point (" M"
/// when `d` is not empty), then L for lines and polylines, A for arcs, C for
/// a Spline whose weights are equal (a polynomial cubic, exactly) and L for
/// the points of a rational one sampled within `loop.tolerance`; no Z.
void append_svg_loop(std::string& d, const CutLoop& loop);

/// The XML declaration and the <svg> start tag of a drawing of the model box
/// `lo`..`hi` with `margin` (model units) all round: the viewBox in model
/// units, width and height in `units` (m written as mm x 1000).
std::string svg_start(const Vec2& lo, const Vec2& hi, double margin, const std::string& units);

}  // namespace fabmesh
