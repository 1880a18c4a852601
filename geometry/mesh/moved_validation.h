#pragma once
// Validation of a validated mesh whose vertices moved (quantization, a
// change of number format) while its faces stayed the same.

#include "geometry/mesh/soup.h"
#include "geometry/mesh/validate.h"

namespace fabmesh {

/// The report validate(moved) would give, without redoing what cannot have
/// changed. `moved` has the same triangles as `original` (same indices, same
/// order) and `original_report` is validate(original) (or
/// validate_constructed). Everything combinatorial is a function of the
/// triangles alone (edges, fans, orientation, components, Euler
/// characteristics, genus, duplicate faces), so it is taken from
/// `original_report` (its example locations are the original positions,
/// within the displacement of the moved ones). Everything geometric is
/// recomputed on `moved` exactly as validate does: finiteness, area, signed
/// volume and orientation, exact degeneracy, and the exact self-intersection
/// test. So valid() and every defect kind and count equal validate(moved)'s.
/// \throw InputError when the triangles differ or an index is out of range.
ValidationReport validate_moved(const TriangleSoup& original, const ValidationReport& original_report,
                                const TriangleSoup& moved, const ValidateOptions& options = {});

}  // namespace fabmesh
