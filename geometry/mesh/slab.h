#pragma once
// Slabs: a triangulated planar region extruded into a closed solid of
// constant thickness (a countertop with its cut-outs).

#include <cstddef>
#include <optional>

#include "geometry/core/limits.h"
#include "geometry/core/proofs.h"
#include "geometry/mesh/halfedge_mesh.h"
#include "geometry/section/region.h"
#include "geometry/section/triangulate.h"

namespace fabmesh {

struct SlabOptions {
  double thickness = 30.0;  ///< z extent, model units (> 0); bottom at z = 0, top at z = thickness
  double max_edge = 0.0;    ///< longest top/bottom edge, model units; 0: no refinement
  std::size_t max_triangles = kDefaultMaxTriangles;  ///< budget for the whole slab; more is a BudgetError
};

/// An extruded slab (returned by value: the mesh is built in place).
struct SlabMesh {
  Mesh mesh;
  PlanarTriangulation triangulation;  ///< the top face's triangulation (bottom: mirrored)
  /// Why the mesh is free of self-intersections without a 3D test (always
  /// given: a simple region extrudes into an embedded slab).
  std::optional<EmbeddingProof> proof;
  /// The connectivity extrude proves: closed, manifold, oriented, one
  /// component of Euler characteristic 2 - 2 x holes.
  std::optional<TopologyProof> topology;
};

/// Triangle count of the slab over `t`: top and bottom, plus two per boundary edge.
std::size_t slab_triangle_count(const PlanarTriangulation& t);

/// Extrudes a triangulation: top (z = thickness) and bottom (z = 0) copies
/// and one vertical wall quad (two triangles) per boundary edge, sharing
/// vertices; watertight, outward oriented, genus = number of holes.
/// \throw RangeError for thickness <= 0.
Mesh extrude(const PlanarTriangulation& triangulation, double thickness);

/// Triangulates `region` (refined to options.max_edge when > 0) and extrudes it:
/// extrude_slab(region, slab_top(region, options), options).
/// \throw RangeError (thickness, max_edge), BudgetError (over max_triangles)
SlabMesh build_slab(const Region2& region, const SlabOptions& options);

/// The top face of a slab over `region`: its triangulation, refined to
/// options.max_edge when > 0, whose slab keeps within options.max_triangles.
/// The thickness is not read: slabs of every thickness over `region` share it.
/// \throw RangeError (max_edge), BudgetError (over max_triangles)
PlanarTriangulation slab_top(const Region2& region, const SlabOptions& options);

/// The slab of options.thickness over `top`, which is slab_top(region,
/// options) (for any thickness), with the proofs of its construction.
/// \throw RangeError (thickness)
SlabMesh extrude_slab(const Region2& region, PlanarTriangulation top, const SlabOptions& options);

}  // namespace fabmesh
