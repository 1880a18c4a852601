#pragma once
// One part of a slip-casting mould as a closed triangle mesh: a side part is
// the mould section swept over its angular range (a partial, or for a box a
// generalised, revolution) and capped on both split planes by CGAL
// triangulations of that section, with the keys' hemispheres stitched into
// the caps; the base part is its section swept all the way round. With keys
// on the base cut, the side parts' bottoms and the base's top are flat
// triangulations with the keys' circles as holes, their hemispheres
// stitched in the same way.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/core/proofs.h"
#include "geometry/core/soup.h"
#include "geometry/mould/keys.h"
#include "geometry/mould/mould_section.h"
#include "geometry/mould/release.h"

namespace fabmesh {

/// A key's hemisphere as built into a part.
struct KeyFeature {
  std::size_t key = 0;  ///< index into KeyLayout::centres
  bool bump = true;     ///< a bump (dome, material) or a socket (pit, empty)
  Vec3 centre{0.0, 0.0, 0.0};
  Vec3 axis{0.0, 0.0, 0.0};  ///< unit normal of the split plane, from the plane toward the apex
  double radius = 0.0;
  std::vector<std::uint32_t> vertices;  ///< soup indices of the hemisphere's vertices (base ring first)
  bool on_base = false;                 ///< on the base cut: `key` indexes KeyLayout::base_centres
};

/// A split plane: the half-plane through the z axis at `angle` (radians).
struct SplitPlane {
  double angle = 0.0;
  Vec2 direction{1.0, 0.0};  ///< (cos angle, sin angle), exact at multiples of 90 degrees
};

/// The split plane k of `parts` equal side parts: angle 2 pi k / parts.
SplitPlane split_plane(int k, int parts);

/// Angular samples of a sweep and the block's outline point at each.
struct AngularSamples {
  std::vector<double> angles;
  std::vector<Vec2> directions;
  std::vector<Vec2> outline;  ///< block outline point (x, y): on the circle, or on the box's side
};

/// Samples [from, to] (closed: [from, from + 2 pi), the last joining the
/// first) with steps of at most `max_step`; for a box every corner angle
/// (45 + 90 k degrees) in the range is a sample, so that between two samples
/// the block's outline is one straight side of the box.
AngularSamples angular_samples(const SplitPlane& from, const SplitPlane& to, bool closed, BlockShape block,
                               double block_radius, double max_step);

struct MouldPart {
  std::string name;  ///< "side 1 of 2", ..., "base"
  MouldPartKind kind = MouldPartKind::Side;
  double from_angle = 0.0, to_angle = 0.0;  ///< radians (base: 0 and 2 pi)
  std::size_t angular_steps = 0;
  TriangleSoup soup;  ///< closed, outward, sharing vertices
  /// Sockets on the `from` plane, bumps on the `to` plane; with base keys,
  /// a side part's socket in its bottom and the base part's bumps on its top.
  std::vector<KeyFeature> keys;
  EmbeddingProof proof;  ///< why the mesh is embedded: validation replaces the 3D test with it
};

/// A side part between two split planes, with sockets on `from` and bumps on `to`.
/// `max_step`: largest angular step; `sagitta`: its radial sagitta bound (for the proof).
/// \throw BudgetError when the part would exceed `max_triangles`.
MouldPart build_side_part(const MouldSection& section, const KeyLayout& keys, const MouldOptions& options,
                          const SplitPlane& from, const SplitPlane& to, double max_step,
                          std::size_t max_triangles);

/// The base part: the base section swept all the way round; with base keys
/// its top (the plaster of the cut) is a flat triangulated annulus with the
/// keys' bumps on it.
MouldPart build_base_part(const MouldSection& section, const KeyLayout& keys, const MouldOptions& options,
                          double max_step, std::size_t max_triangles);

}  // namespace fabmesh
