#include "geometry/repair/repair_log.h"

#include <algorithm>

namespace fabmesh {

const char* to_string(RepairStep step) {
  switch (step) {
    case RepairStep::Weld:
      return "weld";
    case RepairStep::DegenerateFace:
      return "degenerate faces removed";
    case RepairStep::DuplicateFace:
      return "duplicate faces removed";
    case RepairStep::Stitch:
      return "border edges stitched";
    case RepairStep::NonManifoldEdge:
      return "non-manifold edges split";
    case RepairStep::NonManifoldVertex:
      return "non-manifold vertices split";
    case RepairStep::Orientation:
      return "faces flipped to a consistent orientation";
    case RepairStep::HoleFill:
      return "holes filled";
    case RepairStep::DropComponent:
      return "components removed";
    case RepairStep::SelfIntersection:
      return "self-intersections removed";
    case RepairStep::Union:
      return "overlapping shells united";
    case RepairStep::Outward:
      return "shells turned outward";
    case RepairStep::Wrap:
      return "wrapped";
  }
  return "?";
}

const char* to_key(RepairStep step) {
  switch (step) {
    case RepairStep::Weld:
      return "weld";
    case RepairStep::DegenerateFace:
      return "degenerate_face";
    case RepairStep::DuplicateFace:
      return "duplicate_face";
    case RepairStep::Stitch:
      return "stitch";
    case RepairStep::NonManifoldEdge:
      return "non_manifold_edge";
    case RepairStep::NonManifoldVertex:
      return "non_manifold_vertex";
    case RepairStep::Orientation:
      return "orientation";
    case RepairStep::HoleFill:
      return "hole_fill";
    case RepairStep::DropComponent:
      return "drop_component";
    case RepairStep::SelfIntersection:
      return "self_intersection";
    case RepairStep::Union:
      return "union";
    case RepairStep::Outward:
      return "outward";
    case RepairStep::Wrap:
      return "wrap";
  }
  return "?";
}

RepairAction& RepairLog::action(RepairStep step) {
  for (RepairAction& a : actions_) {
    if (a.step == step) return a;
  }
  actions_.push_back(RepairAction{step, 0, {}, {}});
  return actions_.back();
}

void RepairLog::add(RepairStep step, const RepairPlace& place) {
  RepairAction& a = action(step);
  ++a.count;
  if (a.places.size() < max_places_) a.places.push_back(place);
}

void RepairLog::count(RepairStep step, std::size_t count) { action(step).count += count; }

void RepairLog::describe(RepairStep step, const std::string& detail) { action(step).detail = detail; }

std::vector<RepairAction> RepairLog::actions() const {
  std::vector<RepairAction> sorted = actions_;
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const RepairAction& a, const RepairAction& b) { return a.step < b.step; });
  return sorted;
}

const RepairAction* RepairLog::find(RepairStep step) const {
  for (const RepairAction& a : actions_) {
    if (a.step == step) return &a;
  }
  return nullptr;
}

}  // namespace fabmesh
