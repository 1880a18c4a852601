#include "geometry/repair/overlaps.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <set>

#include "geometry/core/disjoint_sets.h"
#include "geometry/mesh/volume.h"
#include "geometry/repair/exact_booleans.h"
#include "geometry/repair/orientation.h"
#include "geometry/repair/surface_ops.h"

namespace fabmesh {
namespace {

using FacePairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

/// The faces of components in `chosen` as a soup of their own.
TriangleSoup extract(const TrackedSoup& mesh, const FaceComponents& comps,
                     const std::set<std::uint32_t>& chosen) {
  TriangleSoup part;
  std::map<std::uint32_t, std::uint32_t> index;
  for (std::size_t f = 0; f < mesh.soup.triangles.size(); ++f) {
    if (chosen.count(comps.of_face[f]) == 0) continue;
    std::array<std::uint32_t, 3> t{};
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh.soup.triangles[f][k];
      auto [it, fresh] = index.try_emplace(v, static_cast<std::uint32_t>(part.vertices.size()));
      if (fresh) part.vertices.push_back(mesh.soup.vertices[v]);
      t[k] = it->second;
    }
    part.triangles.push_back(t);
  }
  return part;
}

/// Replaces the faces of the components in `chosen` by `by` (faces made: no origin).
void replace(TrackedSoup& mesh, const FaceComponents& comps, const std::set<std::uint32_t>& chosen,
             const TriangleSoup& by, std::vector<std::uint32_t>* replaced_origins) {
  std::vector<bool> remove(mesh.soup.triangles.size(), false);
  for (std::size_t f = 0; f < remove.size(); ++f) {
    remove[f] = chosen.count(comps.of_face[f]) != 0;
    if (remove[f] && replaced_origins != nullptr && mesh.face_origin[f] != kNoIndex)
      replaced_origins->push_back(mesh.face_origin[f]);
  }
  remove_faces(mesh, remove);
  const auto base = static_cast<std::uint32_t>(mesh.soup.vertices.size());
  for (const Vec3& p : by.vertices) add_vertex(mesh, p);
  for (const auto& t : by.triangles) {
    mesh.soup.triangles.push_back({base + t[0], base + t[1], base + t[2]});
    mesh.face_origin.push_back(kNoIndex);
  }
  compact_vertices(mesh);
}

RepairPlace pair_place(const TrackedSoup& mesh, std::uint32_t f, const std::string& detail) {
  RepairPlace place = face_place(mesh, f);
  place.detail = detail;
  return place;
}

/// Autorefines the first component that intersects itself; returns whether one did and was mended.
bool resolve_own(TrackedSoup& mesh, const FacePairs& pairs, RepairLog& log, OverlapOutcome& outcome) {
  const FaceComponents comps = face_components(mesh.soup);
  std::uint32_t component = kNoIndex, witness = kNoIndex;
  std::size_t count = 0;
  for (const auto& [f, g] : pairs) {
    if (comps.of_face[f] != comps.of_face[g]) continue;
    if (component == kNoIndex) {
      component = comps.of_face[f];
      witness = f;
    }
    count += comps.of_face[f] == component ? 1 : 0;
  }
  if (component == kNoIndex) return false;
  std::string why;
  const auto result = resolve_self_intersections(extract(mesh, comps, {component}), &why);
  const RepairPlace place = pair_place(mesh, witness, fmt::format("{} intersecting face pairs", count));
  if (!result) {
    outcome.unresolved.push_back(
        fmt::format("a shell intersects itself ({}) at ({:.6g}, {:.6g}, {:.6g}), face {}: {}", place.detail,
                    place.point.x(), place.point.y(), place.point.z(), place.face, why));
    return false;
  }
  log.add(RepairStep::SelfIntersection, place);
  replace(mesh, comps, {component}, *result, &outcome.united_faces);
  return true;
}

/// Unites the clusters of components whose surfaces cross.
void unite_clusters(TrackedSoup& mesh, const FacePairs& pairs, RepairLog& log, OverlapOutcome& outcome) {
  const FaceComponents comps = face_components(mesh.soup);
  DisjointSets<std::uint32_t> sets(static_cast<std::uint32_t>(comps.count));
  std::map<std::uint32_t, std::uint32_t> witness;  // cluster member -> a crossing face
  for (const auto& [f, g] : pairs) {
    const std::uint32_t a = comps.of_face[f], b = comps.of_face[g];
    if (a == b) continue;
    sets.unite(a, b);
    witness.try_emplace(a, f);
    witness.try_emplace(b, g);
  }
  std::map<std::uint32_t, std::set<std::uint32_t>> clusters;
  for (const auto& [c, f] : witness) clusters[sets.find(c)].insert(c);
  std::set<std::uint32_t> all;
  TriangleSoup united_all;
  for (const auto& [root, members] : clusters) {
    std::vector<TriangleSoup> shells;
    for (const std::uint32_t c : members) {
      TriangleSoup shell = extract(mesh, comps, {c});
      if (signed_volume(shell) < 0.0) {
        for (auto& t : shell.triangles) std::swap(t[1], t[2]);
      }
      shells.push_back(std::move(shell));
    }
    std::string why;
    const auto united = unite_shells(shells, &why);
    const std::uint32_t at = witness.at(*members.begin());
    if (!united) {
      const RepairPlace p = face_place(mesh, at);
      outcome.unresolved.push_back(
          fmt::format("{} overlapping shells at ({:.6g}, {:.6g}, {:.6g}), face {}: {}", members.size(),
                      p.point.x(), p.point.y(), p.point.z(), p.face, why));
      continue;
    }
    log.add(RepairStep::Union, pair_place(mesh, at,
                                          fmt::format("{} shells united into {} faces", members.size(),
                                                      united->triangles.size())));
    const auto base = static_cast<std::uint32_t>(united_all.vertices.size());
    united_all.vertices.insert(united_all.vertices.end(), united->vertices.begin(), united->vertices.end());
    for (const auto& t : united->triangles)
      united_all.triangles.push_back({base + t[0], base + t[1], base + t[2]});
    all.insert(members.begin(), members.end());
  }
  if (!all.empty()) replace(mesh, comps, all, united_all, &outcome.united_faces);
}

}  // namespace

OverlapOutcome resolve_intersections(TrackedSoup& mesh, RepairLog& log) {
  OverlapOutcome outcome;
  FacePairs pairs = intersecting_faces(mesh.soup);
  // Own intersections first, one component per round.
  for (int round = 0; round < 256 && !pairs.empty(); ++round) {
    if (!resolve_own(mesh, pairs, log, outcome)) break;
    pairs = intersecting_faces(mesh.soup);
  }
  if (!outcome.unresolved.empty()) return outcome;
  if (!pairs.empty()) unite_clusters(mesh, pairs, log, outcome);
  return outcome;
}

}  // namespace fabmesh
