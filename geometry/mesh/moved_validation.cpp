#include "geometry/mesh/moved_validation.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>
#include <limits>

#include "geometry/core/errors.h"
#include "geometry/core/stage_timer.h"
#include "geometry/mesh/self_intersect.h"

namespace fabmesh {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

bool finite(const Vec3& p) { return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()); }

void add_defect(ValidationReport& report, Defect kind, const DefectCount& found) {
  if (found.count > 0) report.defects.push_back({kind, found.count, found.examples});
}

/// The original report's entry for a combinatorial defect kind, as a count.
DefectCount inherited(const ValidationReport& original, Defect kind) {
  DefectCount out;
  if (const DefectReport* d = original.find(kind)) {
    out.count = d->count;
    out.examples = d->examples;
  }
  return out;
}

/// Area, signed volume (about the box centre) and exact degeneracy, computed
/// as validate computes them, so the values and verdicts are the same.
void measure(const TriangleSoup& soup, std::size_t max_examples, ValidationReport& report,
             DefectCount& degenerate_found, std::vector<char>& degenerate) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Vec3 lo = Vec3::Constant(kInf);
  Vec3 hi = Vec3::Constant(-kInf);
  for (const Vec3& p : soup.vertices) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Vec3 centre = soup.vertices.empty() ? Vec3::Zero() : Vec3(0.5 * (lo + hi));
  double area = 0.0;
  double volume6 = 0.0;
  for (std::size_t f = 0; f < soup.triangles.size(); ++f) {
    const auto& t = soup.triangles[f];
    const Vec3& a = soup.vertices[t[0]];
    const Vec3& b = soup.vertices[t[1]];
    const Vec3& c = soup.vertices[t[2]];
    const Vec3 n = (b - a).cross(c - a);
    area += 0.5 * n.norm();
    volume6 += (a - centre).dot((b - centre).cross(c - centre));
    const bool repeated = t[0] == t[1] || t[1] == t[2] || t[2] == t[0];
    if (repeated ||
        CGAL::collinear(Kernel::Point_3(a.x(), a.y(), a.z()), Kernel::Point_3(b.x(), b.y(), b.z()),
                        Kernel::Point_3(c.x(), c.y(), c.z()))) {
      degenerate[f] = 1;
      degenerate_found.add((a + b + c) / 3.0, max_examples);
    }
  }
  report.area = area;
  report.volume = volume6 / 6.0;
}

}  // namespace

ValidationReport validate_moved(const TriangleSoup& original, const ValidationReport& original_report,
                                const TriangleSoup& moved, const ValidateOptions& options) {
  require_indices_in_range(moved);
  if (moved.triangles != original.triangles || moved.vertices.size() != original.vertices.size()) {
    throw InputError("validate_moved: the moved mesh does not have the original's vertices and triangles");
  }
  // Combinatorial facts: functions of the triangles alone, which are the same.
  ValidationReport report = original_report;
  report.defects.clear();
  report.timings_ms = {};
  report.self_intersection = IntersectionCheck::NotRun;
  report.embedding_proof.clear();
  report.self_intersecting = false;
  report.intersecting_pairs = 0;
  StageTimer timer(report.timings_ms);
  const std::size_t max_examples = options.max_examples;
  DefectCount non_finite;
  for (const Vec3& p : moved.vertices) {
    if (!finite(p)) non_finite.add(p, max_examples);
  }
  report.non_finite_vertices = non_finite.count;
  DefectCount degenerate_found;
  std::vector<char> degenerate(moved.triangles.size(), 0);
  report.area = report.volume = 0.0;
  if (non_finite.count == 0) measure(moved, max_examples, report, degenerate_found, degenerate);
  report.degenerate_faces = degenerate_found.count;
  report.oriented_outward = report.volume > 0.0;
  timer.lap("geometry");

  DefectCount intersections;
  if (options.check_self_intersections && non_finite.count == 0) {
    SelfIntersectOptions si;
    si.parallel = options.parallel;
    si.max_pairs = max_examples;
    const SelfIntersections found = find_self_intersections(moved, degenerate, si);
    report.self_intersection = IntersectionCheck::Tested;
    report.intersecting_pairs = found.count;
    report.self_intersecting = found.count > 0;
    intersections.count = found.count;
    for (const auto& [f, g] : found.pairs) {
      Vec3 mid = Vec3::Zero();
      for (const std::uint32_t v : moved.triangles[f]) mid += moved.vertices[v];
      for (const std::uint32_t v : moved.triangles[g]) mid += moved.vertices[v];
      intersections.examples.push_back(mid / 6.0);
    }
  }
  timer.lap("self_intersection");

  // The defects in validate's order.
  if (moved.triangles.empty()) report.defects.push_back({Defect::Empty, 1, {}});
  add_defect(report, Defect::NonFiniteVertex, non_finite);
  add_defect(report, Defect::BoundaryEdge, inherited(original_report, Defect::BoundaryEdge));
  add_defect(report, Defect::NonManifoldEdge, inherited(original_report, Defect::NonManifoldEdge));
  add_defect(report, Defect::NonManifoldVertex, inherited(original_report, Defect::NonManifoldVertex));
  add_defect(report, Defect::InconsistentOrientation,
             inherited(original_report, Defect::InconsistentOrientation));
  const bool closed = !moved.triangles.empty() && report.boundary_edges == 0 && non_finite.count == 0;
  if (closed && !report.oriented_outward) report.defects.push_back({Defect::InsideOut, 1, {}});
  add_defect(report, Defect::DegenerateFace, degenerate_found);
  add_defect(report, Defect::DuplicateFace, inherited(original_report, Defect::DuplicateFace));
  add_defect(report, Defect::SelfIntersection, intersections);
  return report;
}

}  // namespace fabmesh
