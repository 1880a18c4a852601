#include "geometry/repair/solids.h"

#include <algorithm>

#include "geometry/repair/orientation.h"
#include "geometry/repair/tracked_soup.h"

namespace fabmesh {

std::vector<TriangleSoup> solids_of(const TriangleSoup& soup, const ValidationReport& report) {
  const auto& shells = report.component_shells;
  const FaceComponents comps = face_components(soup);
  const bool nested =
      !shells.empty() && shells.size() == comps.count &&
      std::all_of(shells.begin(), shells.end(), [](const ComponentShell& s) { return s.depth.has_value(); });
  if (!nested) return {soup};
  // The solid of each component: itself at even depth, else the one containing it.
  std::vector<std::uint32_t> solid_of(comps.count, kNoIndex);
  std::vector<std::uint32_t> number(comps.count, kNoIndex);
  std::size_t solids = 0;
  for (std::size_t c = 0; c < comps.count; ++c) {
    if (*shells[c].depth % 2 == 0) number[c] = static_cast<std::uint32_t>(solids++);
  }
  for (std::size_t c = 0; c < comps.count; ++c)
    solid_of[c] = *shells[c].depth % 2 == 0 ? number[c] : number[*shells[c].inside];
  std::vector<TriangleSoup> result(solids);
  std::vector<std::uint32_t> index(soup.vertices.size(), kNoIndex);
  for (std::size_t f = 0; f < soup.triangles.size(); ++f) {
    TriangleSoup& s = result[solid_of[comps.of_face[f]]];
    std::array<std::uint32_t, 3> t{};
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = soup.triangles[f][k];
      if (index[v] == kNoIndex) {
        index[v] = static_cast<std::uint32_t>(s.vertices.size());
        s.vertices.push_back(soup.vertices[v]);
      }
      t[k] = index[v];
    }
    s.triangles.push_back(t);
  }
  return result;
}

}  // namespace fabmesh
