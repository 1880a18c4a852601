#include "pipeline/design_curves.h"

#include <type_traits>

#include "geometry/surfaces/patch_network.h"

namespace fabmesh {

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
