#include "geometry/repair/repair.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "geometry/core/errors.h"
#include "geometry/mesh/bounding_box.h"
#include "geometry/mesh/volume.h"
#include "geometry/repair/alpha_wrap.h"
#include "geometry/repair/edge_table.h"
#include "geometry/repair/face_cleanup.h"
#include "geometry/repair/manifold_split.h"
#include "geometry/repair/orientation.h"
#include "geometry/repair/overlaps.h"
#include "geometry/repair/stitch.h"
#include "geometry/repair/surface_ops.h"
#include "geometry/repair/tracked_soup.h"

namespace fabmesh {
namespace {

void require_option(const char* name, double value) {
  if (!std::isfinite(value) || value < 0.0)
    throw RangeError(name, value, fmt::format("{} = {:g} must be a number >= 0", name, value));
}

void check_input(const TriangleSoup& input, const RepairOptions& options) {
  require_indices_in_range(input);
  if (input.triangles.empty()) throw InputError("the mesh has no triangles: nothing to repair");
  for (std::size_t v = 0; v < input.vertices.size(); ++v) {
    const Vec3& p = input.vertices[v];
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()))
      throw InputError(fmt::format("vertex {} has a coordinate that is not a finite number", v));
  }
  if (options.weld_distance >= 0.0 || !std::isfinite(options.weld_distance))
    require_option("weld distance", options.weld_distance);
  require_option("separation", options.separation);
  require_option("max deviation", options.max_deviation);
}

double diagonal(const TriangleSoup& soup) { return bounding_box(soup.vertices).size().norm(); }

/// The state of a repair under way.
struct Work {
  TrackedSoup mesh;
  RepairLog log;
  std::vector<bool> unmeasured;                ///< per face read: not measured from the input side
  std::vector<bool> united;                    ///< per face read: part of a shell united or autorefined
  std::vector<std::uint32_t> input_component;  ///< per face read: its component in the input
  std::set<std::uint32_t> dropped_components;  ///< input components dropped with a reason already
  std::vector<std::string> unresolved;
  std::vector<DroppedComponent> dropped;
  /// Holes no patch closed: a vertex of each border and what to say, unless
  /// its component is then dropped as a sheet.
  std::vector<std::pair<std::uint32_t, std::string>> open_holes;
};

void mark_unmeasured(Work& w, const std::vector<std::uint32_t>& origins) {
  for (const std::uint32_t f : origins) {
    if (f != kNoIndex) w.unmeasured[f] = true;
  }
}

std::string at(const Vec3& p) { return fmt::format("({:.6g}, {:.6g}, {:.6g})", p.x(), p.y(), p.z()); }

void fill(Work& w, RepairResult& r) {
  HoleFilling filled;
  try {
    filled = fill_holes(w.mesh.soup);
  } catch (const InputError&) {
    const EdgeTable edges = edge_table(w.mesh.soup);
    Vec3 where = Vec3::Zero();
    for (std::size_t e = 0; e < edges.edges(); ++e) {
      if (edges.faces_of(e) == 1) {
        where =
            0.5 * (w.mesh.soup.vertices[edges.side(e, 0).from] + w.mesh.soup.vertices[edges.side(e, 0).to]);
        break;
      }
    }
    w.unresolved.push_back(fmt::format(
        "holes left open at {} and elsewhere: the surface is not manifold (an edge of three faces or more)",
        at(where)));
    return;
  }
  w.mesh.soup = std::move(filled.soup);
  w.mesh.face_origin.resize(w.mesh.soup.triangles.size(), kNoIndex);
  w.mesh.vertex_origin.resize(w.mesh.soup.vertices.size(), kNoIndex);
  for (const FilledHole& hole : filled.holes) {
    if (!hole.filled) {
      w.open_holes.emplace_back(
          hole.border_vertex,
          fmt::format("a hole of {} border edges at {} (vertex {}): every patch tried crosses the surface",
                      hole.border_edges, at(hole.centre), w.mesh.vertex_origin[hole.border_vertex]));
      continue;
    }
    w.log.add(RepairStep::HoleFill,
              RepairPlace{kNoIndex, w.mesh.vertex_origin[hole.border_vertex], hole.centre,
                          fmt::format("{} border edges, {} faces and {} vertices added{}", hole.border_edges,
                                      hole.faces_added, hole.vertices_added,
                                      hole.faired               ? ", faired"
                                      : hole.vertices_added > 0 ? ", refined"
                                                                : ", flat")});
  }
  (void)r;
}

