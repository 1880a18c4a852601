#pragma once
// The curves of a design, by name, for the commands that work on curves, and
// the design's shape (curves and patches) built without a mesh.

#include <optional>
#include <string>
#include <vector>

#include "geometry/sampling/sample_curve.h"
#include "io/design/design.h"
#include "pipeline/result.h"

namespace fabmesh {

struct NamedCurve {
  std::string name;  ///< "curve", "profile", "outline", "holes[0]", ...
  CurveSpec spec;
};

/// Every curve a design declares, in file order.
std::vector<NamedCurve> design_curves(const Design& design);

/// Throws GeometryError at `key` when `line` (a curve sampled with `params`)
/// is closed and crosses itself: "the closed curve crosses itself near (x, y)
/// (segments i and j)". `sample` and `run` judge a closed curve by this one rule.
void require_simple_closed(const Polyline2& line, const std::vector<CurveParam>& params,
                           const std::string& key);

/// A design's curves as built and a surface's patch network: what its plot draws.
struct BuiltShape {
  std::vector<NamedBuiltCurve> curves;  ///< in design_curves' order
  std::optional<PatchNetwork> patches;  ///< a surface's
  /// A vessel: the curves are profiles in the (radius, height) half-plane, revolved about x = 0.
  bool revolved = false;
  /// A vessel's section as its builder makes it: closed loops (the profile,
  /// the rim, a shell's inner wall and base, the axis) in the design's units,
  /// at the fired size (before shrinkage's scaling). Empty when not built.
  std::vector<std::vector<Vec2>> section;
  /// A vessel with `print`: the stretches overhanging beyond its limit, as
  /// the plot flags them; empty otherwise.
  std::vector<std::vector<Vec2>> overhangs;
  double overhang_limit_deg = 45.0;
};

/// The design's curves built (build_curve, in design_curves' order) and a
/// surface's patch network (build_patch_network), without building a mesh:
/// what `plot` draws. With `contradicted`, a curve whose joints contradict
/// their declared continuity (or what fairing must keep) is not an error: it
/// is taken as constructed (unfaired), its joints measured (so the plot flags
/// the failed ones), and the error's message is appended to `contradicted`.
/// \throw as build_curve / build_patch_network
BuiltShape build_shape(const Design& design, std::vector<std::string>* contradicted = nullptr);

}  // namespace fabmesh
