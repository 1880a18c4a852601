#pragma once
// Thickening an open surface mesh into a closed solid shell for fabrication.

#include <array>
#include <cstddef>
#include <vector>

#include "geometry/core/limits.h"
#include "geometry/core/types.h"
#include "geometry/mesh/halfedge_mesh.h"

namespace fabmesh {

/// Which side of an open surface a shell goes to (design key `thicken`).
/// Normal: along S_s x S_t (the patches' orientation); Outward / Inward: away
/// from / into the volume the surface encloses with a flat cap over its rim
/// (for a basin or a tray: below and outside / inside the bowl); Centered:
/// half the thickness to each side.
enum class ThickenSide { Normal, Outward, Inward, Centered };

/// "normal", "outward", "inward", "centered".
const char* to_string(ThickenSide side);

struct ThickenOptions {
  /// Distance between the two sheets along the vertex normals, model units (> 0).
  double thickness = 1.0;
  /// The shell spans p + offset n to p + (offset + thickness) n: 0 puts the
  /// sheet itself on one side, -thickness on the other, -thickness/2 centres it.
  double offset = 0.0;
  std::size_t max_triangles = kDefaultMaxTriangles;  ///< budget for the shell; more is a BudgetError
};

/// Triangles of the shell over `sheet`: both sheets and two per boundary edge.
std::size_t thickened_triangle_count(const Mesh& sheet);

/// The shell between the sheets p + offset n(p) and p + (offset + thickness)
/// n(p): the upper sheet keeps the sheet's orientation, the lower one is reversed, and
/// each boundary edge gets a side-wall quad (two triangles) sharing the
/// vertices of both sheets. With `vertex_normals` the unit normals the
/// sheet's faces turn counter-clockwise about (one per sheet vertex), the
/// solid is closed and oriented outward. Whether the offset sheet folds or
/// meets the rest (thickness beyond a radius of curvature) is not decided
/// here: validate the result with the self-intersection test.
/// \throw RangeError (thickness <= 0 or not finite, a normal count that does
///        not match), BudgetError (over max_triangles), GeometryError (a sheet
///        that is not manifold at its border)
Mesh thicken(const Mesh& sheet, const std::vector<Vec3>& vertex_normals, const ThickenOptions& options);

/// Signed volume enclosed by `sheet` (faces counter-clockwise about its
/// normals) closed by a fan from the centroid of its boundary vertices over
/// its boundary edges: positive when the normals point out of that volume.
double enclosed_volume(const Mesh& sheet);

/// The shell's span [from, to] along the normals (to - from = thickness) for
/// `side`; `volume` is enclosed_volume of the sheet and `size` its extent
/// (diagonal). \throw GeometryError for outward or inward when the sheet
/// encloses no volume to tell the sides by (|volume| <= 1e-6 size^3).
std::array<double, 2> shell_span(ThickenSide side, double thickness, double volume, double size);

}  // namespace fabmesh
