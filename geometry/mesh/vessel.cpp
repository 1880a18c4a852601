#include "geometry/mesh/vessel.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "geometry/core/budget.h"
#include "geometry/core/error_checks.h"
#include "geometry/core/side_by_side.h"
#include "geometry/mesh/revolution_margin.h"
#include "geometry/mesh/revolve.h"
#include "geometry/sampling/sample_curve.h"

namespace fabmesh {

namespace {

// The share of the tolerance that keeps rings off the axis (see
// VesselSectionOptions::axis_clearance): a profile leaving the axis tangent
// to it would otherwise put rings of radius 1e-4 around the pole, whose
// vertices sit a few micrometres apart and break under any rounding.
constexpr double kAxisClearance = 0.1;

// Refuses a tolerance whose lower bound of triangles is over the budget
// before anything is sampled: every chord of a curved segment revolves into
// at least `segments` triangles, and the angular step must keep the sagitta
// at the largest radius of an end point within the tolerance.
void require_budget(const CompositeCurve& profile, const VesselOptions& options, double sample_tolerance) {
  double chords = 0.0, radius = 0.0;
  for (const Segment& seg : profile.segments()) {
    if (seg.kind() != SegmentKind::Line) chords += min_chord_count(seg, sample_tolerance, 2);
    radius = std::max({radius, std::abs(seg.point(0.0).x()), std::abs(seg.point(1.0).x())});
  }
  const int segments = angular_segments(radius, options.tolerance);
  const double triangles = chords * segments;
  require_within_budget(
      triangles, options.max_triangles,
      [&] {
        return fmt::format(
            "the mesh needs at least {:.4g} triangles (estimated before sampling: {:.4g} "
            "profile chords x {} angular steps)",
            triangles, chords, segments);
      },
      "raise max_triangles or the tolerance");
}

}  // namespace

VesselMesh build_vessel(const CompositeCurve& profile, const VesselOptions& options) {
  require_positive("tolerance", options.tolerance);
  VesselSectionOptions so;
  so.mode = options.mode;
  so.wall = options.wall;
  so.base = options.base;
  so.rim = options.rim;
  // The section's share covers its sampling (half the tolerance) and the
  // move of points near the axis off it (kAxisClearance of it).
  ToleranceBudget budget(options.tolerance);
  budget.take("section", 0.5 + kAxisClearance);
  so.tolerance = 0.5 * options.tolerance;
  so.min_clearance = options.tolerance;
  so.axis_clearance = kAxisClearance * options.tolerance;
  so.max_points = options.max_triangles / 3 * 2 + 1;  // see VesselOptions::max_triangles
  so.name_key = options.name_key;
  require_budget(profile, options, so.tolerance);
  VesselSection section = build_vessel_section(profile, so);
  budget.use("section", section.max_deviation);

  const double angular_tolerance = budget.take_rest("revolution");
  const int segments = angular_segments(section.max_radius, angular_tolerance);
  const std::size_t triangles = revolved_triangle_count(section.loops, segments);
  require_within_budget(
      triangles, options.max_triangles, [&] { return fmt::format("the mesh needs {} triangles", triangles); },
      "raise max_triangles or the tolerance");
  const std::size_t vertices = revolved_vertex_count(section.loops, segments);
  const double bytes = static_cast<double>(triangles) * sizeof(std::array<std::uint32_t, 3>) +
                       static_cast<double>(vertices) * sizeof(Vec3);
  if (bytes > static_cast<double>(options.max_bytes)) {
    throw BudgetError(
        bytes, static_cast<double>(options.max_bytes),
        fmt::format("the mesh needs {} triangles and {:.3g} GB of memory, more than the {:.3g} GB "
                    "this process can use (raise the tolerance or lower max_triangles)",
                    triangles, bytes * 1e-9, static_cast<double>(options.max_bytes) * 1e-9));
  }
  RevolveOptions ro;
  ro.segments = segments;
  const double sagitta = chord_sagitta(section.max_radius, angular_step(segments));
  budget.use("revolution", sagitta);
  const double max_deviation = section.max_deviation + sagitta;
  EmbeddingProof proof;
  proof.statement = section.proof + fmt::format("; revolved in {} uniform angular steps", segments);
  // The margin is computed on the section alone: beside the revolution.
  RevolvedSoup revolved;
  side_by_side([&] { proof.margin = revolution_margin(section.loops, segments); },
               [&] { revolved = revolve(section.loops, ro); });
  return VesselMesh{std::move(revolved.soup),
                    std::move(revolved.topology),
                    std::move(section),
                    segments,
                    max_deviation,
                    budget.shares(),
                    std::move(proof)};
}

}  // namespace fabmesh
