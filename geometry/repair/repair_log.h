#pragma once
// What a repair did, step by step and where: the record every repair keeps
// (docs/repair.md). Places are given as indices into the mesh as it was read
// (before any welding) and as coordinates, so a user can find them.

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "geometry/core/types.h"

namespace fabmesh {

/// An index that names nothing: a face or vertex the repair made.
inline constexpr std::uint32_t kNoIndex = std::numeric_limits<std::uint32_t>::max();

/// The kinds of repair, in the order they run.
enum class RepairStep {
  Weld,               ///< nearly coincident border vertices merged (distance from the data)
  DegenerateFace,     ///< a face with a repeated corner or collinear corners removed
  DuplicateFace,      ///< a second copy of a face removed (opposite copies cancel: both removed)
  Stitch,             ///< a border edge split where a border vertex lies on it (a T-junction closed)
  NonManifoldEdge,    ///< an edge of more than two faces split into manifold pairs
  NonManifoldVertex,  ///< a vertex whose faces form several fans split into one vertex per fan
  Orientation,        ///< faces flipped to agree with their neighbours
  HoleFill,           ///< a hole (border loop) triangulated, refined and faired
  DropComponent,      ///< a component removed: it has no area or encloses no volume
  SelfIntersection,   ///< a component's own intersections removed (CGAL autorefinement)
  Union,              ///< closed shells that overlap replaced by the surface of their union
  Outward,            ///< a closed shell turned to face outward (inward for a cavity)
  Wrap,               ///< the whole mesh replaced by an alpha wrap (--wrap)
};

/// A short lower-case description, e.g. "weld", "hole fill".
const char* to_string(RepairStep step);

/// The step as a JSON key, e.g. "weld", "hole_fill", "non_manifold_edge".
const char* to_key(RepairStep step);

/// One place a repair step acted on.
struct RepairPlace {
  std::uint32_t face = kNoIndex;    ///< a face of the mesh as read, or kNoIndex
  std::uint32_t vertex = kNoIndex;  ///< a vertex of the mesh as read, or kNoIndex
  Vec3 point = Vec3::Zero();        ///< where, model units (a vertex, face centroid or loop centre)
  std::string detail;               ///< e.g. "12 border edges, 40 faces added"; may be empty
};

/// Everything one kind of step did: how often and where (the first places).
struct RepairAction {
  RepairStep step = RepairStep::Weld;
  std::size_t count = 0;            ///< faces, vertices, holes, shells ... acted on (see docs/repair.md)
  std::vector<RepairPlace> places;  ///< the first RepairOptions::max_places of them
  std::string detail;               ///< the step's own facts, e.g. "distance 1.2e-05"
};

/// A component the repair removed: which, how large, and why.
struct DroppedComponent {
  std::size_t faces = 0;   ///< its faces in the mesh as read
  double area = 0.0;       ///< model units^2
  Vec3 lo = Vec3::Zero();  ///< its bounding box, model units
  Vec3 hi = Vec3::Zero();
  std::uint32_t first_face = kNoIndex;  ///< its lowest face index in the mesh as read
  std::string why;
};

/// The log of a repair: one action per step kind that acted, in step order.
class RepairLog {
 public:
  explicit RepairLog(std::size_t max_places = 20) : max_places_(max_places) {}
  /// Counts one more place for `step` (kept when fewer than max_places are).
  void add(RepairStep step, const RepairPlace& place);
  /// Adds `count` to `step` without a place (e.g. vertices of one weld group).
  void count(RepairStep step, std::size_t count);
  /// Sets the step's own facts line (creating the action if needed).
  void describe(RepairStep step, const std::string& detail);
  /// The actions, sorted by step.
  std::vector<RepairAction> actions() const;
  /// The action of `step`, or nullptr when it never acted.
  const RepairAction* find(RepairStep step) const;

 private:
  RepairAction& action(RepairStep step);
  std::size_t max_places_;
  std::vector<RepairAction> actions_;
};

}  // namespace fabmesh
