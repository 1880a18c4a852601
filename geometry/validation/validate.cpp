#include "geometry/validation/validate.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "geometry/core/errors.h"
#include "geometry/core/stage_timer.h"
#include "geometry/mesh/volume.h"
#include "geometry/validation/detail/components.h"
#include "geometry/validation/detail/self_intersect.h"
#include "geometry/validation/detail/topology.h"
#include "geometry/validation/detail/vertex_star.h"

namespace fabmesh {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

bool finite(const Vec3& p) { return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()); }

void add_defect(ValidationReport& report, Defect kind, const DefectCount& found) {
  if (found.count > 0) report.defects.push_back({kind, found.count, found.examples, found.locations});
}

/// The total area of `soup`'s faces, model units^2.
double total_area(const TriangleSoup& soup) {
  double area = 0.0;
  for (const auto& t : soup.triangles) {
    const Vec3& a = soup.vertices[t[0]];
    area += 0.5 * (soup.vertices[t[1]] - a).cross(soup.vertices[t[2]] - a).norm();
  }
  return area;
}

/// `soup` scaled by 2^-k, k the binary exponent of its largest coordinate
/// magnitude (exact but for underflow): its measures cannot overflow.
TriangleSoup unit_scaled(const TriangleSoup& soup, int& k) {
  double largest = 0.0;
  for (const Vec3& p : soup.vertices) largest = std::max(largest, p.cwiseAbs().maxCoeff());
  std::frexp(largest, &k);
  TriangleSoup scaled = soup;
  for (Vec3& p : scaled.vertices)
    p = Vec3(std::ldexp(p.x(), -k), std::ldexp(p.y(), -k), std::ldexp(p.z(), -k));
  return scaled;
}

/// Where products of coordinates overflowed (a mesh of coordinates near
/// 1e300) or underflowed in the area and signed volume of `report`, they are
/// computed again on the mesh scaled by a power of two and scaled back: a
/// measure beyond the range of doubles is then +-infinity, never NaN.
void rescale_sizes(const TriangleSoup& soup, ValidationReport& report) {
  if (std::isfinite(report.area) && std::isfinite(report.volume) &&
      (report.area > 1e-200 || report.area == 0.0))
    return;
  int k = 0;
  const TriangleSoup scaled = unit_scaled(soup, k);
  report.area = std::ldexp(total_area(scaled), 2 * k);
  report.volume = std::ldexp(signed_volume(scaled), 3 * k);
}

/// Marks in `skip` the extra copies of each face (the same three vertices,
/// in any order) at a vertex of kStarMinDegree faces or more: a face
/// repeated a million times (an STL of a few faces written over and over)
/// would make the 3D test quadratic there, and duplicates are a defect of
/// their own. Linear for a mesh without such vertices.
void skip_piled_copies(const TriangleSoup& soup, std::vector<char>& skip) {
  std::vector<std::uint32_t> degree(soup.vertices.size(), 0);
  for (const auto& t : soup.triangles) {
    for (const std::uint32_t v : t) ++degree[v];
  }
  using Key = std::array<std::uint32_t, 3>;
  std::vector<std::pair<Key, std::uint32_t>> piled;
  for (std::uint32_t f = 0; f < soup.triangles.size(); ++f) {
    Key t = soup.triangles[f];
    if (skip[f] || std::max({degree[t[0]], degree[t[1]], degree[t[2]]}) < detail::kStarMinDegree) continue;
    std::sort(t.begin(), t.end());
    piled.emplace_back(t, f);
  }
  std::sort(piled.begin(), piled.end());
  for (std::size_t i = 1; i < piled.size(); ++i) {
    if (piled[i].first == piled[i - 1].first) skip[piled[i].second] = 1;
  }
}

