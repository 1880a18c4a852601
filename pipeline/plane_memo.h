#pragma once
// A countertop's work in the plane (its exact curves, the loops proven to
// bound a region, the top's triangulation) kept across the builds of one
// batch, so that variants that differ only in their thickness share it.
// The memo belongs to the batch that makes it (no global state); its planes
// are immutable and shared by the builds that read them, from any thread.

#include <cstddef>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "geometry/section/region.h"
#include "geometry/section/triangulate.h"
#include "pipeline/result.h"

namespace fabmesh {

/// What a countertop's build does before its extrusion: a pure function of
/// the design's loops, tolerance and budgets, not of its thickness.
struct CountertopPlane {
  std::vector<NamedBuiltCurve> curves;  ///< the outline, then each hole ("holes[i]")
  std::vector<RegionHole> holes;        ///< the holes' curves with their labels and keys
  Region2 region;                       ///< the loops as sampled and proven
  PlanarTriangulation top;              ///< the slab's top (slab_top)
};

/// Memory a plane holds, bytes (an estimate from its arrays' sizes).
std::size_t plane_bytes(const CountertopPlane& plane);

/// Planes by key: the exact text of everything a plane is a function of
/// (PlaneReuse::key). Safe to use from several threads at once.
class PlaneMemo {
 public:
  /// A memo holding at most `max_bytes` of planes and keys (plane_bytes + the key's length).
  explicit PlaneMemo(std::size_t max_bytes = std::size_t{64} << 20);

  /// The plane kept under `key`, or null (counted in reused() when found).
  std::shared_ptr<const CountertopPlane> find(const std::string& key);
  /// Keeps `plane` under `key` as the most recently used; the least recently
  /// used planes leave while the memo holds more than its bytes. A plane
  /// larger than that alone is not kept; a key kept already is left as it is.
  void keep(const std::string& key, std::shared_ptr<const CountertopPlane> plane);

  std::size_t size() const;    ///< planes held
  std::size_t reused() const;  ///< planes found by find()

 private:
  struct Entry {
    std::string key;
    std::shared_ptr<const CountertopPlane> plane;
    std::size_t bytes = 0;
  };
  mutable std::mutex mutex_;
  std::list<Entry> entries_;  // the most recently used first
  std::size_t max_bytes_;
  std::size_t bytes_ = 0;
  std::size_t reused_ = 0;
};

/// Where a build may take its plane from a memo, and keep it there.
struct PlaneReuse {
  PlaneMemo* memo = nullptr;  ///< null: the plane is built and not kept
  /// The design's canonical text with its name and thickness left out
  /// (DesignSource::resolve's blanked text for kPlaneFreeKeys); the builder
  /// adds the tolerance it builds to. Empty: not reused.
  std::string key;
};

/// The root keys of a countertop design whose values its plane does not
/// read: `name` (a batch names each variant) and `thickness` (read into the
/// extrusion, the cut's default depth, the backsplash's default thickness and
/// the edge profile's default radius).
inline const std::vector<std::string>& plane_free_keys() {
  static const std::vector<std::string> keys{"name", "thickness"};
  return keys;
}

}  // namespace fabmesh
