#include "fabmesh/curves.h"

#include <fmt/format.h>

#include <cmath>

#include "api/src/detail.h"
#include "geometry/curves/curve_spec.h"
#include "geometry/sampling/sample_curve.h"

namespace fabmesh::api {
namespace {

Curve handle(fabmesh::CompositeCurve curve) {
  return Curve(std::make_shared<const detail::CurveData>(detail::CurveData{std::move(curve)}));
}

std::vector<Vec2> plane_points(const std::vector<Point2>& points) {
  std::vector<Vec2> out;
  out.reserve(points.size());
  for (const Point2& p : points) out.emplace_back(p[0], p[1]);
  return out;
}

// Segments of one family through 3n + 1 points, each explicit (four control
// points, the last shared with the next segment).
fabmesh::CurveSpec chain(SegmentKind kind, CurveFamily family, const std::vector<Point2>& points) {
  if (points.size() < 4 || (points.size() - 1) % 3 != 0) {
    detail::bad_argument("points",
                         fmt::format("{} control points; a chain of cubic segments takes 3n + 1 (4, 7, "
                                     "10, ...)",
                                     points.size()));
  }
  const std::vector<Vec2> p = plane_points(points);
  fabmesh::CurveSpec spec;
  spec.family = family;
  spec.key = "points";
  for (std::size_t i = 0; i + 3 < p.size(); i += 3) {
    fabmesh::SegmentSpec s;
    s.kind = kind;
    s.points = {p[i], p[i + 1], p[i + 2], p[i + 3]};
    s.key = fmt::format("points[{}:{}]", i, i + 4);
    spec.segments.push_back(std::move(s));
  }
  return spec;
}

Curve constructed(const fabmesh::CurveSpec& spec) {
  return detail::translated([&] { return handle(fabmesh::construct_curve(spec)); });
}

// The segment and its own parameter at global t (the last segment takes t = n).
std::pair<const Segment*, double> at(const fabmesh::CompositeCurve& curve, double t) {
  const double n = static_cast<double>(curve.size());
  if (!std::isfinite(t) || t < 0.0 || t > n)
    detail::bad_argument("t", fmt::format("t = {} is not in [0, {}]", t, n));
  const std::size_t i = std::min(static_cast<std::size_t>(t), curve.size() - 1);
  return {&curve.segments()[i], t - static_cast<double>(i)};
}

Point2 pair(const Vec2& v) { return {v.x(), v.y()}; }

}  // namespace

std::size_t Curve::segments() const { return data_->curve.size(); }
bool Curve::closed() const { return data_->curve.closed(); }

Point2 Curve::point(double t) const {
  const auto [segment, s] = at(data_->curve, t);
  return pair(segment->point(s));
}

Point2 Curve::derivative(double t, int order) const {
  if (order < 1 || order > 3) detail::bad_argument("order", fmt::format("order {} is not 1, 2 or 3", order));
  const auto [segment, s] = at(data_->curve, t);
  return pair(segment->jet(s)[static_cast<std::size_t>(order)]);
}

double Curve::curvature(double t) const {
  const auto [segment, s] = at(data_->curve, t);
  return segment->curvature(s);
}

SampledCurve Curve::sample(double tolerance) const {
  if (!(tolerance > 0.0) || !std::isfinite(tolerance))
    detail::bad_argument("tolerance", fmt::format("tolerance = {} must be > 0", tolerance));
  return detail::translated([&] {
    fabmesh::SampleOptions options;
    options.tolerance = tolerance;
    const Polyline2 line = fabmesh::sample_curve(data_->curve, options);
    SampledCurve out;
    out.points.reserve(line.points.size());
    for (const Vec2& p : line.points) out.points.push_back(pair(p));
    out.closed = line.closed;
    out.max_deviation = line.max_deviation;
    return out;
  });
}

Curve tbezier(const std::vector<Point2>& points, double lambda, double mu) {
  fabmesh::CurveSpec spec = chain(SegmentKind::TBezier, CurveFamily::TBezier, points);
  for (fabmesh::SegmentSpec& s : spec.segments) {
    s.lambda = lambda;
    s.mu = mu;
  }
  return constructed(spec);
}

Curve hbezier(const std::vector<Point2>& points, double alpha, double lambda, double mu) {
  fabmesh::CurveSpec spec = chain(SegmentKind::HBezier, CurveFamily::HBezier, points);
  for (fabmesh::SegmentSpec& s : spec.segments) {
    s.alpha = alpha;
    s.lambda = lambda;
    s.mu = mu;
  }
  return constructed(spec);
}

Curve quasi_bspline(const std::vector<Point2>& points, const std::vector<double>& lambdas) {
  fabmesh::CurveSpec spec;
  spec.family = CurveFamily::QuasiBSpline;
  spec.key = "points";
  spec.bspline_points = plane_points(points);
  spec.bspline_lambdas = lambdas;
  return constructed(spec);
}

}  // namespace fabmesh::api