/// Whether face `f` of `soup` is degenerate: a repeated index, or three
/// collinear corners (exactly).
bool degenerate_face(const TriangleSoup& soup, std::size_t f) {
  const auto& t = soup.triangles[f];
  if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) return true;
  const Vec3& a = soup.vertices[t[0]];
  const Vec3& b = soup.vertices[t[1]];
  const Vec3& c = soup.vertices[t[2]];
  return CGAL::collinear(Kernel::Point_3(a.x(), a.y(), a.z()), Kernel::Point_3(b.x(), b.y(), b.z()),
                         Kernel::Point_3(c.x(), c.y(), c.z()));
}

/// Area, signed volume, the exact sign of the volume and exact degeneracy;
/// marks degenerate faces in `degenerate`. The faces' flags and the three
/// sums are independent, so with `parallel` they are found side by side (the
/// flags by blocks of faces); each sum is taken in face order either way, so
/// the report is the same. \pre every coordinate finite
void measure(const TriangleSoup& soup, const ValidationOptions& options, ValidationReport& report,
             DefectCount& degenerate_found, std::vector<char>& degenerate) {
  const std::size_t n = soup.triangles.size();
  const auto flag = [&](std::size_t from, std::size_t to) {
    for (std::size_t f = from; f < to; ++f) degenerate[f] = degenerate_face(soup, f) ? 1 : 0;
  };
  const auto area = [&] { report.area = total_area(soup); };
  const auto volume = [&] { report.volume = signed_volume(soup); };
  const auto outward = [&] { report.oriented_outward = total_volume_sign(soup) > 0; };
  if (options.parallel) {
    const auto flags = [&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, std::size_t{1} << 14),
                        [&](const tbb::blocked_range<std::size_t>& r) { flag(r.begin(), r.end()); });
    };
    tbb::parallel_invoke(flags, area, volume, outward);
  } else {
    flag(0, n);
    area();
    volume();
    outward();
  }
  rescale_sizes(soup, report);
  for (std::size_t f = 0; f < n; ++f) {
    if (!degenerate[f]) continue;
    const auto& t = soup.triangles[f];
    const Vec3 centroid = (soup.vertices[t[0]] + soup.vertices[t[1]] + soup.vertices[t[2]]) / 3.0;
    degenerate_found.add(centroid, options.max_examples, options.max_locations, [&] {
      return DefectLocation{{static_cast<std::uint32_t>(f)}, {t[0], t[1], t[2]}};
    });
  }
}

void set_genus(ValidationReport& report, const Topology& topo) {
  report.euler_characteristics = topo.euler_characteristics;
  const bool closed_manifold = report.boundary_edges == 0 && report.non_manifold_edges == 0 &&
                               report.non_manifold_vertices == 0 && report.consistently_oriented &&
                               topo.components > 0;
  if (!closed_manifold) return;
  long genus = 0;
  for (const long chi : topo.euler_characteristics) {
    if (chi > 2 || (2 - chi) % 2 != 0) return;  // not a closed orientable surface
    genus += (2 - chi) / 2;
  }
  report.genus = genus;
}

}  // namespace

const char* to_string(Defect kind) {
  switch (kind) {
    case Defect::Empty:
      return "no faces";
    case Defect::NonFiniteVertex:
      return "non-finite vertices";
    case Defect::BoundaryEdge:
      return "boundary edges";
    case Defect::NonManifoldEdge:
      return "non-manifold edges";
    case Defect::NonManifoldVertex:
      return "non-manifold vertices";
    case Defect::InconsistentOrientation:
      return "inconsistently oriented edges";
    case Defect::InsideOut:
      return "inside-out (non-positive volume)";
    case Defect::InvertedComponent:
      return "inverted components";
    case Defect::NestedSameOrientation:
      return "nested components of the same orientation";
    case Defect::DegenerateFace:
      return "degenerate faces";
    case Defect::DuplicateFace:
      return "duplicate faces";
    case Defect::SelfIntersection:
      return "self-intersecting face pairs";
  }
  return "unknown defect";
}

