#pragma once
// The repair's last resort (`repair --wrap`): CGAL's 3D alpha wrapping, a
// closed, manifold, embedded surface around the input at an offset. Lossy by
// design: details narrower than alpha are closed over. CGAL stays in
// alpha_wrap.cpp.

#include "geometry/core/soup.h"

namespace fabmesh {

/// The wrap's two lengths, model units.
struct WrapOptions {
  double alpha = 0.0;   ///< the largest gap the wrap does not enter (> 0)
  double offset = 0.0;  ///< how far outside the input the wrap lies (> 0)
};

/// The alpha wrap of the triangles of `input` (any soup: open, non-manifold,
/// self-intersecting), oriented outward. \throw RangeError when alpha or
/// offset is not positive and finite.
TriangleSoup alpha_wrap(const TriangleSoup& input, const WrapOptions& options);

}  // namespace fabmesh