/// Removes the components that enclose no volume (sheets, folds): they cannot be solids.
void drop_flat(Work& w) {
  const FaceComponents comps = face_components(w.mesh.soup);
  std::vector<double> volume6(comps.count, 0.0), area(comps.count, 0.0);
  const auto& p = w.mesh.soup.vertices;
  for (std::size_t f = 0; f < w.mesh.soup.triangles.size(); ++f) {
    const auto& t = w.mesh.soup.triangles[f];
    const std::uint32_t c = comps.of_face[f];
    volume6[c] += p[t[0]].dot(p[t[1]].cross(p[t[2]]));
    area[c] += 0.5 * (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).norm();
  }
  std::vector<bool> drop(comps.count, false);
  for (std::size_t c = 0; c < comps.count; ++c)
    drop[c] = std::abs(volume6[c] / 6.0) <= 1e-9 * std::pow(area[c], 1.5);
  std::vector<bool> remove(w.mesh.soup.triangles.size(), false);
  for (std::size_t c = 0; c < comps.count; ++c) {
    if (!drop[c]) continue;
    DroppedComponent d;
    d.area = area[c];
    d.lo = Vec3::Constant(std::numeric_limits<double>::infinity());
    d.hi = Vec3::Constant(-std::numeric_limits<double>::infinity());
    for (std::size_t f = 0; f < remove.size(); ++f) {
      if (comps.of_face[f] != c) continue;
      remove[f] = true;
      for (const std::uint32_t v : w.mesh.soup.triangles[f]) {
        d.lo = d.lo.cwiseMin(p[v]);
        d.hi = d.hi.cwiseMax(p[v]);
      }
      const std::uint32_t origin = w.mesh.face_origin[f];
      if (origin == kNoIndex) continue;
      ++d.faces;
      d.first_face = std::min(d.first_face, origin);
      w.unmeasured[origin] = true;
      w.dropped_components.insert(w.input_component[origin]);
    }
    d.why = fmt::format(
        "encloses no volume (|volume| {:.3g} for area {:.3g}): a flat sheet or a fold, not a solid",
        std::abs(volume6[c] / 6.0), area[c]);
    w.log.add(RepairStep::DropComponent, RepairPlace{d.first_face, kNoIndex, 0.5 * (d.lo + d.hi), d.why});
    w.dropped.push_back(d);
  }
  // A hole left open in a component dropped is gone with it.
  std::vector<bool> kept_vertex(w.mesh.soup.vertices.size(), false);
  for (std::size_t f = 0; f < remove.size(); ++f) {
    if (remove[f]) continue;
    for (const std::uint32_t v : w.mesh.soup.triangles[f]) kept_vertex[v] = true;
  }
  for (const auto& [vertex, line] : w.open_holes) {
    if (kept_vertex[vertex]) w.unresolved.push_back(line);
  }
  remove_faces(w.mesh, remove);
  compact_vertices(w.mesh);
}

bool has_border(const TriangleSoup& soup) {
  const EdgeTable edges = edge_table(soup);
  for (std::size_t e = 0; e < edges.edges(); ++e) {
    if (edges.faces_of(e) == 1) return true;
  }
  return false;
}

void local_repairs(Work& w, const RepairOptions& o, RepairResult& r) {
  const double size = diagonal(w.mesh.soup);
  r.weld = choose_weld_distance(w.mesh.soup, o.weld_distance);
  weld_borders(w.mesh, r.weld.distance, w.log);
  if (w.log.find(RepairStep::Weld) != nullptr)
    w.log.describe(RepairStep::Weld, fmt::format("distance {:.3g}: {}", r.weld.distance, r.weld.why));
  remove_degenerate_faces(w.mesh, w.log);
  mark_unmeasured(w, remove_duplicate_faces(w.mesh, w.log));
  stitch_t_junctions(w.mesh, std::max(r.weld.distance, 1e-9 * size), w.log);
  const double separation = o.separation > 0.0 ? o.separation : 1e-5 * size;
  split_non_manifold(w.mesh, separation, w.log);
  RepairPlace where;
  if (!orient_consistently(w.mesh, w.log, &where)) {
    w.unresolved.push_back(
        fmt::format("a surface that cannot be oriented (one-sided, like a Moebius strip) at {}, face {}",
                    at(where.point), where.face));
    return;
  }
  if (o.fill_holes && has_border(w.mesh.soup)) fill(w, r);
  drop_flat(w);
}