const char* to_key(Defect kind) {
  switch (kind) {
    case Defect::Empty:
      return "empty";
    case Defect::NonFiniteVertex:
      return "non_finite_vertex";
    case Defect::BoundaryEdge:
      return "boundary_edge";
    case Defect::NonManifoldEdge:
      return "non_manifold_edge";
    case Defect::NonManifoldVertex:
      return "non_manifold_vertex";
    case Defect::InconsistentOrientation:
      return "inconsistent_orientation";
    case Defect::InsideOut:
      return "inside_out";
    case Defect::InvertedComponent:
      return "inverted_component";
    case Defect::NestedSameOrientation:
      return "nested_same_orientation";
    case Defect::DegenerateFace:
      return "degenerate_face";
    case Defect::DuplicateFace:
      return "duplicate_face";
    case Defect::SelfIntersection:
      return "self_intersection";
  }
  return "unknown";
}

const char* to_string(IntersectionCheck check) {
  switch (check) {
    case IntersectionCheck::NotRun:
      return "not run";
    case IntersectionCheck::Tested:
      return "tested";
    case IntersectionCheck::ProvenByConstruction:
      return "proven by construction";
  }
  return "unknown";
}

const DefectReport* ValidationReport::find(Defect kind) const {
  for (const DefectReport& d : defects) {
    if (d.kind == kind) return &d;
  }
  return nullptr;
}

namespace {

// What the positions alone decide: finite coordinates, the faces' measures
// and degeneracy, orientation and the self-intersection test (stages
// "geometry" and "self_intersection"). Independent of the connectivity
// analysis, so validate runs it beside analyse_topology.
struct PositionFacts {
  ValidationReport report;  ///< the fields the positions decide, and the stages' timings
  DefectCount non_finite, degenerate, intersections;
};
PositionFacts position_facts(const TriangleSoup& soup, const ValidationOptions& options);

// The report of `facts` completed with the connectivity facts and every
// defect, shared by every path of validate.
ValidationReport validate_with(const TriangleSoup& soup, const Topology& topo, PositionFacts facts);

// The connectivity facts a moved copy shares with its original: functions of
// the triangles alone, taken from the original's report.
Topology inherited_topology(const ValidationReport& original_report) {
  const auto inherited = [&](Defect kind) {
    DefectCount out;
    if (const DefectReport* d = original_report.find(kind)) {
      out.count = d->count;
      out.examples = d->examples;
      out.locations = d->locations;
    }
    return out;
  };
  Topology topo;
  topo.boundary_edges = inherited(Defect::BoundaryEdge);
  topo.non_manifold_edges = inherited(Defect::NonManifoldEdge);
  topo.non_manifold_vertices = inherited(Defect::NonManifoldVertex);
  topo.inconsistent_edges = inherited(Defect::InconsistentOrientation);
  topo.duplicate_faces = inherited(Defect::DuplicateFace);
  topo.components = original_report.components;
  topo.euler_characteristics = original_report.euler_characteristics;
  return topo;
}

// validate(moved) with options.moved_from: the original's combinatorial facts,
// the geometry tested again, and the original's embedding margin when no
// vertex moved as far.
ValidationReport validate_moved(const TriangleSoup& moved, const MovedFrom& from,
                                const ValidationOptions& options) {
  const TriangleSoup& original = *from.soup;
  const ValidationReport& original_report = *from.report;
  if (moved.triangles != original.triangles || moved.vertices.size() != original.vertices.size()) {
    throw InputError(
        "validate: the moved mesh (moved_from) does not have the original's vertices and triangles");
  }
  // Within the original's embedding margin the move cannot create an intersection.
  double moved_by = 0.0;
  for (std::size_t v = 0; v < moved.vertices.size(); ++v) {
    moved_by = std::max(moved_by, (moved.vertices[v] - original.vertices[v]).norm());
  }
  moved_by *= 1.0 + 1e-12;  // the norm's rounding, upward
  const bool constructed = original_report.self_intersection == IntersectionCheck::ProvenByConstruction;
  const bool within_margin = constructed && moved_by < original_report.embedding_margin;
  // Beyond the margin, the builder's own exact argument may still hold for the copy.
  const bool rechecked = constructed && !within_margin && original_report.embedding_recheck &&
                         original_report.embedding_recheck(moved);
  ValidationOptions checks = options;
  if (within_margin || rechecked) checks.check_self_intersections = false;
  ValidationReport report =
      validate_with(moved, inherited_topology(original_report), position_facts(moved, checks));
  report.topology_proof = original_report.topology_proof;
  if (within_margin && report.non_finite_vertices == 0) {
    report.self_intersection = IntersectionCheck::ProvenByConstruction;
    report.embedding_proof =
        fmt::format("{}; every vertex moved by at most {:.3g}, less than its margin {:.3g}",
                    original_report.embedding_proof, moved_by, original_report.embedding_margin);
    report.embedding_margin = original_report.embedding_margin - moved_by;
  } else if (rechecked && report.non_finite_vertices == 0) {
    report.self_intersection = IntersectionCheck::ProvenByConstruction;
    report.embedding_proof =
        fmt::format("{}; every vertex moved by at most {:.3g}, and as moved {}",
                    original_report.embedding_proof, moved_by, original_report.embedding_recheck_statement);
  }
  return report;
}

// The report with the builder's proof of embedding in place of the 3D test.
ValidationReport with_embedding(ValidationReport report, const EmbeddingProof& proof) {
  if (report.non_finite_vertices == 0) {
    report.self_intersection = IntersectionCheck::ProvenByConstruction;
    report.embedding_proof = proof.statement;
    report.embedding_margin = proof.margin;
    report.embedding_recheck = proof.recheck;
    report.embedding_recheck_statement = proof.recheck_statement;
    report.self_intersecting = false;
  }
  return report;
}

/// Adds `found` as a defect of `kind`, keeping the defects in enum order.
void insert_defect(ValidationReport& report, Defect kind, const DefectCount& found) {
  if (found.count == 0) return;
  const auto at = std::find_if(report.defects.begin(), report.defects.end(),
                               [&](const DefectReport& d) { return d.kind > kind; });
  report.defects.insert(at, {kind, found.count, found.examples, found.locations});
}

/// The one shell of a single-component mesh, from the totals: no other
/// component can contain it, so its orientation is the InsideOut check.
ComponentShell single_shell(const TriangleSoup& soup, const ValidationReport& report) {
  ComponentShell shell;
  std::uint32_t lowest = UINT32_MAX;
  for (const auto& t : soup.triangles) {
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) continue;
    ++shell.faces;
    lowest = std::min({lowest, t[0], t[1], t[2]});
  }
  shell.volume = report.volume;
  shell.outward = report.oriented_outward;
  if (lowest != UINT32_MAX) shell.location = soup.vertices[lowest];
  shell.depth = 0;
  return shell;
}

