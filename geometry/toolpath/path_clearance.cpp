#include "geometry/toolpath/path_clearance.h"

#include <algorithm>

#include "geometry/sampling/sample_curve.h"

namespace fabmesh {

SampledBoundary sample_boundary(const std::vector<CutCurve>& loops, double tolerance,
                                std::size_t max_points) {
  SampledBoundary out;
  SampleOptions so;
  so.tolerance = tolerance;
  so.max_points = max_points;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    std::vector<CurveParam> params;
    const Polyline2 line = sample_curve(*loops[l].curve, so, &params);
    so.max_points -= std::min(so.max_points - 1, line.points.size());
    out.deviation = std::max(out.deviation, line.max_deviation);
    const std::size_t n = line.points.size();
    for (std::size_t i = 0; i < n; ++i) {
      out.edges.push_back({line.points[i], line.points[(i + 1) % n], l, params[i].segment});
    }
  }
  return out;
}

Clearance path_clearance(const std::vector<PathPiece>& path, const BoundaryIndex& boundary, double radius,
                         double sagitta) {
  Clearance best;
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (path[i].role == PieceRole::Dogbone) continue;
    const std::vector<Vec2> pts = piece_polyline(path[i], sagitta);
    for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
      const BoundaryIndex::Nearest n = boundary.nearest(pts[k], pts[k + 1], radius);
      if (n.distance < best.distance) best = {n.distance, i, n.edge, n.on_query};
    }
  }
  return best;
}

}  // namespace fabmesh
