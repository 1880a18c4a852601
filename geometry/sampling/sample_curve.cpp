#include "geometry/sampling/sample_curve.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geometry/core/budget.h"
#include "geometry/core/error_checks.h"

namespace fabmesh {
namespace {

constexpr int kThirdDerivativeGrid = 64;
constexpr int kCountGrid = 64;

struct Piece {
  double s0, s1;
  ChordBound::Ends a, b;
};

[[noreturn]] void over_budget(std::size_t count, const SampleOptions& options) {
  throw BudgetError(
      static_cast<double>(count), static_cast<double>(options.max_points),
      fmt::format("the curve needs more than {} samples (the point budget)", options.max_points));
}

}  // namespace

double third_derivative_bound(const Segment& seg) {
  double grid_max = 0.0;
  for (int i = 0; i <= kThirdDerivativeGrid; ++i) {
    grid_max = std::max(grid_max, seg.jet(static_cast<double>(i) / kThirdDerivativeGrid)[3].norm());
  }
  return grid_max + 0.5 / kThirdDerivativeGrid * seg.fourth_derivative_bound();
}

SegmentChordBound::SegmentChordBound(const Segment& segment)
    : segment_(&segment),
      m3_(segment.kind() == SegmentKind::Line ? 0.0 : fabmesh::third_derivative_bound(segment)) {}

ChordBound::Ends SegmentChordBound::at(double s) const {
  Ends e{};
  e[0] = segment_->kind() == SegmentKind::Line ? 0.0 : segment_->jet(s)[2].norm();
  return e;
}

double SegmentChordBound::bound(double s0, double s1, const Ends& a, const Ends& b) const {
  const double h = s1 - s0;
  return h * h / 8.0 * (std::max(a[0], b[0]) + 0.5 * h * m3_);
}

std::vector<double> sample_parameters(const ChordBound& bound, const SampleOptions& options,
                                      double* achieved) {
  require_positive("tolerance", options.tolerance);
  std::vector<double> params{0.0};
  double worst = 0.0;
  // Depth-first bisection with an explicit stack keeps the parameters ordered;
  // the stack holds at most one piece per level (plus the initial pieces).
  const int initial = std::max(1, options.min_pieces_per_segment);
  std::vector<ChordBound::Ends> ends(static_cast<std::size_t>(initial) + 1);
  for (int i = 0; i <= initial; ++i) ends[i] = bound.at(static_cast<double>(i) / initial);
  std::vector<Piece> stack;
  for (int i = initial - 1; i >= 0; --i) {
    stack.push_back(
        {static_cast<double>(i) / initial, static_cast<double>(i + 1) / initial, ends[i], ends[i + 1]});
  }
  while (!stack.empty()) {
    const Piece p = stack.back();
    stack.pop_back();
    const double b = bound.bound(p.s0, p.s1, p.a, p.b);
    if (b <= options.tolerance) {
      params.push_back(p.s1);
      worst = std::max(worst, b);
      if (params.size() > options.max_points) over_budget(params.size(), options);
      continue;
    }
    const double mid = 0.5 * (p.s0 + p.s1);
    if (!(mid > p.s0 && mid < p.s1)) {
      throw BudgetError(
          0.0, 0.0,
          fmt::format("the curve cannot be sampled within {:.3g} in double precision", options.tolerance));
    }
    const ChordBound::Ends m = bound.at(mid);
    stack.push_back({mid, p.s1, m, p.b});
    stack.push_back({p.s0, mid, p.a, m});
    if (stack.size() + params.size() > options.max_points) over_budget(stack.size() + params.size(), options);
  }
  params.back() = 1.0;
  if (achieved) *achieved = worst;
  return params;
}

std::vector<double> sample_segment_parameters(const Segment& seg, const SampleOptions& options,
                                              double* achieved) {
  require_positive("tolerance", options.tolerance);
  if (seg.kind() == SegmentKind::Line) {
    if (achieved) *achieved = 0.0;
    return {0.0, 1.0};
  }
  return sample_parameters(SegmentChordBound(seg), options, achieved);
}

double min_chord_count(const Segment& seg, double tolerance, int min_pieces) {
  require_positive("tolerance", tolerance);
  if (seg.kind() == SegmentKind::Line) return 1.0;
  // On each grid cell |r''| >= |r''(mid)| - (step/2) M3.
  const double m3 = third_derivative_bound(seg);
  const double step = 1.0 / kCountGrid;
  double integral = 0.0;
  for (int k = 0; k < kCountGrid; ++k) {
    const double low = seg.jet((k + 0.5) * step)[2].norm() - 0.5 * step * m3;
    if (low > 0.0) integral += step * std::sqrt(low / (8.0 * tolerance));
  }
  return std::max({1.0, static_cast<double>(min_pieces), std::ceil(integral)});
}

Polyline2 sample_curve(const CompositeCurve& curve, const SampleOptions& options,
                       std::vector<CurveParam>* params) {
  require_positive("tolerance", options.tolerance);
  if (params) params->clear();
  const auto& segs = curve.segments();
  // Refuse before refining when even the lower bound is over the budget.
  double estimate = 0.0;
  for (const Segment& seg : segs)
    estimate += min_chord_count(seg, options.tolerance, options.min_pieces_per_segment);
  require_within_budget(estimate, options.max_points, [&] {
    return fmt::format(
        "the curve needs at least {:.4g} samples (estimated from its second derivatives before "
        "sampling)",
        estimate);
  });
  Polyline2 out;
  out.closed = curve.closed();
  double worst = 0.0, worst_gap = 0.0;
  for (std::size_t i = 0; i < segs.size(); ++i) {
    double achieved = 0.0;
    SampleOptions left = options;
    left.max_points = options.max_points - std::min(options.max_points, out.points.size());
    const auto seg_params = sample_segment_parameters(segs[i], left, &achieved);
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
    if (out.points.size() > options.max_points) over_budget(out.points.size(), options);
  }
  out.max_deviation = worst + worst_gap;
  return out;
}

std::array<double, 2> edge_parameters(const std::vector<CurveParam>& params, std::size_t i) {
  const CurveParam& a = params[i];
  const std::size_t next = (i + 1) % params.size();
  const CurveParam& b = params[next];
  const bool same = next != 0 && b.segment == a.segment;
  return {a.s, same ? b.s : 1.0};
}

}  // namespace fabmesh
