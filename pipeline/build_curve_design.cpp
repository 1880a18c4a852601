// kind: curve: no mesh; its drawing at true size (DXF, SVG) for templates.

#include "geometry/fairing/build_curve.h"
#include "geometry/sampling/sample_curve.h"
#include "pipeline/build_design.h"
#include "pipeline/design_curves.h"

namespace fabmesh {

Result build(const CurveDesign& design, const BuildContext& context) {
  const BuiltCurve curve = build_curve(design.curve);
  context.watch.lap("curve");
  Result out;
  out.purpose = MeshPurpose::Drawing;  // no mesh to validate
  CutLoopOptions options;
  options.tolerance = context.tolerance;
  CurveProducts products;
  products.drawing.push_back(cut_loop(curve.curve, "curve", true, options));
  // Lines and exact arcs are drawn exactly; the rest as polylines sampled within the tolerance.
  SampleOptions so;
  so.tolerance = context.tolerance;
  std::vector<CurveParam> params;
  const Polyline2 line = sample_curve(curve.curve, so, &params);
  require_simple_closed(line, params, design.curve.key.empty() ? "curve" : design.curve.key);  // as `sample`
  out.max_deviation = line.max_deviation;
  out.facts.set("segments", curve.curve.size()).set("closed", curve.curve.closed());
  context.watch.lap("drawing");
  out.curves.push_back({"curve", curve});
  out.products = std::move(products);
  return out;
}

}  // namespace fabmesh
