#pragma once
// A planar region bounded by one outer loop and any number of holes (a
// countertop with its sink and cooktop cut-outs), sampled from exact curves
// and proven simple with exact predicates.

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "geometry/core/limits.h"
#include "geometry/core/types.h"
#include "geometry/curves/composite.h"

namespace fabmesh {

/// A closed curve cut out of the region, with the name used in messages,
/// e.g. "holes[1] (rounded_rect)".
struct RegionHole {
  CompositeCurve curve;
  std::string label;
  std::string key = {};  ///< its design key path ("holes[1]"), where errors about it are; empty: none
};

struct RegionOptions {
  double tolerance = 0.01;  ///< max distance between each loop and its exact curve, model units (> 0)
  std::size_t max_points = kDefaultMaxPoints;  ///< sampling budget over all loops; more is a BudgetError
  std::string outline_key;  ///< the outline's design key path ("outline"), where errors about it are
};

/// An oriented polygon with holes: the outer loop counter-clockwise, every
/// hole clockwise (the region is on the left of every loop). Loops do not
/// repeat their first point. Simple, pairwise disjoint, holes strictly inside
/// the outer loop and not nested: decided with exact predicates on these points.
struct Region2 {
  std::vector<Vec2> outer;
  std::vector<std::vector<Vec2>> holes;  ///< in the order the holes were given
  double max_deviation = 0.0;            ///< proven bound: loop points/edges vs the exact curves
  double area = 0.0;                     ///< polygon area (outer minus holes), model units^2
  /// Per loop (outer first, then the holes): true when the loop runs against
  /// its curve's direction (the curve was given the other way round).
  std::vector<bool> reversed;
  /// Where each point of `outer` lies on the outline: segment + s (the
  /// outline's global parameter, CompositeCurve::point), in `outer`'s order.
  std::vector<double> outer_along;
  std::string proof;  ///< why the region is simple (for reports)
  /// The smallest distance between two different exact curves (outline and
  /// holes, holes among themselves), a proven lower bound; infinity with no hole.
  double min_clearance = std::numeric_limits<double>::infinity();
  std::string clearance_where;  ///< the two curves and the place (for reports)
};

/// Samples the outline and the holes and checks that they bound a region:
/// the outline is closed and closes (its closing joint has no gap), each loop
/// is simple and comes nowhere within `tolerance` of itself across a neck
/// (find_neck), no two loops meet (no touching), every hole lies strictly
/// inside the outline and outside every other hole, and the exact curves of
/// different loops stay at least `tolerance` apart (exact_clearance: decided
/// on the curves, not on the polylines, which may be up to twice their
/// deviation closer or farther).
/// \throw GeometryError naming the outline segment or the hole at fault, with
///        a point near the problem (its location: the curve's key and the
///        point); RangeError (tolerance), BudgetError (points).
Region2 build_region(const CompositeCurve& outline, const std::vector<RegionHole>& holes,
                     const RegionOptions& options);

/// The loops of `region` in one list: the outer loop first, then the holes.
std::vector<std::vector<Vec2>> region_loops(const Region2& region);

}  // namespace fabmesh
