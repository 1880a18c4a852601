#include "geometry/sampling/sample_curve.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geometry/core/errors.h"

namespace fabmesh {
namespace {

constexpr int kThirdDerivativeGrid = 64;

// Upper bound of |r'''| over [0, 1]: grid values plus half a grid step times
// the bound of |r''''|.
double third_derivative_bound(const Segment& seg) {
  double grid_max = 0.0;
  for (int i = 0; i <= kThirdDerivativeGrid; ++i) {
    grid_max = std::max(grid_max, seg.jet(static_cast<double>(i) / kThirdDerivativeGrid)[3].norm());
  }
  return grid_max + 0.5 / kThirdDerivativeGrid * seg.fourth_derivative_bound();
}

struct Piece {
  double s0, s1;
  double d2_0, d2_1;  // |r''| at the ends
};

}  // namespace

std::vector<double> sample_segment_parameters(const Segment& seg, const SampleOptions& options,
                                              double* achieved) {
  require_positive("tolerance", options.tolerance);
  std::vector<double> params{0.0};
  double worst = 0.0;
  if (seg.kind() == SegmentKind::Line) {
    params.push_back(1.0);
    if (achieved) *achieved = 0.0;
    return params;
  }
  const double m3 = third_derivative_bound(seg);
  auto d2 = [&](double s) { return seg.jet(s)[2].norm(); };
  auto bound = [&](const Piece& p) {
    const double h = p.s1 - p.s0;
    return h * h / 8.0 * (std::max(p.d2_0, p.d2_1) + 0.5 * h * m3);
  };

  // Depth-first bisection with an explicit stack keeps the parameters ordered.
  const int initial = std::max(1, options.min_pieces_per_segment);
  std::vector<Piece> stack;
  std::vector<double> d2_initial(static_cast<std::size_t>(initial) + 1);
  for (int i = 0; i <= initial; ++i) d2_initial[i] = d2(static_cast<double>(i) / initial);
  for (int i = initial - 1; i >= 0; --i) {
    stack.push_back({static_cast<double>(i) / initial, static_cast<double>(i + 1) / initial, d2_initial[i],
                     d2_initial[i + 1]});
  }
  while (!stack.empty()) {
    const Piece p = stack.back();
    stack.pop_back();
    const double b = bound(p);
    if (b <= options.tolerance) {
      params.push_back(p.s1);
      worst = std::max(worst, b);
      if (params.size() > options.max_points) {
        throw BudgetError(static_cast<double>(params.size()), static_cast<double>(options.max_points),
                          fmt::format("tolerance {} needs more than {} curve samples (the point budget)",
                                      options.tolerance, options.max_points));
      }
      continue;
    }
    const double mid = 0.5 * (p.s0 + p.s1);
    if (!(mid > p.s0 && mid < p.s1)) {
      throw BudgetError(0.0, 0.0,
                        fmt::format("tolerance {} cannot be reached in double precision", options.tolerance));
    }
    const double dm = d2(mid);
    stack.push_back({mid, p.s1, dm, p.d2_1});
    stack.push_back({p.s0, mid, p.d2_0, dm});
    if (stack.size() + params.size() > options.max_points) {
      throw BudgetError(static_cast<double>(stack.size() + params.size()),
                        static_cast<double>(options.max_points),
                        fmt::format("tolerance {} needs more than {} curve samples (the point budget)",
                                    options.tolerance, options.max_points));
    }
  }
  params.back() = 1.0;
  if (achieved) *achieved = worst;
  return params;
}

Polyline2 sample_curve(const CompositeCurve& curve, const SampleOptions& options,
                       std::vector<CurveParam>* params) {
  require_positive("tolerance", options.tolerance);
  if (params) params->clear();
  Polyline2 out;
  out.closed = curve.closed();
  double worst = 0.0, worst_gap = 0.0;
  const auto& segs = curve.segments();
  for (std::size_t i = 0; i < segs.size(); ++i) {
    double achieved = 0.0;
    const auto seg_params = sample_segment_parameters(segs[i], options, &achieved);
    worst = std::max(worst, achieved);
    // Each segment contributes its start and interior samples; the end is the next one's start.
    for (std::size_t k = 0; k + 1 < seg_params.size(); ++k) {
      out.points.push_back(segs[i].point(seg_params[k]));
      if (params) params->push_back({i, seg_params[k]});
    }
    const Vec2 end = segs[i].point(1.0);
    const bool last = i + 1 == segs.size();
    if (!last || curve.closed()) {
      const Vec2 next_start = last ? segs.front().point(0.0) : segs[i + 1].point(0.0);
      worst_gap = std::max(worst_gap, (end - next_start).norm());
    } else {
      out.points.push_back(end);
      if (params) params->push_back({i, 1.0});
    }
    if (out.points.size() > options.max_points) {
      throw BudgetError(static_cast<double>(out.points.size()), static_cast<double>(options.max_points),
                        fmt::format("tolerance {} needs more than {} curve samples (the point budget)",
                                    options.tolerance, options.max_points));
    }
  }
  out.max_deviation = worst + worst_gap;
  return out;
}

}  // namespace fabmesh