/// Turns each closed shell to face out of its solid: outward at even nesting depth, inward (a cavity) at odd.
void orient_outward(Work& w, const RepairOptions& o) {
  const ValidationReport report = validate(w.mesh.soup, o.validation);
  const auto& shells = report.component_shells;
  if (shells.empty() ||
      std::any_of(shells.begin(), shells.end(), [](const ComponentShell& s) { return !s.depth; }))
    return;
  const FaceComponents comps = face_components(w.mesh.soup);
  if (comps.count != shells.size()) return;
  std::vector<bool> flip(shells.size(), false);
  for (std::size_t c = 0; c < shells.size(); ++c) {
    const bool cavity = *shells[c].depth % 2 == 1;
    flip[c] = shells[c].outward == cavity;
    if (!flip[c]) continue;
    w.log.add(RepairStep::Outward,
              RepairPlace{kNoIndex, kNoIndex, shells[c].location,
                          fmt::format("{} faces at nesting depth {}: turned to face {}", shells[c].faces,
                                      *shells[c].depth, cavity ? "into its cavity" : "outward")});
  }
  flip_components(w.mesh, comps, flip);
}

void wrap(Work& w, const RepairOptions& o) {
  const double size = diagonal(w.mesh.soup);
  const double deviation = o.max_deviation > 0.0 ? o.max_deviation : 0.01 * size;
  const WrapOptions options{deviation / 2.0, deviation / 4.0};
  w.mesh.soup = alpha_wrap(w.mesh.soup, options);
  w.mesh.face_origin.assign(w.mesh.soup.triangles.size(), kNoIndex);
  w.mesh.vertex_origin.assign(w.mesh.soup.vertices.size(), kNoIndex);
  w.log.add(RepairStep::Wrap,
            RepairPlace{kNoIndex, kNoIndex, Vec3::Zero(),
                        fmt::format("alpha {:.3g}, offset {:.3g}", options.alpha, options.offset)});
  w.log.describe(RepairStep::Wrap,
                 fmt::format("alpha {:.3g}, offset {:.3g} (from a deviation of {:.3g}{})", options.alpha,
                             options.offset, deviation, o.max_deviation > 0.0 ? "" : ": 1% of the size"));
}

/// The faces of each side made from one face of the other by moving corners:
/// an output face from its origin, an input face from its only output face.
std::pair<std::vector<std::uint32_t>, std::vector<std::uint32_t>> partners(
    const std::vector<std::uint32_t>& origin, std::size_t input_faces) {
  std::vector<std::uint32_t> out(origin.size(), kNoPartner), in(input_faces, kNoPartner);
  std::vector<std::uint32_t> pieces(input_faces, 0);
  for (const std::uint32_t o : origin) {
    if (o != kNoIndex) ++pieces[o];
  }
  for (std::uint32_t f = 0; f < origin.size(); ++f) {
    if (origin[f] == kNoIndex) continue;
    out[f] = origin[f];
    if (pieces[origin[f]] == 1) in[origin[f]] = f;
  }
  return {out, in};
}

RepairMeasure measure(const TriangleSoup& input, const TriangleSoup& output,
                      const std::vector<std::uint32_t>& origin, const std::vector<bool>& unmeasured,
                      const DistanceOptions& options) {
  RepairMeasure m;
  std::vector<bool> measured(unmeasured.size());
  for (std::size_t f = 0; f < unmeasured.size(); ++f) {
    measured[f] = !unmeasured[f];
    m.unmeasured_faces += unmeasured[f] ? 1 : 0;
  }
  const auto [out_partners, in_partners] = partners(origin, input.triangles.size());
  m.input_to_output = one_sided_distance(input, measured, output, options, in_partners);
  m.output_to_input = one_sided_distance(output, {}, input, options, out_partners);
  m.distance = std::max(m.input_to_output.upper, m.output_to_input.upper);
  return m;
}

