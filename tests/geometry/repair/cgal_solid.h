#pragma once
// CGAL Polygon Mesh Processing's own judgement of a repaired mesh, the
// independent check of the repair tests: a polygon mesh, closed, free of
// self-intersections, bounding a volume. CGAL stays in cgal_solid.cpp.

#include "geometry/core/soup.h"

namespace fabmesh::testing {

/// What PMP says of a soup (equal positions already one vertex).
struct CgalSolid {
  bool polygon_mesh = false;      ///< PMP::is_polygon_soup_a_polygon_mesh
  bool closed = false;            ///< CGAL::is_closed
  bool self_intersecting = true;  ///< PMP::does_self_intersect
  bool bounds_a_volume = false;   ///< PMP::does_bound_a_volume
  double volume = 0.0;            ///< PMP::volume

  bool solid() const { return polygon_mesh && closed && !self_intersecting && bounds_a_volume; }
};

CgalSolid cgal_solid(const TriangleSoup& soup);

}  // namespace fabmesh::testing
