// The proven two-sided distance between two mesh files (the bound of
// geometry/repair/surface_distance.h), for repair_vs_peers.sh: how far each
// tool moved the surface, relative to the input's size.
//
//   repair_distance INPUT OUTPUT  -> prints {"bound": ..., "found": ..., "diagonal": ...}

#include <cstdio>

#include "geometry/mesh/bounding_box.h"
#include "geometry/mesh/weld.h"
#include "geometry/repair/surface_distance.h"
#include "io/mesh/read_mesh.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: repair_distance INPUT OUTPUT\n");
    return 2;
  }
  const fabmesh::TriangleSoup a = fabmesh::weld(fabmesh::read_mesh(argv[1])).soup;
  const fabmesh::TriangleSoup b = fabmesh::weld(fabmesh::read_mesh(argv[2])).soup;
  const fabmesh::DistanceBound d = fabmesh::hausdorff_distance(a, b);
  const double diagonal = fabmesh::bounding_box(a.vertices).size().norm();
  std::printf("{\"bound\": %.9g, \"found\": %.9g, \"diagonal\": %.9g}\n", d.upper, d.lower, diagonal);
  return 0;
}
