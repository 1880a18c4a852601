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
  so.max_points = options.max_triangles;
  VesselMesh out;
  out.section = build_vessel_section(profile, so);

  const double angular_tolerance = options.tolerance - out.section.max_deviation;
  out.segments = angular_segments(out.section.max_radius, angular_tolerance);
  const std::size_t triangles = revolved_triangle_count(out.section.loops, out.segments);
  if (triangles > options.max_triangles) {
    throw BudgetError(
        static_cast<double>(triangles), static_cast<double>(options.max_triangles),
        fmt::format("tolerance {} needs {} triangles, over the budget of {} (raise max_triangles or "
                    "the tolerance)",
                    options.tolerance, triangles, options.max_triangles));
  }
  RevolveOptions ro;
  ro.segments = out.segments;
  revolve(out.section.loops, ro, out.mesh);
  const double sagitta = out.section.max_radius * (1.0 - std::cos(M_PI / out.segments));
  out.max_deviation = out.section.max_deviation + sagitta;
  out.embedding_proof =
      out.section.proof + fmt::format("; revolved in {} uniform angular steps", out.segments);
  return out;
}

}  // namespace fabmesh