/// Whether the components of a mesh so validated are disjoint closed
/// surfaces, so that one lies inside another or not: the mesh has no
/// defect other than its total volume's sign, and was tested or proven
/// free of self-intersections.
bool nesting_determined(const ValidationReport& report) {
  return report.self_intersection != IntersectionCheck::NotRun &&
         std::all_of(report.defects.begin(), report.defects.end(),
                     [](const DefectReport& d) { return d.kind == Defect::InsideOut; });
}

/// The shells of a mesh with several components: labels, volumes and, when
/// determined, the nesting with the components that contradict it.
void add_shells(const TriangleSoup& soup, ValidationReport& report, std::size_t max_examples,
                std::size_t max_locations) {
  const ComponentLabels labels = label_components(soup);
  std::vector<double> volumes = component_volumes(soup, labels);
  if (!std::all_of(volumes.begin(), volumes.end(), [](double v) { return std::isfinite(v); })) {
    int k = 0;  // overflow: as rescale_sizes does
    volumes = component_volumes(unit_scaled(soup, k), labels);
    for (double& v : volumes) v = std::ldexp(v, 3 * k);
  }
  const std::vector<int> signs = component_volume_signs(soup, labels);
  auto& shells = report.component_shells;
  shells.resize(labels.count);
  for (std::size_t c = 0; c < labels.count; ++c) {
    shells[c].faces = labels.faces[c];
    shells[c].volume = volumes[c];
    shells[c].outward = signs[c] > 0;
    shells[c].location = soup.vertices[labels.lowest_vertex[c]];
  }
  if (!nesting_determined(report)) return;
  const Nesting nesting = nest_components(soup, labels);
  DefectCount inverted;
  DefectCount nested;
  for (std::size_t c = 0; c < labels.count; ++c) {
    if (!nesting.determined[c]) {
      ++report.undetermined_components;
      continue;
    }
    shells[c].depth = nesting.depth[c];
    shells[c].inside = nesting.inside[c];
    // The component as a location: its lowest vertex and all its faces.
    const auto component = [&] {
      DefectLocation at{{}, {labels.lowest_vertex[c]}};
      for (std::uint32_t f = 0; f < labels.face_component.size(); ++f) {
        if (labels.face_component[f] == c) at.faces.push_back(f);
      }
      return at;
    };
    if (!nesting.inside[c] && !shells[c].outward)
      inverted.add(shells[c].location, max_examples, max_locations, component);
    if (nesting.inside[c] && nesting.determined[*nesting.inside[c]] &&
        shells[c].outward == shells[*nesting.inside[c]].outward) {
      nested.add(shells[c].location, max_examples, max_locations, component);
    }
  }
  insert_defect(report, Defect::InvertedComponent, inverted);
  insert_defect(report, Defect::NestedSameOrientation, nested);
}

