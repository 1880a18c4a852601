#pragma once
// A thickened surface (a shell) as B-spline faces that close into one solid,
// for STEP files (docs/math/h-bezier.md "Shells as B-spline faces"): a sheet
// on the surface itself as the patches' bicubic B-spline surfaces
// (bspline_patch.h); an offset sheet, which is not rational, as the bilinear
// B-spline surface through its proven tessellation's grid; each outer side's
// wall as the ruled surface between the two sheets' border curves.

#include <cstddef>
#include <string>
#include <vector>

#include "geometry/core/types.h"
#include "geometry/surfaces/bspline_face.h"
#include "geometry/surfaces/patch_network.h"

namespace fabmesh {

struct SurfaceTessellation;

/// A shell's sheets as its tessellation placed them: the grid of each patch
/// and the sheet's vertices with their unit normals; the shell spans
/// points + from normals to points + to normals.
struct ShellGrid {
  double from = 0.0, to = 0.0;
  double bound = 0.0;  ///< the tessellation's proven bound (SurfaceTessellation::max_deviation)
  std::vector<std::vector<double>> s_breaks, t_breaks;  ///< per patch
  std::vector<std::vector<int>> vertices;               ///< per patch, as SurfaceTessellation::grid_vertices
  std::vector<Vec3> points, normals;                    ///< per sheet vertex
};

/// The grid of `sheet` for the shell between offsets from < to.
ShellGrid shell_grid(const SurfaceTessellation& sheet, double from, double to);

struct BSplinePatch;

/// A patch's bicubic B-spline surface (bspline_patch.h) as a face.
BSplineFace bspline_face(const BSplinePatch& patch, const std::string& name);

struct BSplineShell {
  /// The sheet at `from` (one face per patch), the sheet at `to`, then one
  /// wall per outer side of a patch (outer_sides), u along the side and v
  /// (degree 1) from the `from` sheet's border to the `to` sheet's.
  std::vector<BSplineFace> faces;
  /// >= the distance of every face from its exact surface at the same
  /// parameters: the grid's bound for an offset sheet and, at `tolerance`,
  /// bspline_network's for a sheet on the surface; a wall, a convex
  /// combination of its two borders, is within the larger of the two.
  double bound = 0.0;
};

/// The shell of `grid` (from < to; one of them may be 0) as B-spline faces
/// whose shared borders are one curve each (up to rounding).
/// \throw RangeError (from >= to, a grid that does not match the network),
///        GeometryError (bspline_network)
BSplineShell bspline_shell(const PatchNetwork& network, const ShellGrid& grid, double tolerance);

}  // namespace fabmesh
