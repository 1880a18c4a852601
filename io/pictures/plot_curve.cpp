#include "io/pictures/plot_curve.h"

namespace fabmesh {

std::vector<std::vector<Vec2>> control_polygons(const CompositeCurve& curve) {
  std::vector<std::vector<Vec2>> out;
  bool in_bspline_run = false;
  for (const Segment& seg : curve.segments()) {
    const auto& p = seg.control_points();
    switch (seg.kind()) {
      case SegmentKind::TBezier:
      case SegmentKind::HBezier:
      case SegmentKind::RationalBezier:
        out.push_back({p[0], p[1], p[2], p[3]});
        break;
      case SegmentKind::QuasiBSpline:
        // Span i uses p(i-1) .. p(i+2): a run contributes p(i), p(i+1) of its
        // first span, then p(i+1) of each further span.
        if (!in_bspline_run) out.push_back({p[1]});
        out.back().push_back(p[2]);
        break;
      case SegmentKind::Line:
      case SegmentKind::EllipseArc:
        break;
    }
    in_bspline_run = seg.kind() == SegmentKind::QuasiBSpline;
  }
  return out;
}

PlotCurve plot_curve(const BuiltCurve& built, const std::string& name) {
  PlotCurve out;
  out.name = name;
  out.curve = built.curve;
  out.control_polygons = control_polygons(built.curve);
  out.joints = built.joints;
  out.declared = built.declared;
  out.through = built.through;
  if (!built.fairing) return out;
  out.before_fairing = built.fairing->before;
  out.energy_before = built.fairing->energy_before;
  out.energy_after = built.fairing->energy_after;
  out.energy_name = built.fairing->energy_name;
  return out;
}

}  // namespace fabmesh