/// The report with its component shells: from the totals for one component
/// (nothing more to compute), by labelling and ray casting for several.
ValidationReport with_shells(const TriangleSoup& soup, ValidationReport report,
                             const ValidationOptions& options) {
  if (soup.triangles.empty() || report.non_finite_vertices > 0 || report.components == 0) return report;
  if (report.components == 1) {
    report.component_shells.push_back(single_shell(soup, report));
    return report;
  }
  StageTimer timer(report.timings_ms);
  add_shells(soup, report, options.max_examples, options.max_locations);
  timer.lap("components");
  return report;
}

}  // namespace

ValidationReport validate(const TriangleSoup& soup, const ValidationOptions& options) {
  require_indices_in_range(soup);
  if (options.moved_from) {
    if (options.topology || options.embedding) {
      throw InputError(
          "validate: a moved copy takes its proofs from the original's report, not from options");
    }
    return with_shells(soup, validate_moved(soup, *options.moved_from, options), options);
  }
  ValidationOptions checks = options;
  if (options.embedding) checks.check_self_intersections = false;  // the proof replaces the 3D test
  ValidationReport report;
  if (options.topology) {
    Topology known;
    known.components = options.topology->components;
    known.euler_characteristics = options.topology->euler_characteristics;
    report = validate_with(soup, known, position_facts(soup, checks));
    report.topology_proof = options.topology->statement;
  } else {
    // The connectivity analysis is sequential: the positions' stages (the
    // self-intersection test, itself parallel) run beside it.
    Topology topo;
    StageTimings topology_time;
    const auto analyse = [&] {
      StageTimer timer(topology_time);
      topo = analyse_topology(soup, options.max_examples,
                              options.examples_in_face_order ? ExampleOrder::ByFace : ExampleOrder::ByVertex,
                              options.max_locations);
      timer.lap("topology");
    };
    PositionFacts facts;
    const auto positions = [&] { facts = position_facts(soup, checks); };
    if (options.parallel) {
      tbb::parallel_invoke(analyse, positions);
    } else {
      analyse();
      positions();
    }
    facts.report.timings_ms.insert(facts.report.timings_ms.begin(), topology_time.begin(),
                                   topology_time.end());
    report = validate_with(soup, topo, std::move(facts));
  }
  if (options.embedding) report = with_embedding(std::move(report), *options.embedding);
  return with_shells(soup, std::move(report), options);
}

bool fit_for(const ValidationReport& report, MeshPurpose purpose) {
  if (purpose == MeshPurpose::Drawing || report.valid()) return true;
  return purpose == MeshPurpose::Viewing && report.self_intersection != IntersectionCheck::NotRun &&
         std::all_of(report.defects.begin(), report.defects.end(),
                     [](const DefectReport& d) { return d.kind == Defect::BoundaryEdge; });
}

