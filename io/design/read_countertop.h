#pragma once
// Reads the body of a `kind: countertop` design (product.md "Countertop").

#include <yaml-cpp/yaml.h>

#include "io/design/design.h"
#include "io/design/yaml_fields.h"

namespace fabmesh {

/// Reads outline (a closed curve), holes (ellipse, rounded_rect or a closed
/// outline each), thickness (> 0), max_edge (> 0, optional) and
/// max_triangles (optional) from the design's root map. Ellipse and
/// rounded_rect holes become closed curves of exact segments (one 0..360
/// ellipse arc; 4 lines and 4 quarter circles, declared G1).
/// \throw FileError naming file, line, column and field
CountertopDesign read_countertop(const yaml::Fields& fields, const YAML::Node& root);

/// A rounded rectangle as a closed curve spec: centre, width w, height h
/// (> 0), corner radius r in [0, min(w, h) / 2], rotated by rotation_deg
/// about its centre; counter-clockwise from the middle of its lower edge's start.
/// \throw RangeError for sizes out of range
CurveSpec rounded_rect_curve(const Vec2& center, double w, double h, double r, double rotation_deg);

/// A whole ellipse (one exact arc 0..360 degrees) as a closed curve spec. \throw RangeError
CurveSpec ellipse_curve(const Vec2& center, double a, double b, double rotation_deg);

}  // namespace fabmesh
