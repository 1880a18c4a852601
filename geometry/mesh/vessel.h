#pragma once
// Vessels: a profile curve revolved into a watertight solid or shell mesh.

#include <cstddef>
#include <string>

#include "geometry/curves/composite.h"
#include "geometry/section/vessel_section.h"

namespace fabmesh {

struct VesselOptions {
  BodyMode mode = BodyMode::Solid;
  double wall = 0.0;  ///< shell wall thickness, model units
  double base = 0.0;  ///< shell base thickness (0: wall), model units
  /// Largest distance between the mesh and the exact surface, model units:
  /// half goes to sampling the profile, the rest to the angular step.
  double tolerance = 0.01;
  std::size_t max_triangles = 20000000;  ///< budget; more is a BudgetError
};

/// Returned by value (NRVO: built in place); OpenMesh meshes are copied, not moved.
struct VesselMesh {
  Mesh mesh;
  VesselSection section;
  int segments = 0;            ///< angular segments
  double max_deviation = 0.0;  ///< proven: section deviation + angular sagitta at the largest radius
  /// Why the mesh is free of self-intersections without a 3D test.
  std::string embedding_proof;
};

/// Builds the section, chooses the angular step and revolves.
/// \throw GeometryError (profile/wall), RangeError, BudgetError (tolerance too small for max_triangles)
VesselMesh build_vessel(const CompositeCurve& profile, const VesselOptions& options);

}  // namespace fabmesh
