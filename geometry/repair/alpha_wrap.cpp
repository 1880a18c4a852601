#include "geometry/repair/alpha_wrap.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/alpha_wrap_3.h>

#include <array>
#include <cmath>

#include "geometry/core/errors.h"

namespace fabmesh {

TriangleSoup alpha_wrap(const TriangleSoup& input, const WrapOptions& options) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Point = Kernel::Point_3;
  if (!(options.alpha > 0.0) || !std::isfinite(options.alpha))
    throw RangeError("wrap alpha", options.alpha, "the wrap's alpha must be a positive number");
  if (!(options.offset > 0.0) || !std::isfinite(options.offset))
    throw RangeError("wrap offset", options.offset, "the wrap's offset must be a positive number");
  std::vector<Point> points;
  points.reserve(input.vertices.size());
  for (const Vec3& v : input.vertices) points.emplace_back(v.x(), v.y(), v.z());
  std::vector<std::array<std::size_t, 3>> faces;
  faces.reserve(input.triangles.size());
  for (const auto& t : input.triangles) {
    if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) faces.push_back({t[0], t[1], t[2]});
  }
  CGAL::Surface_mesh<Point> wrap;
  CGAL::alpha_wrap_3(points, faces, options.alpha, options.offset, wrap);
  TriangleSoup soup;
  for (const auto v : wrap.vertices()) {
    const Point& p = wrap.point(v);
    soup.vertices.emplace_back(p.x(), p.y(), p.z());
  }
  for (const auto f : wrap.faces()) {
    std::array<std::uint32_t, 3> t{};
    int k = 0;
    for (const auto v : CGAL::vertices_around_face(wrap.halfedge(f), wrap))
      t[k++] = static_cast<std::uint32_t>(v.idx());
    soup.triangles.push_back(t);
  }
  return soup;
}

}  // namespace fabmesh