bool valid_when_moved(const ValidationReport& report, double moved_by) {
  return report.valid() && (moved_by == 0.0 || moved_by < report.embedding_margin);
}

namespace {

PositionFacts position_facts(const TriangleSoup& soup, const ValidationOptions& options) {
  PositionFacts out;
  ValidationReport& report = out.report;
  StageTimer timer(report.timings_ms);
  report.vertices = soup.vertices.size();
  report.triangles = soup.triangles.size();
  const std::size_t max_examples = options.max_examples;
  const std::size_t max_locations = options.max_locations;
  for (std::size_t v = 0; v < soup.vertices.size(); ++v) {
    if (!finite(soup.vertices[v])) {
      out.non_finite.add(soup.vertices[v], max_examples, max_locations, [&] {
        return DefectLocation{{}, {static_cast<std::uint32_t>(v)}};
      });
    }
  }
  report.non_finite_vertices = out.non_finite.count;

  std::vector<char> degenerate(soup.triangles.size(), 0);
  if (out.non_finite.count == 0) measure(soup, options, report, out.degenerate, degenerate);
  report.degenerate_faces = out.degenerate.count;
  timer.lap("geometry");

  if (options.check_self_intersections && out.non_finite.count == 0) {
    SelfIntersectOptions si;
    si.parallel = options.parallel;
    si.max_pairs = std::max(max_examples, max_locations);
    si.deadline = deadline_after(options.max_self_intersection_seconds);
    std::vector<char> skip = degenerate;
    skip_piled_copies(soup, skip);
    const SelfIntersections found = find_self_intersections(soup, skip, si);
    report.self_intersection = found.incomplete ? IntersectionCheck::NotRun : IntersectionCheck::Tested;
    report.self_intersection_timed_out = found.incomplete;
    report.self_intersection_pairs_tested = found.candidates_tested;
    report.intersecting_pairs = found.count;
    report.self_intersecting = found.count > 0;
    out.intersections.count = found.count;
    for (const auto& [f, g] : found.pairs) {
      const auto& a = soup.triangles[f];
      const auto& b = soup.triangles[g];
      if (out.intersections.locations.size() < max_locations)
        out.intersections.locations.push_back({{f, g}, {a[0], a[1], a[2], b[0], b[1], b[2]}});
      if (out.intersections.examples.size() == max_examples) continue;
      Vec3 mid = Vec3::Zero();
      for (const std::uint32_t v : a) mid += soup.vertices[v];
      for (const std::uint32_t v : b) mid += soup.vertices[v];
      out.intersections.examples.push_back(mid / 6.0);  // between the two centroids
    }
  }
  timer.lap("self_intersection");
  return out;
}

ValidationReport validate_with(const TriangleSoup& soup, const Topology& topo, PositionFacts facts) {
  ValidationReport report = std::move(facts.report);
  report.components = topo.components;
  report.boundary_edges = topo.boundary_edges.count;
  report.non_manifold_edges = topo.non_manifold_edges.count;
  report.non_manifold_vertices = topo.non_manifold_vertices.count;
  report.inconsistent_edges = topo.inconsistent_edges.count;
  report.duplicate_faces = topo.duplicate_faces.count;
  report.consistently_oriented = topo.inconsistent_edges.count == 0;
  set_genus(report, topo);
  const DefectCount& non_finite = facts.non_finite;
  const DefectCount& degenerate_found = facts.degenerate;
  const DefectCount& intersections = facts.intersections;

  if (soup.triangles.empty()) report.defects.push_back({Defect::Empty, 1, {}, {}});
  add_defect(report, Defect::NonFiniteVertex, non_finite);
  add_defect(report, Defect::BoundaryEdge, topo.boundary_edges);
  add_defect(report, Defect::NonManifoldEdge, topo.non_manifold_edges);
  add_defect(report, Defect::NonManifoldVertex, topo.non_manifold_vertices);
  add_defect(report, Defect::InconsistentOrientation, topo.inconsistent_edges);
  const bool closed = !soup.triangles.empty() && report.boundary_edges == 0 && non_finite.count == 0;
  if (closed && !report.oriented_outward) report.defects.push_back({Defect::InsideOut, 1, {}, {}});
  add_defect(report, Defect::DegenerateFace, degenerate_found);
  add_defect(report, Defect::DuplicateFace, topo.duplicate_faces);
  add_defect(report, Defect::SelfIntersection, intersections);
  return report;
}

}  // namespace

