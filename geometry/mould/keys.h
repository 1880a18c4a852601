#pragma once
// Registration keys on the split planes of a mould: hemispherical bumps on
// one face of each split, matching hemispherical sockets (larger by a
// clearance) on the other; with a base part, one per side part on the base
// cut too (docs/math/moulds.md 2).

#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/core/soup.h"
#include "geometry/mould/mould_options.h"
#include "geometry/mould/mould_section.h"

namespace fabmesh {

/// Where the keys go in every split plane and how much room they have.
struct KeyLayout {
  std::vector<Vec2> centres;   ///< (r, z), master size, the same in every split plane
  double radius = 0.0;         ///< bump radius
  double socket_radius = 0.0;  ///< radius + clearance
  /// Vertices of each base circle polygon: its sagitta at the socket radius
  /// is at most tolerance / 2, so every hemisphere face is within the tolerance.
  int segments = 0;
  /// Per key: least distance from its socket to the exact section's boundary.
  std::vector<double> clearances;
  /// With a base part: keys on the base cut, (x, y) on the plane z = z_cut,
  /// one per side part on its bisector, midway across the plaster between
  /// the cavity and the block. Bumps rise from the base into sockets in the
  /// side parts' bottoms (axes vertical: the base is pulled down first).
  std::vector<Vec2> base_centres;
  std::vector<double> base_clearances;  ///< per base key, as `clearances`
};

/// Places the keys (options.key_positions, or options.keys spread evenly in
/// height along the middle of the wall between the cavity and the block)
/// and checks them: every socket circle inside the side section, at least
/// key_margin (default key_radius / 2) + `sagitta` from the exact cavity
/// (the sampled cavity minus its deviation bound) and from the block's
/// edges, and the sockets that far from each other. `sagitta` is how far the
/// lateral mesh moves inside the section between angular samples.
/// With a base part and keys, one key per side part on the base cut too
/// (KeyLayout::base_centres), with the same margins from the cavity on both
/// sides of the cut, from the block and from the split planes.
/// \throw GeometryError with where = "keys[i]" naming the key, its centre,
///        its clearance and what it comes too close to; for a base key
///        where = "key_radius", naming the base key and the room it has.
KeyLayout place_keys(const MouldSection& section, const MouldOptions& options, double sagitta);

/// A hemisphere over a circle in a split plane: base circle points
/// centre + radius (cos a_k u + sin a_k w), a_k = 2 pi k / n, apex centre + radius axis.
struct Hemisphere {
  Vec3 centre{0.0, 0.0, 0.0};
  Vec3 u{1.0, 0.0, 0.0}, w{0.0, 0.0, 1.0}, axis{0.0, 1.0, 0.0};  ///< orthonormal
  double radius = 1.0;
};

/// Latitude rings (base ring included) of a hemisphere meshed with `segments`
/// points per ring: the latitude step is at most the longitude step.
int hemisphere_rings(int segments);

/// Appends a latitude-longitude hemisphere to `soup` over an existing base
/// ring (`base_ring[k]` = base circle point k, in the soup already): the
/// other rings and the apex become new vertices. Triangles use base edge
/// k -> k+1 (flip: k+1 -> k), so that the surface continues a cap that uses
/// the other direction. Every vertex lies on the sphere and the faces (planar
/// latitude-longitude quads split in two) bound a convex polyhedron inside
/// it, within 2 radius (1 - cos(pi / n)) of it for n base points.
void append_hemisphere(TriangleSoup& soup, const std::vector<std::uint32_t>& base_ring,
                       const Hemisphere& hemisphere, bool flip);

}  // namespace fabmesh
