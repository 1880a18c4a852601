#pragma once
// Faces that are not part of any surface: degenerate ones (a repeated corner,
// or three collinear corners) and repeated copies of one face.

#include <cstdint>
#include <vector>

#include "geometry/repair/repair_log.h"
#include "geometry/repair/tracked_soup.h"

namespace fabmesh {

/// Removes faces with a repeated corner or exactly collinear corners (the
/// needle a collinear face leaves is closed by stitch_t_junctions). Logs
/// each as RepairStep::DegenerateFace.
void remove_degenerate_faces(TrackedSoup& mesh, RepairLog& log);

/// Removes repeated faces (the same three vertices): copies facing the same
/// way keep one; two copies facing opposite ways cancel (both removed: the
/// wall two touching parts share, written once by each). Logs each face
/// removed as RepairStep::DuplicateFace. Returns the origins of the faces
/// that cancelled (walls inside the solid).
std::vector<std::uint32_t> remove_duplicate_faces(TrackedSoup& mesh, RepairLog& log);

}  // namespace fabmesh
