#pragma once
// A polynomial B-spline surface as plain data: what a STEP file's
// B_SPLINE_SURFACE_WITH_KNOTS holds (the faces of io/step/step_model.h).

#include <cstddef>
#include <string>
#include <vector>

#include "geometry/core/types.h"

namespace fabmesh {

/// poles[k * v_poles + l], k along u, l along v; distinct knots with their
/// multiplicities, clamped (end multiplicities degree + 1).
struct BSplineFace {
  std::string name;  ///< for messages: "front_left", "front_left offset", "front_left u_min wall"
  int u_degree = 3, v_degree = 3;
  std::vector<double> u_knots, v_knots;
  std::vector<int> u_multiplicities, v_multiplicities;
  std::size_t u_poles = 0, v_poles = 0;
  std::vector<Vec3> poles;
};

/// The knot vector in full: each distinct knot repeated by its multiplicity.
std::vector<double> full_knots(const std::vector<double>& knots, const std::vector<int>& multiplicities);

/// The point at (u, v) (de Boor's algorithm in each direction).
Vec3 face_point(const BSplineFace& face, double u, double v);

}  // namespace fabmesh
