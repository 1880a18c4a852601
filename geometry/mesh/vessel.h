#pragma once
// Vessels: a profile curve revolved into a watertight solid or shell mesh.

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "geometry/core/limits.h"
#include "geometry/core/proofs.h"
#include "geometry/core/soup.h"
#include "geometry/core/tolerance_budget.h"
#include "geometry/curves/composite.h"
#include "geometry/section/vessel_section.h"

namespace fabmesh {

struct VesselOptions {
  BodyMode mode = BodyMode::Solid;
  double wall = 0.0;            ///< shell wall thickness, model units
  double base = 0.0;            ///< shell base thickness (0: wall), model units
  RimCut rim = RimCut::Square;  ///< shell: how the rim is cut (see RimCut)
  /// Largest distance between the mesh and the exact surface, model units:
  /// half goes to sampling the profile, the rest to the angular step.
  double tolerance = 0.01;
  /// Budget; more is a BudgetError. It also bounds the profile samples: a
  /// section of n points revolves into at least 1.5 n triangles (at most n/2
  /// axis edges, at least 3 angular steps).
  std::size_t max_triangles = kDefaultMaxTriangles;
  /// Memory the mesh's arrays may take, bytes (the caller's machine or
  /// process limit); more is a BudgetError before they are allocated.
  std::size_t max_bytes = std::numeric_limits<std::size_t>::max();
  KeyNamer name_key;  ///< names the profile in messages (VesselSectionOptions::name_key)
};

/// A revolved vessel.
struct VesselMesh {
  TriangleSoup soup;       ///< the revolution (revolve's layout)
  TopologyProof topology;  ///< its connectivity, proven by the revolution grid
  VesselSection section;
  int segments = 0;            ///< angular segments
  double max_deviation = 0.0;  ///< proven: section deviation + angular sagitta at the largest radius
  /// How the tolerance was divided: the section (half for sampling, a tenth
  /// for the axis clearance) and the revolution (what the section left).
  std::vector<ToleranceShare> tolerance_shares;
  /// Why the mesh is free of self-intersections without a 3D test (always
  /// given: a simple section revolves into an embedded surface).
  EmbeddingProof proof;
};

/// Builds the section, chooses the angular step and revolves. Before any
/// sampling, a lower bound of the triangle count (profile chords from
/// min_chord_count times the angular steps the largest end radius needs) is
/// checked against max_triangles. A shell's exact walls must stay `tolerance`
/// apart (VesselSectionOptions::min_clearance).
/// \throw GeometryError (profile/wall), RangeError, BudgetError (tolerance too small for
///        max_triangles, or the mesh larger than max_bytes)
VesselMesh build_vessel(const CompositeCurve& profile, const VesselOptions& options);

}  // namespace fabmesh
