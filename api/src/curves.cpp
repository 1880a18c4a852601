#include "fabmesh/curves.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "api/src/detail.h"
#include "geometry/core/errors.h"
#include "geometry/curves/curve_spec.h"
#include "geometry/curves/quasi_bspline_through.h"
#include "geometry/fairing/build_curve.h"
#include "geometry/sampling/sample_curve.h"

namespace fabmesh::api {
namespace {

fabmesh::Continuity internal(Continuity c) { return static_cast<fabmesh::Continuity>(static_cast<int>(c)); }
Continuity public_continuity(fabmesh::Continuity c) { return static_cast<Continuity>(static_cast<int>(c)); }

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

// Built as the stages build a designer's curve: constructed, its declared
// continuity verified.
Curve constructed(const fabmesh::CurveSpec& spec) {
  return detail::translated([&] { return detail::curve_handle(fabmesh::build_curve(spec), spec); });
}

// One public segment as the design reader gives it, at key "segments[i]".
fabmesh::SegmentSpec segment_spec(const Segment& in, std::size_t i) {
  fabmesh::SegmentSpec s;
  s.key = fmt::format("segments[{}]", i);
  s.points = plane_points(in.points);
  s.lambda = in.lambda;
  s.mu = in.mu;
  s.alpha = in.alpha;
  s.declared = internal(in.continuity);
  switch (in.family) {
    case SegmentFamily::TBezier:
      s.kind = SegmentKind::TBezier;
      break;
    case SegmentFamily::HBezier:
      s.kind = SegmentKind::HBezier;
      break;
    case SegmentFamily::Line:
      s.kind = SegmentKind::Line;
      if (in.join) detail::bad_argument(s.key + ".join", "a line is straight; it cannot be joined");
      break;
  }
  if (in.family != SegmentFamily::Line) {
    // The shape parameters' ranges, named at the segment's own key.
    const std::array<Vec2, 4> probe{Vec2(0, 0), Vec2(1, 1), Vec2(2, 1), Vec2(3, 0)};
    try {
      if (in.family == SegmentFamily::TBezier) {
        fabmesh::Segment::tbezier(probe, in.lambda, in.mu);
      } else {
        fabmesh::Segment::hbezier(probe, in.alpha, in.lambda, in.mu);
      }
    } catch (const fabmesh::RangeError& e) {
      detail::bad_argument(s.key + "." + e.field(), e.what());
    }
  }
  if (in.join) {
    fabmesh::JoinSpec join;
    if (in.join->continuity == Continuity::None)
      detail::bad_argument(s.key + ".join.continuity", "a join is G0, G1 or G2");
    join.continuity = internal(in.join->continuity);
    join.alpha = in.join->alpha;
    join.beta = in.join->beta;
    join.k = in.join->k;
    join.m = in.join->m;
    s.join = join;
  }
  return s;
}

// The segment and its own parameter at global t (the last segment takes t = n).
std::pair<const fabmesh::Segment*, double> at(const fabmesh::CompositeCurve& curve, double t) {
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

std::vector<Joint> Curve::joints() const {
  std::vector<Joint> out;
  const std::vector<fabmesh::JointReport> measured = data_->curve.joints();
  for (std::size_t i = 0; i < measured.size(); ++i) {
    const fabmesh::JointReport& j = measured[i];
    Joint joint;
    joint.before = j.before;
    joint.after = j.after;
    joint.closing = j.closing;
    joint.gap = j.gap;
    joint.tangent_angle = j.tangent_angle;
    joint.curvature_before = j.curvature_before;
    joint.curvature_after = j.curvature_after;
    joint.curvature_jump = j.curvature_jump;
    joint.declared = i < data_->declared.size() ? public_continuity(data_->declared[i]) : Continuity::G0;
    joint.achieved = public_continuity(j.achieved);
    out.push_back(joint);
  }
  return out;
}

std::optional<Fairing> Curve::fairing() const { return data_->fairing; }

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

Curve composite(const std::vector<Segment>& segments, bool closed, Continuity closing) {
  if (segments.empty()) detail::bad_argument("segments", "a composite needs at least one segment");
  if (closing == Continuity::None) detail::bad_argument("closing", "the closing joint is G0, G1 or G2");
  fabmesh::CurveSpec spec;
  spec.key = "segments";
  spec.closed = closed;
  spec.closing_declared = internal(closing);
  // Fairing refuses an all-H-Bézier curve; a composite with a T-Bézier segment fairs those.
  spec.family = CurveFamily::HBezier;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    spec.segments.push_back(segment_spec(segments[i], i));
    if (segments[i].family == SegmentFamily::TBezier) spec.family = CurveFamily::TBezier;
  }
  return constructed(spec);
}

Curve quasi_bspline_through(const std::vector<Point2>& through, const std::vector<double>& lambdas) {
  if (through.size() < 3) {
    detail::bad_argument("through", fmt::format("a quasi-cubic B-spline needs at least 3 points q0..qn "
                                                "(n >= 2), got {}",
                                                through.size()));
  }
  for (std::size_t i = 0; i < through.size(); ++i) {
    if (!std::isfinite(through[i][0]) || !std::isfinite(through[i][1]))
      detail::bad_argument(
          "through", fmt::format("point q{} = ({}, {}) is not finite", i, through[i][0], through[i][1]));
  }
  if (!lambdas.empty() && lambdas.size() != through.size() - 2) {
    detail::bad_argument("lambdas",
                         fmt::format("expected n - 1 = {} values lambda_1..lambda_{} for {} points, "
                                     "got {}",
                                     through.size() - 2, through.size() - 2, through.size(), lambdas.size()));
  }
  fabmesh::CurveSpec spec;
  spec.family = CurveFamily::QuasiBSpline;
  spec.key = "through";
  spec.bspline_through = plane_points(through);
  spec.bspline_lambdas = lambdas;
  return detail::translated([&] {
    fabmesh::QuasiBSplineThrough solved;
    try {
      solved = fabmesh::quasi_bspline_through(spec.bspline_through, lambdas, "through");
    } catch (const fabmesh::RangeError& e) {
      detail::bad_argument("lambdas", e.what());
    }
    spec.bspline_points = std::move(solved.points);
    spec.bspline_through_deviation = solved.deviation;
    return detail::curve_handle(fabmesh::build_curve(spec), spec);
  });
}

std::optional<Through> Curve::through() const {
  const fabmesh::CurveSpec& spec = data_->spec;
  if (spec.bspline_through.empty()) return std::nullopt;
  Through out;
  for (const Vec2& q : spec.bspline_through) out.points.push_back(pair(q));
  for (const Vec2& p : spec.bspline_points) out.control_points.push_back(pair(p));
  out.deviation = spec.bspline_through_deviation;
  return out;
}

Curve fair(const Curve& curve, Energy energy, std::optional<Continuity> keeps) {
  const detail::CurveData& data = curve.data();
  fabmesh::CurveSpec spec = data.spec;
  if (spec.segments.empty() && spec.bspline_points.empty())
    detail::bad_argument("curve", "this curve was not built from control points; it cannot be faired");
  if (!spec.bspline_through.empty()) {
    detail::bad_argument("curve",
                         "a curve through points keeps them; fairing its lambdas with its control points "
                         "fixed would move it off them");
  }
  const bool bspline = spec.family == CurveFamily::QuasiBSpline;
  if (!bspline && spec.family == CurveFamily::HBezier) {
    detail::bad_argument("energy",
                         "fairing is defined for T-Bézier segments and quasi-cubic B-splines; this "
                         "curve has neither");
  }
  if (!bspline && energy == Energy::Strain) {
    detail::bad_argument("energy",
                         "T-Bézier segments are faired for the curvature variation; strain "
                         "fairing is for quasi-cubic B-splines");
  }
  if (keeps && *keeps == Continuity::None) detail::bad_argument("keeps", "keeps is G0, G1 or G2");
  spec.fair = energy == Energy::Strain ? FairMode::Strain : FairMode::CurvatureVariation;
  if (keeps) spec.fair_keeps = internal(*keeps);
  const std::string key = spec.key;
  spec.key = "keeps";  // the one way a constructed curve can fail here: a joint fairing lowered
  return detail::translated([&] {
    fabmesh::BuiltCurve built = fabmesh::build_curve(spec);
    spec.key = key;
    return detail::curve_handle(built, spec);
  });
}

namespace detail {

Curve curve_handle(const fabmesh::BuiltCurve& built, fabmesh::CurveSpec spec) {
  auto data = std::make_shared<CurveData>();
  data->curve = built.curve;
  data->declared = built.declared;
  if (built.fairing) {
    Fairing f;
    f.energy = spec.fair == FairMode::Strain ? Energy::Strain : Energy::CurvatureVariation;
    f.energy_before = built.fairing->energy_before;
    f.energy_after = built.fairing->energy_after;
    data->fairing = f;
  }
  // The curve as faired is the curve as given to a later fairing. Joins
  // computed their points from the shapes before fairing, so the faired
  // cubics become explicit segments (their points as built), each declaring
  // the continuity its joint kept; lines and arcs follow their predecessors' ends.
  if (built.bspline) spec.bspline_lambdas = built.bspline->lambdas;
  if (!built.segments.empty() && built.curve.size() == spec.segments.size()) {
    const std::vector<fabmesh::Segment>& segs = built.curve.segments();
    const std::vector<fabmesh::JointReport>& joints = built.joints;
    auto kept = [&](std::size_t joint) {
      if (joint >= joints.size() || joint >= built.declared.size()) return fabmesh::Continuity::G0;
      return std::min(built.declared[joint], joints[joint].achieved);
    };
    for (std::size_t i = 0; i < segs.size(); ++i) {
      fabmesh::SegmentSpec& s = spec.segments[i];
      if (s.kind != SegmentKind::TBezier && s.kind != SegmentKind::HBezier) continue;
      const auto& p = segs[i].control_points();
      s.points.assign(p.begin(), p.end());
      s.lambda = segs[i].lambda();
      s.mu = segs[i].mu();
      s.join.reset();
      if (i > 0) s.declared = kept(i - 1);
    }
    if (spec.closed) spec.closing_declared = kept(segs.size() - 1);
  }
  spec.fair = FairMode::None;
  spec.fair_keeps.reset();
  data->spec = std::move(spec);
  return Curve(std::move(data));
}

}  // namespace detail
}  // namespace fabmesh::api
