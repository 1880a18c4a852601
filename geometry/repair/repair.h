#pragma once
// `fabmesh repair` as a function over a triangle soup: local repairs first,
// each recorded with where, then intersections resolved exactly, or the
// whole wrapped when asked; the result validated and its distance to the
// input measured (docs/repair.md). Pure: no I/O.

#include <cstddef>
#include <string>
#include <vector>

#include "geometry/core/soup.h"
#include "geometry/repair/repair_log.h"
#include "geometry/repair/surface_distance.h"
#include "geometry/repair/weld_borders.h"
#include "geometry/validation/validate.h"

namespace fabmesh {

/// What a repair may do.
struct RepairOptions {
  /// Border vertices closer than this merge (model units); < 0 (default):
  /// chosen from the data (choose_weld_distance), 0: no border weld.
  double weld_distance = -1.0;
  /// How far apart the copies of a split non-manifold vertex are moved
  /// (model units); 0: 1e-5 of the bounding box diagonal. The caller raises
  /// it above what writing moves a vertex (float32, 3MF's decimals).
  double separation = 0.0;
  bool fill_holes = true;  ///< fill holes (else an open mesh stays invalid)
  /// Replace the mesh by its alpha wrap (lossy, always closed): only when asked.
  bool wrap = false;
  /// The largest distance the output may be from the input (model units; 0:
  /// no limit). Past it the repair is refused. With `wrap`, it also sets
  /// the wrap's alpha (this) and offset (a third of it); 0 then means 1% of
  /// the bounding box diagonal.
  double max_deviation = 0.0;
  std::size_t max_places = 20;   ///< places kept per step kind
  ValidationOptions validation;  ///< of the input and of the result
  DistanceOptions distance;
};

/// The measured change: before and after, and the distance between them.
struct RepairMeasure {
  DistanceBound input_to_output;  ///< sup over the input's measured faces of the distance to the output
  DistanceBound output_to_input;  ///< sup over the output of the distance to the input
  double distance = 0.0;          ///< the proven two-sided bound: max of both uppers
  /// Faces read not measured from the input side: the shells united or
  /// autorefined (every point on the output or inside it, by construction),
  /// the copies of a face that cancelled (a wall inside the solid), and the
  /// components dropped (listed in RepairResult::dropped).
  std::size_t unmeasured_faces = 0;
};

/// What repair did and got.
struct RepairResult {
  TriangleSoup soup;             ///< the result (vertices unused by faces removed)
  ValidationReport before;       ///< the input after the exact weld
  ValidationReport after;        ///< the result
  bool changed = false;          ///< false: the input was valid and is returned as it is (welded)
  std::size_t exact_welded = 0;  ///< coincident vertices merged first (every STL repeats its corners)
  WeldChoice weld;               ///< the border weld's distance and why
  std::vector<RepairAction> actions;
  std::vector<DroppedComponent> dropped;
  std::size_t components_before = 0;  ///< of the input after the exact weld
  RepairMeasure measure;
  /// What could not be mended, one line each with where; empty when the result is valid.
  std::vector<std::string> unresolved;
  /// The result is valid and within max_deviation: write it.
  bool ok() const { return after.valid() && unresolved.empty(); }
};

/// Repairs `input` (see docs/repair.md for each step and its guarantees).
/// Never throws for a mesh that cannot be mended: the result then says what
/// is left (`unresolved`, `after`). \throw InputError for an empty mesh, a
/// non-finite coordinate or an index out of range; RangeError for a negative
/// or non-finite option.
RepairResult repair(const TriangleSoup& input, const RepairOptions& options = {});

}  // namespace fabmesh
