#pragma once
// Orientation: the faces of each connected surface made to agree across
// their shared edges, and closed shells turned to face out of the solid they
// bound (a cavity's shell into it).

#include <cstddef>
#include <vector>

#include "geometry/repair/repair_log.h"
#include "geometry/repair/tracked_soup.h"

namespace fabmesh {

/// The connected components of a soup's faces (sharing a vertex), numbered
/// by their lowest vertex index, as validate numbers its component shells.
struct FaceComponents {
  std::size_t count = 0;
  std::vector<std::uint32_t> of_face;  ///< per face: its component
};

/// The components of `soup` (every face has three distinct corners).
FaceComponents face_components(const TriangleSoup& soup);

/// Flips faces so that faces sharing an edge of exactly two faces traverse
/// it in opposite directions, per component keeping the orientation of the
/// larger part (fewer flips). Logs each flipped face as
/// RepairStep::Orientation. Returns false, with the mesh unchanged, when a
/// component cannot be oriented (a Moebius strip: an odd cycle of
/// disagreements); `where` then holds a face of it.
bool orient_consistently(TrackedSoup& mesh, RepairLog& log, RepairPlace* where = nullptr);

/// Reverses every face of the components whose flag is set.
void flip_components(TrackedSoup& mesh, const FaceComponents& components, const std::vector<bool>& flip);

}  // namespace fabmesh
