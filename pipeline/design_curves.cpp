#include "pipeline/design_curves.h"

#include <fmt/format.h>

#include <exception>
#include <type_traits>

#include "geometry/core/errors.h"
#include "geometry/section/print_checks.h"
#include "geometry/section/simple_polygon.h"
#include "geometry/section/vessel_section.h"
#include "geometry/surfaces/patch_network.h"
#include "pipeline/failure.h"
#include "pipeline/load_design.h"

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

namespace {

// The curve as constructed when only its declared continuity fails: drawn
// with the failed joints flagged, the message kept. Any other failure is thrown.
BuiltCurve curve_as_drawn(const Design& design, const CurveSpec& spec,
                          std::vector<std::string>* contradicted) {
  if (contradicted == nullptr) return build_curve(spec);
  try {
    return build_curve(spec);
  } catch (const GeometryError& e) {
    const std::exception_ptr failure = std::current_exception();
    BuiltCurve out;
    try {
      out.curve = construct_curve(spec);
    } catch (const InputError&) {
      std::rethrow_exception(failure);  // not a matter of continuity: the curve cannot be made at all
    }
    out.declared = declared_continuity(spec);
    out.joints = out.curve.joints();
    bool lost = false;
    for (std::size_t i = 0; i < out.joints.size() && i < out.declared.size(); ++i)
      lost = lost || static_cast<int>(out.joints[i].achieved) < static_cast<int>(out.declared[i]);
    if (!lost) throw;  // constructed fine, yet fairing failed for another reason
    GeometryError located = e;
    if (located.location().place.empty() && is_design_key(design, located.location().key))
      located.set_location(placed(design.common, located.location()));
    contradicted->push_back(describe_failure(std::make_exception_ptr(located)).message);
    return out;
  }
}

// A vessel's section as its builder makes it (the shell's inner wall, rim
// and base), at the design's tolerance; none when the profile does not make
// one (a profile across the axis, a wall too thick): the plot shows the
// profile still, and `run` says what is wrong.
std::optional<VesselSection> section_as_drawn(const VesselDesign& vessel, const CompositeCurve& profile,
                                              double tolerance) {
  VesselSectionOptions options;
  options.mode = vessel.mode;
  options.wall = vessel.wall;
  options.base = vessel.base;
  options.rim = vessel.rim;
  options.tolerance = 0.5 * tolerance;
  try {
    return build_vessel_section(profile, options);
  } catch (const InputError&) {
    return std::nullopt;
  }
}

}  // namespace

BuiltShape build_shape(const Design& design, std::vector<std::string>* contradicted) {
  BuiltShape shape;
  for (const NamedCurve& nc : design_curves(design))
    shape.curves.push_back({nc.name, curve_as_drawn(design, nc.spec, contradicted)});
  if (const auto* surface = std::get_if<SurfaceDesign>(&design.body))
    shape.patches = build_patch_network(surface->patches);
  if (const auto* vessel = std::get_if<VesselDesign>(&design.body)) {
    shape.revolved = true;
    const CompositeCurve& profile = shape.curves.front().curve.curve;
    if (auto section = section_as_drawn(*vessel, profile, design.common.tolerance)) {
      shape.section = section->loops;
      // A design that prints upright flags its overhangs (the angles do not depend on the scale).
      if (vessel->print) {
        shape.overhang_limit_deg = vessel->print->max_overhang_deg;
        for (OverhangRun& run : check_print(profile, *section, *vessel->print).runs)
          shape.overhangs.push_back(std::move(run.points));
      }
    }
  }
  return shape;
}

}  // namespace fabmesh
