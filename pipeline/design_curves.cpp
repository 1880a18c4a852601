#include "pipeline/design_curves.h"

#include <fmt/format.h>

#include <type_traits>

#include "geometry/core/errors.h"
#include "geometry/section/simple_polygon.h"
#include "geometry/surfaces/patch_network.h"

namespace fabmesh {

void require_simple_closed(const Polyline2& line, const std::vector<CurveParam>& params,
                           const std::string& key) {
  if (!line.closed) return;
  // Exact predicates on the sampled loop.
  if (const auto c = find_crossing(line.points, true)) {
    throw GeometryError(
        ErrorLocation{key, {}, {c->where.x(), c->where.y()}},
        fmt::format("the closed curve crosses itself near ({:.6g}, {:.6g}) (segments {} and {})",
                    c->where.x(), c->where.y(), params[c->first].segment + 1, params[c->second].segment + 1));
  }
}

std::vector<NamedCurve> design_curves(const Design& design) {
  return std::visit(
      [](const auto& body) -> std::vector<NamedCurve> {
        using T = std::decay_t<decltype(body)>;
        if constexpr (std::is_same_v<T, CurveDesign>) return {{"curve", body.curve}};
        if constexpr (std::is_same_v<T, VesselDesign>) return {{"profile", body.profile}};
        if constexpr (std::is_same_v<T, CountertopDesign>) {
          std::vector<NamedCurve> curves{{"outline", body.outline}};
          for (std::size_t i = 0; i < body.holes.size(); ++i) {
            curves.push_back({"holes[" + std::to_string(i) + "]", body.holes[i].curve});
          }
          return curves;
        }
        if constexpr (std::is_same_v<T, SurfaceDesign>) return {};  // patches, no curves
      },
      design.body);
}

BuiltShape build_shape(const Design& design) {
  BuiltShape shape;
  for (const NamedCurve& nc : design_curves(design)) shape.curves.push_back({nc.name, build_curve(nc.spec)});
  if (const auto* surface = std::get_if<SurfaceDesign>(&design.body))
    shape.patches = build_patch_network(surface->patches);
  return shape;
}

}  // namespace fabmesh
