#pragma once
// Stitching borders: where a border vertex lies on another border edge (a
// T-junction: a crack between a coarse and a fine side, or the needle a
// collinear face left), the edge's face is split at the vertex so that the
// two sides meet edge to edge.

#include "geometry/repair/repair_log.h"
#include "geometry/repair/tracked_soup.h"

namespace fabmesh {

/// Splits each border edge at the border vertices within `tolerance` (model
/// units, > 0) of its interior, in rounds until none is left (at most 8).
/// Each split fans the edge's face from its opposite corner (the new faces
/// keep the face's origin); each vertex inserted is logged as
/// RepairStep::Stitch. Returns the number of vertices inserted.
std::size_t stitch_t_junctions(TrackedSoup& mesh, double tolerance, RepairLog& log);

}  // namespace fabmesh
