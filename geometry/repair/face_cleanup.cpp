#include "geometry/repair/face_cleanup.h"

#include <algorithm>
#include <array>
#include <numeric>

#include "geometry/repair/surface_ops.h"

namespace fabmesh {

void remove_degenerate_faces(TrackedSoup& mesh, RepairLog& log) {
  const auto& p = mesh.soup.vertices;
  std::vector<bool> remove(mesh.soup.triangles.size(), false);
  for (std::uint32_t f = 0; f < mesh.soup.triangles.size(); ++f) {
    const auto& t = mesh.soup.triangles[f];
    const bool repeated = t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
    if (!repeated && !corners_collinear(p[t[0]], p[t[1]], p[t[2]])) continue;
    remove[f] = true;
    RepairPlace place = face_place(mesh, f);
    place.detail = repeated ? "a repeated corner" : "collinear corners";
    log.add(RepairStep::DegenerateFace, place);
  }
  remove_faces(mesh, remove);
}

std::vector<std::uint32_t> remove_duplicate_faces(TrackedSoup& mesh, RepairLog& log) {
  std::vector<std::uint32_t> cancelled;
  const auto& tris = mesh.soup.triangles;
  // Faces by their sorted corners; within a group, by orientation (the
  // cyclic order of the corners is even or odd against the sorted one).
  std::vector<std::uint32_t> order(tris.size());
  std::iota(order.begin(), order.end(), 0u);
  auto sorted = [&](std::uint32_t f) {
    std::array<std::uint32_t, 3> s = tris[f];
    std::sort(s.begin(), s.end());
    return s;
  };
  auto even = [&](std::uint32_t f) {
    const auto& t = tris[f];
    const std::size_t k = static_cast<std::size_t>(std::min_element(t.begin(), t.end()) - t.begin());
    return t[(k + 1) % 3] < t[(k + 2) % 3];
  };
  std::stable_sort(order.begin(), order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return sorted(a) < sorted(b); });
  std::vector<bool> remove(tris.size(), false);
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i;
    while (j < order.size() && sorted(order[j]) == sorted(order[i])) ++j;
    if (j - i > 1) {
      std::vector<std::uint32_t> up, down;
      for (std::size_t k = i; k < j; ++k) (even(order[k]) ? up : down).push_back(order[k]);
      std::sort(up.begin(), up.end());
      std::sort(down.begin(), down.end());
      // Copies facing one way: one kept. Both ways: they cancel in pairs (a
      // face counts +1 one way, -1 the other); one of the majority is kept.
      const bool cancel = !up.empty() && !down.empty();
      const std::vector<std::uint32_t>* keep = up.size() > down.size()   ? &up
                                               : down.size() > up.size() ? &down
                                                                         : nullptr;
      for (const auto* group : {&up, &down}) {
        for (std::size_t k = 0; k < group->size(); ++k) remove[(*group)[k]] = !(group == keep && k == 0);
      }
      for (std::size_t k = i; k < j; ++k) {
        if (!remove[order[k]]) continue;
        RepairPlace place = face_place(mesh, order[k]);
        place.detail = cancel ? "copies facing opposite ways cancel" : "a second copy";
        if (cancel && mesh.face_origin[order[k]] != kNoIndex) cancelled.push_back(mesh.face_origin[order[k]]);
        log.add(RepairStep::DuplicateFace, place);
      }
    }
    i = j;
  }
  remove_faces(mesh, remove);
  return cancelled;
}

}  // namespace fabmesh
