#include "geometry/mesh/vessel.h"

#include <fmt/format.h>

#include <cmath>

#include "geometry/core/errors.h"
#include "geometry/mesh/revolve.h"

namespace fabmesh {

VesselMesh build_vessel(const CompositeCurve& profile, const VesselOptions& options) {
  require_positive("tolerance", options.tolerance);
  VesselSectionOptions so;
  so.mode = options.mode;
  so.wall = options.wall;
  so.base = options.base;
  so.tolerance = 0.5 * options.tolerance;
  so.max_points = options.max_triangles / 3 * 2 + 1;  // see VesselOptions::max_triangles
  VesselSection section = build_vessel_section(profile, so);

  const double angular_tolerance = options.tolerance - section.max_deviation;
  const int segments = angular_segments(section.max_radius, angular_tolerance);
  const std::size_t triangles = revolved_triangle_count(section.loops, segments);
  if (triangles > options.max_triangles) {
    throw BudgetError(
        static_cast<double>(triangles), static_cast<double>(options.max_triangles),
        fmt::format("tolerance {} needs {} triangles, over the budget of {} (raise max_triangles or "
                    "the tolerance)",
                    options.tolerance, triangles, options.max_triangles));
  }
  RevolveOptions ro;
  ro.segments = segments;
  const double sagitta = section.max_radius * (1.0 - std::cos(M_PI / segments));
  const double max_deviation = section.max_deviation + sagitta;
  EmbeddingProof proof{section.proof + fmt::format("; revolved in {} uniform angular steps", segments)};
  // The mesh member is initialised from revolve's result in place (meshes cannot be moved).
  return VesselMesh{revolve(section.loops, ro), std::move(section), segments, max_deviation,
                    std::move(proof)};
}

}  // namespace fabmesh
