// kind: vessel -> profile curve -> section -> revolution, proven embedded.

#include <cmath>

#include "geometry/curves/build_curve.h"
#include "geometry/mesh/bounding_box.h"
#include "geometry/mesh/vessel.h"
#include "pipeline/build_design.h"

namespace fabmesh {

BuiltMesh build(const VesselDesign& design, const BuildContext& context) {
  const BuiltCurve profile = build_curve(design.profile);
  context.watch.lap("curve");
  VesselOptions options;
  options.mode = design.mode;
  options.wall = design.wall;
  options.base = design.base;
  options.rim = design.rim;
  options.tolerance = context.tolerance;
  options.max_triangles = design.max_triangles;
  options.label = design.profile.label;
  const VesselMesh vessel = build_vessel(profile.curve, options);
  context.watch.lap("build");
  std::size_t section_points = 0;
  for (const auto& loop : vessel.section.loops) section_points += loop.size();
  BuiltMesh out = validated(vessel.mesh, vessel.proof, context);
  out.max_deviation = vessel.max_deviation;
  const BoundingBox box = bounding_box(out.soup.vertices);
  out.facts = {{"angular_segments", vessel.segments},
               {"section_loops", vessel.section.loops.size()},
               {"section_points", section_points},
               {"max_radius", vessel.section.max_radius},
               {"bbox_min", {box.lo.x(), box.lo.y(), box.lo.z()}},
               {"bbox_max", {box.hi.x(), box.hi.y(), box.hi.z()}}};
  if (!std::isnan(vessel.section.min_clearance)) {
    // The thinnest place of the shell, between the exact outer and inner surfaces.
    out.facts["min_clearance"] = vessel.section.min_clearance;
    out.facts["min_clearance_where"] = vessel.section.clearance_where;
  }
  return out;
}

}  // namespace fabmesh
