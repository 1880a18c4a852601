#pragma once
// The pins that join a casting case's pieces and sections, sized to its wall.

#include "geometry/mould/casting_case.h"

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

}  // namespace fabmesh
