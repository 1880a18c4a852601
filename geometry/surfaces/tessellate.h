#pragma once
// Tessellation of a patch network into one conforming triangle mesh.

#include <cstddef>
#include <functional>
#include <vector>

#include "geometry/core/limits.h"
#include "geometry/core/types.h"
#include "geometry/mesh/halfedge_mesh.h"
#include "geometry/surfaces/cell_bound.h"
#include "geometry/surfaces/patch_network.h"

namespace fabmesh {

struct TessellateOptions {
  /// Largest distance between the mesh and the exact surface, model units (> 0).
  double tolerance = 0.01;
  /// A shell (thicken) between the sheets S + shell_from n and S + shell_to n
  /// when shell_to > shell_from, model units: both sheets (those not at 0)
  /// and the side walls between them along the outer border are kept within
  /// `tolerance` of their exact surfaces as well.
  double shell_from = 0.0;
  double shell_to = 0.0;
  int initial_segments = 4;  ///< segments per patch direction before refinement (>= 1)
  std::size_t max_triangles = kDefaultMaxTriangles;  ///< budget; more is a BudgetError
};

/// A network tessellated: one mesh, vertices shared by index across borders.
struct SurfaceTessellation {
  Mesh mesh;
  /// Unit normal of the exact surface at each mesh vertex (mean of the
  /// patches meeting there), indexed like the mesh's vertices.
  std::vector<Vec3> normals;
  /// The achieved bound, proven, on the distance between the mesh and the
  /// exact surface (both ways: it bounds |S(s, t) - L(s, t)| for the
  /// piecewise-linear interpolant L), model units. Per cell
  /// (M_ss ds^2 + 2 M_st ds dt + M_tt dt^2) / 8 with M_xy sup bounds of the
  /// second partials over the whole cell (cell_bound.h); for a shell the same
  /// with the offset sheets' second partials, and for the side walls the
  /// sheets' bound plus (shell_to - shell_from) |n1 - n0| / 4 per border edge
  /// (the twist of each side quad), plus the thickness times the largest
  /// measured normal angle along shared borders (averaged vertex normals).
  double max_deviation = 0.0;
  /// Grid breakpoints in s and t of each patch (shared borders share them).
  std::vector<std::vector<double>> s_breaks, t_breaks;
  /// The mesh vertex at each grid point of each patch: grid_vertices[p][a *
  /// (t_breaks[p].size()) + b] is at (s_breaks[p][a], t_breaks[p][b]).
  std::vector<std::vector<int>> grid_vertices;
};

/// Tessellates `network` adaptively: the grid lines of each parameter
/// direction are refined (in classes of directions tied together by shared
/// borders, so both sides of a border use the same samples and the same
/// vertices) until every cell is within `tolerance`. Each grid cell becomes two
/// triangles counter-clockwise about S_s x S_t; collapsed sides become one
/// vertex. The only boundary edges are on the network's outer border.
/// Before refining, min_triangle_count is checked against the budget.
/// Refinement keeps only the grid breakpoints and per-pass data (memory
/// linear in the breakpoints, not in the cells visited).
/// \throw RangeError (tolerance), BudgetError (max_triangles, estimated
///        before refining or reached while refining), GeometryError (a
///        network whose patches cannot form a manifold mesh; a shell where the
///        surface normal vanishes, so its offset cannot be bounded)
SurfaceTessellation tessellate(const PatchNetwork& network, const TessellateOptions& options);

/// A lower bound on the triangles tessellate makes for `tolerance`, from the
/// patches' second derivatives alone: a cell of width ds accepted at
/// `tolerance` has M_ss ds^2 / 8 <= tolerance, so each patch needs at least
/// max_t integral sqrt(|S_ss(s, t)| / (8 tolerance)) ds columns (a lower sum
/// on a grid with the bound of |S_sss|), likewise rows, and directions tied by
/// shared borders share their breakpoints.
double min_triangle_count(const PatchNetwork& network, double tolerance);

/// The cell bounds of tessellate over a finished grid: for each cell of each
/// patch, `visit(patch, s0, s1, t0, t1, bounds)`.
void for_each_cell_bound(
    const PatchNetwork& network, const std::vector<std::vector<double>>& s_breaks,
    const std::vector<std::vector<double>>& t_breaks,
    const std::function<void(std::size_t, double, double, double, double, const CellDerivatives&)>& visit);

}  // namespace fabmesh
