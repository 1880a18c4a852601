#pragma once
// Test meshes made of slivers, as fabmesh's own builders make them.

#include "geometry/core/soup.h"
#include "geometry/mesh/halfedge_mesh.h"
#include "geometry/mesh/slab.h"
#include "geometry/section/region.h"
#include "tests/geometry/section/region_shapes.h"

namespace fabmesh::test {

/// A countertop slab (what the countertop builder makes): a constrained
/// Delaunay triangulation of a rounded rectangle with a sink, long slivers
/// and many coplanar neighbours.
inline TriangleSoup countertop_slab() {
  RegionOptions ro;
  ro.tolerance = 0.5;
  const Region2 region =
      build_region(rounded_rect(0, 0, 1200, 600, 60), {{ellipse({350, 300}, 200, 150, 10), "sink"}}, ro);
  return to_soup(build_slab(region, SlabOptions{}).mesh);
}

}  // namespace fabmesh::test