namespace {

std::string point_text(const Vec3& p) { return fmt::format("({:g}, {:g}, {:g})", p.x(), p.y(), p.z()); }

/// "1 inverted components: component 2 of 2 (12 faces, volume -125, at
/// (20, 0, 0)) faces inward inside no other component", naming as many
/// components as the report kept examples.
std::string describe_shells(const ValidationReport& report, const DefectReport& d) {
  const auto& shells = report.component_shells;
  std::string line = fmt::format("{} {}:", d.count, to_string(d.kind));
  std::size_t named = 0;
  for (std::size_t c = 0; c < shells.size() && named < d.examples.size(); ++c) {
    const ComponentShell& s = shells[c];
    if (!s.depth) continue;
    const bool inverted = !s.inside && !s.outward;
    const bool nested = s.inside && s.outward == shells[*s.inside].outward;
    if (d.kind == Defect::InvertedComponent ? !inverted : !nested) continue;
    line += fmt::format("{} component {} of {} ({} faces, volume {:g}, at {}) faces {}",
                        named == 0 ? "" : ";", c + 1, shells.size(), s.faces, s.volume,
                        point_text(s.location), s.outward ? "outward" : "inward");
    line += s.inside ? fmt::format(" like component {}, the innermost containing it", *s.inside + 1)
                     : std::string(" inside no other component");
    ++named;
  }
  return line;
}

}  // namespace

std::vector<std::string> describe_defects(const ValidationReport& report) {
  std::vector<std::string> lines;
  for (const DefectReport& d : report.defects) {
    if (d.kind == Defect::InvertedComponent || d.kind == Defect::NestedSameOrientation) {
      lines.push_back(describe_shells(report, d));
      continue;
    }
    std::string line = d.kind == Defect::Empty || d.kind == Defect::InsideOut
                           ? std::string(to_string(d.kind))
                           : fmt::format("{} {}", d.count, to_string(d.kind));
    if (d.kind == Defect::InsideOut) line += fmt::format(" (volume {:g})", report.volume);
    if (!d.examples.empty()) {
      line += " (e.g. at";
      for (std::size_t i = 0; i < d.examples.size(); ++i) {
        const Vec3& p = d.examples[i];
        line += fmt::format("{} ({:g}, {:g}, {:g})", i == 0 ? "" : ",", p.x(), p.y(), p.z());
      }
      line += ")";
    }
    lines.push_back(std::move(line));
  }
  if (report.undetermined_components > 0) {
    lines.push_back(
        fmt::format("orientation of {} of {} components undetermined: every ray cast from them met "
                    "another component at an edge, a vertex or within a face's plane",
                    report.undetermined_components, report.component_shells.size()));
  }
  if (report.self_intersection_timed_out) {
    lines.push_back(
        fmt::format("self-intersection test unfinished: out of time after {} candidate face pairs",
                    report.self_intersection_pairs_tested));
  } else if (report.self_intersection == IntersectionCheck::NotRun && report.non_finite_vertices == 0) {
    lines.emplace_back("self-intersection test not run");
  }
  return lines;
}

void require_valid(const ValidationReport& report, const std::string& what) {
  if (report.valid()) return;
  std::string message = fmt::format("{}: the mesh is not valid for fabrication", what);
  for (const std::string& line : describe_defects(report)) message += "; " + line;
  throw ValidationFailed(message);
}

}  // namespace fabmesh
