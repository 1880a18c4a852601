#pragma once
// What a casting case's pieces and sections share: the pins that join
// them, sized to its wall, and the hair-short edges their cuts leave.

#include <optional>

#include "geometry/mould/casting_case.h"
#include "geometry/validation/validate.h"

namespace fabmesh {

/// A pin of a case whose wall is w = `options.wall`: w / 4 in radius and
/// standing w / 2 out of its piece's face, running w / 4 back into its own
/// piece from the seam (`buried`: a carved piece's or a section's pin; a
/// plate's stands on its face and sets it to 0); its hole `clearance` wider
/// all round and deeper; its polygons of `pin_sides` sides for the hole's
/// circle and the tolerance. Its base and axis are left zero.
CasePin case_pin(const CaseOptions& options);

/// How far a pin's hole and its foot keep from the case's outside and from
/// other cuts all round: w / 16.
double case_pin_margin(const CaseOptions& options);

/// The validation of `piece` with its edges shorter than a hundredth of
/// `tolerance` collapsed (collapse_short_edges: no point moves), when it had
/// some and is valid without them; it then takes their place. None
/// otherwise, the piece as it was. A cut by exact booleans that passes a
/// hair from a vertex (of the part, of another cut, of a pin) leaves such
/// edges, which float32 files could fold.
std::optional<ValidationReport> without_hairs(TriangleSoup& piece, double tolerance);

}  // namespace fabmesh