/// Input components with no face left that no step has named: say so.
void account_components(Work& w, const TriangleSoup& input, bool wrapped) {
  if (wrapped) return;
  std::set<std::uint32_t> alive;
  for (const std::uint32_t origin : w.mesh.face_origin) {
    if (origin != kNoIndex) alive.insert(w.input_component[origin]);
  }
  for (std::uint32_t f = 0; f < w.united.size(); ++f) {
    if (w.united[f]) alive.insert(w.input_component[f]);
  }
  std::map<std::uint32_t, std::vector<std::uint32_t>> lost;
  for (std::uint32_t f = 0; f < w.input_component.size(); ++f) {
    const std::uint32_t c = w.input_component[f];
    if (alive.count(c) == 0 && w.dropped_components.count(c) == 0) lost[c].push_back(f);
  }
  for (const auto& [c, faces] : lost) {
    DroppedComponent d;
    d.faces = faces.size();
    d.first_face = faces.front();
    d.lo = Vec3::Constant(std::numeric_limits<double>::infinity());
    d.hi = Vec3::Constant(-std::numeric_limits<double>::infinity());
    for (const std::uint32_t f : faces) {
      const auto& t = input.triangles[f];
      const auto& p = input.vertices;
      d.area += 0.5 * (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).norm();
      for (const std::uint32_t v : t) {
        d.lo = d.lo.cwiseMin(p[v]);
        d.hi = d.hi.cwiseMax(p[v]);
      }
    }
    d.why = "every face of it was removed: degenerate (no area), or copies facing opposite ways that cancel";
    w.dropped.push_back(d);
  }
}

}  // namespace

RepairResult repair(const TriangleSoup& input, const RepairOptions& options) {
  check_input(input, options);
  RepairResult result;
  Work w{track(input), RepairLog(options.max_places), {}, {}, {}, {}, {}, {}, {}};
  result.exact_welded = weld_exact(w.mesh);
  const TriangleSoup welded_input = w.mesh.soup;
  result.before = validate(welded_input, options.validation);
  result.components_before = result.before.components;
  if (result.before.valid() && !options.wrap) {
    compact_vertices(w.mesh);
    result.soup = std::move(w.mesh.soup);
    result.after = result.before;
    return result;
  }
  result.changed = true;
  w.unmeasured.assign(input.triangles.size(), false);
  w.united.assign(input.triangles.size(), false);
  w.input_component = face_components(welded_input).of_face;
  if (options.wrap) {
    wrap(w, options);
  } else {
    local_repairs(w, options, result);
    if (w.unresolved.empty()) {
      const OverlapOutcome overlaps = resolve_intersections(w.mesh, w.log);
      w.unresolved.insert(w.unresolved.end(), overlaps.unresolved.begin(), overlaps.unresolved.end());
      mark_unmeasured(w, overlaps.united_faces);
      for (const std::uint32_t f : overlaps.united_faces) w.united[f] = true;
    }
    if (w.unresolved.empty()) orient_outward(w, options);
  }
  compact_vertices(w.mesh);
  account_components(w, welded_input, options.wrap);
  result.soup = w.mesh.soup;
  result.after = validate(result.soup, options.validation);
  result.actions = w.log.actions();
  result.dropped = w.dropped;
  result.unresolved = w.unresolved;
  if (!result.soup.triangles.empty())
    result.measure = measure(welded_input, result.soup, w.mesh.face_origin, w.unmeasured, options.distance);
  if (!result.after.valid() && result.unresolved.empty()) {
    for (const std::string& line : describe_defects(result.after))
      result.unresolved.push_back("left: " + line);
  }
  if (options.max_deviation > 0.0 && result.measure.distance > options.max_deviation) {
    result.unresolved.push_back(
        fmt::format("the surface moved by up to {:.4g} (a proven bound; a point {:.4g} away at {}), more "
                    "than the maximum "
                    "deviation {:.4g}",
                    result.measure.distance,
                    std::max(result.measure.input_to_output.lower, result.measure.output_to_input.lower),
                    at(result.measure.input_to_output.lower >= result.measure.output_to_input.lower
                           ? result.measure.input_to_output.at
                           : result.measure.output_to_input.at),
                    options.max_deviation));
  }
  return result;
}

}  // namespace fabmesh
