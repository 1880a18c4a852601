#include "io/pictures/curvature_profile.h"

#include <cmath>

#include "geometry/core/error_checks.h"
#include "geometry/fairing/gauss_legendre.h"

namespace fabmesh {

double drawn_curvature(const Segment& seg, double s) {
  const double k = seg.curvature(s);
  const auto& p = seg.control_points();
  Vec2 lo = p[0], hi = p[0];
  for (int i = 1; i < seg.control_count(); ++i) {
    lo = lo.cwiseMin(p[static_cast<std::size_t>(i)]);
    hi = hi.cwiseMax(p[static_cast<std::size_t>(i)]);
  }
  const double size = (hi - lo).norm();
  return std::abs(k) * size < 1e-9 ? 0.0 : k;
}

CurvatureProfile curvature_profile(const CompositeCurve& curve, int samples_per_segment) {
  require_in_range("curvature samples_per_segment", samples_per_segment, 1, 100000);
  const QuadratureRule rule = gauss_legendre(8);
  const int m = samples_per_segment;
  CurvatureProfile out;
  double length = 0.0;
  for (const Segment& seg : curve.segments()) {
    std::vector<CurvatureSample> samples;
    for (int j = 0; j <= m; ++j) {
      const double s = static_cast<double>(j) / m;
      if (j > 0) {
        const double s0 = static_cast<double>(j - 1) / m;
        for (std::size_t q = 0; q < rule.nodes.size(); ++q) {
          length += rule.weights[q] / m * seg.jet(s0 + rule.nodes[q] / m)[1].norm();
        }
      }
      const double k = drawn_curvature(seg, s);
      if (std::isfinite(k)) samples.push_back({s, length, k});
    }
    out.segments.push_back(std::move(samples));
    out.segment_ends.push_back(length);
  }
  out.length = length;
  return out;
}

}  // namespace fabmesh
