#include "geometry/curves/curve_spec.h"

#include <fmt/format.h>

#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#include <cmath>

#include "geometry/core/error_checks.h"

namespace fabmesh {
namespace {

int control_count(SegmentKind kind) { return kind == SegmentKind::Line ? 2 : 4; }

// An error about segment i: at its key, named as the design names it; for a
// curve built without keys, the message says "segment i".
GeometryError segment_error(const SegmentSpec& s, std::size_t i, const std::string& message) {
  if (s.key.empty()) return GeometryError(ErrorLocation{}, fmt::format("segment {}: {}", i + 1, message));
  return GeometryError(ErrorLocation{s.key, s.name}, message);
}

// Number of leading control points a segment's join computes.
int computed_count(const CurveSpec& spec, std::size_t i) {
  const SegmentSpec& s = spec.segments[i];
  const bool has_predecessor = i > 0 || spec.closed;
  if (s.kind == SegmentKind::Line) return (i > 0 || (spec.closed && s.points.size() == 1)) ? 1 : 0;
  if (!s.join) return 0;
  if (!has_predecessor) {
    throw segment_error(s, i, "the first segment of an open curve cannot have a join");
  }
  return static_cast<int>(s.join->continuity) + 1;
}

// A segment of the right family and shape with probe points: only its basis weights are used.
Segment basis_segment(const SegmentSpec& s) {
  const std::array<Vec2, 4> probe{Vec2(0, 0), Vec2(1, 0), Vec2(2, 0), Vec2(3, 0)};
  switch (s.kind) {
    case SegmentKind::TBezier:
      return Segment::tbezier(probe, s.lambda, s.mu);
    case SegmentKind::HBezier:
      return Segment::hbezier(probe, s.alpha, s.lambda, s.mu);
    case SegmentKind::Line:
      return Segment::line(probe[0], probe[1]);
    case SegmentKind::EllipseArc:
      return Segment::ellipse_arc(s.ellipse);
    case SegmentKind::QuasiBSpline:
      return Segment::quasi_bspline_span(probe, s.lambda, s.mu);
    case SegmentKind::RationalBezier:
      return Segment::rational_bezier(probe, s.weights);
  }
  throw GeometryError("segment", "unknown segment kind");
}

// Native-parameter derivative weights of order k at s.
std::array<double, 4> native_weights(const Segment& seg, double s, int k) {
  const BasisJet w = seg.weights(s);
  std::array<double, 4> out = w[k];
  const double scale = std::pow(seg.native_scale(), k);
  for (double& x : out) x /= scale;
  return out;
}

// Derivative factors of a join: next_d1 = c1 prev_d1; next_d2 = c2 prev_d2 + c21 prev_d1.
struct JoinFactors {
  double c1, c2, c21;
};

JoinFactors join_factors(const SegmentSpec& next, std::size_t i) {
  const JoinSpec& j = *next.join;
  try {
    if (next.kind == SegmentKind::HBezier) {
      require_positive("join k", j.k);
      require_in_range("join m", j.m, -1e300, 1e300);
      return {j.k, j.k * j.k, j.m};
    }
    require_positive("join alpha", j.alpha);
    require_in_range("join beta", j.beta, -1e300, 1e300);
  } catch (const RangeError& e) {
    const GeometryError at = segment_error(next, i, e.what());  // at the segment
    throw RangeError(e.field(), e.value(), at.what(), at.location());
  }
  const double a = j.alpha;
  return {1.0 / a, 1.0 / (a * a), -j.beta / (a * a * a)};
}

CompositeCurve construct_quasi_bspline(const CurveSpec& spec) {
  const auto& p = spec.bspline_points;
  if (p.size() < 3) {
    throw GeometryError(
        spec.key, fmt::format("a quasi-cubic B-spline needs at least 3 points (n >= 2), got {}", p.size()));
  }
  if (spec.closed) throw GeometryError(spec.key, "a quasi-cubic B-spline curve is open");
  const std::size_t n = p.size() - 1;
  std::vector<double> lam(n + 1, 0.0);
  lam.front() = lam.back() = 4.0;
  if (!spec.bspline_lambdas.empty()) {
    if (spec.bspline_lambdas.size() != n - 1) {
      throw GeometryError(spec.key, fmt::format("lambdas has {} values; {} points need n - 1 = {}",
                                                spec.bspline_lambdas.size(), p.size(), n - 1));
    }
    for (std::size_t i = 1; i < n; ++i) {
      lam[i] = spec.bspline_lambdas[i - 1];
      try {
        require_in_range(fmt::format("lambda_{}", i), lam[i], -8.0, 1.0);
      } catch (const RangeError& e) {
        throw RangeError(e.field(), e.value(), e.what(), ErrorLocation{spec.key});
      }
    }
  }
  auto at = [&](long i) { return p[static_cast<std::size_t>(std::clamp<long>(i, 0, static_cast<long>(n)))]; };
  std::vector<Segment> spans;
  for (std::size_t i = 0; i < n; ++i) {
    const long li = static_cast<long>(i);
    spans.push_back(
        Segment::quasi_bspline_span({at(li - 1), at(li), at(li + 1), at(li + 2)}, lam[i], lam[i + 1]));
  }
  return CompositeCurve(std::move(spans), false);
}

}  // namespace

const char* to_string(CurveFamily f) {
  switch (f) {
    case CurveFamily::TBezier:
      return "tbezier";
    case CurveFamily::HBezier:
      return "hbezier";
    case CurveFamily::QuasiBSpline:
      return "quasi_bspline";
  }
  return "unknown";
}

const char* to_string(FairMode f) {
  switch (f) {
    case FairMode::None:
      return "none";
    case FairMode::Strain:
      return "strain";
    case FairMode::CurvatureVariation:
      return "curvature_variation";
  }
  return "unknown";
}

namespace {

// The linear system of a composite curve's control points: one unknown row
// (x and y solved together) per control point of every segment, in segment
// order; given points are identity rows, computed ones the join conditions.
struct JoinSystem {
  std::vector<int> offset;     ///< the first unknown of each segment (and the total at the end)
  std::vector<Segment> bases;  ///< each segment's kind, shape parameters and (for arcs) exact points
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixX2d rhs;
};

// Rows k < computed of segment i: its k-th derivative at its start equals
// the previous segment's at its end (scaled by the join's factors).
void add_join_rows(const CurveSpec& spec, std::size_t i, int computed, JoinSystem& sys) {
  const std::size_t n = spec.segments.size();
  const SegmentSpec& s = spec.segments[i];
  const std::size_t p = (i + n - 1) % n;
  const JoinFactors f = s.join ? join_factors(s, i) : JoinFactors{1.0, 1.0, 0.0};
  // Each derivative order k of the previous segment's end, as weights on its points (or constants).
  auto add_prev = [&](int row, int k, double factor) {
    if (spec.segments[p].kind == SegmentKind::EllipseArc) {
      const CurveJet jet = sys.bases[p].jet(1.0);
      sys.rhs.row(row) += factor * jet[k].transpose() / std::pow(sys.bases[p].native_scale(), k);
      return;
    }
    const auto w = native_weights(sys.bases[p], 1.0, k);
    for (int l = 0; l < control_count(spec.segments[p].kind); ++l) {
      if (w[l] != 0.0) sys.entries.emplace_back(row, sys.offset[p] + l, -factor * w[l]);
    }
  };
  for (int k = 0; k < computed; ++k) {
    const int row = sys.offset[i] + k;
    const auto wn = native_weights(sys.bases[i], 0.0, k);
    for (int l = 0; l < control_count(s.kind); ++l) {
      if (wn[l] != 0.0) sys.entries.emplace_back(row, sys.offset[i] + l, wn[l]);
    }
    if (k == 0) add_prev(row, 0, 1.0);
    if (k == 1) add_prev(row, 1, f.c1);
    if (k == 2) {
      add_prev(row, 2, f.c2);
      add_prev(row, 1, f.c21);
    }
  }
}

// The rows of segment i: its given points, then its join conditions.
void add_segment_rows(const CurveSpec& spec, std::size_t i, JoinSystem& sys) {
  const SegmentSpec& s = spec.segments[i];
  const int count = control_count(s.kind);
  if (s.kind == SegmentKind::EllipseArc) {
    if (s.join) throw segment_error(s, i, "an ellipse arc cannot be joined; it is exact");
    for (int j = 0; j < 4; ++j) {
      sys.entries.emplace_back(sys.offset[i] + j, sys.offset[i] + j, 1.0);
      sys.rhs.row(sys.offset[i] + j) = sys.bases[i].control_points()[j].transpose();
    }
    return;
  }
  const int computed = computed_count(spec, i);
  const int given = static_cast<int>(s.points.size());
  if (given != count - computed) {
    const std::string how =
        s.join ? fmt::format("after a {} join", to_string(s.join->continuity))
               : (computed > 0 ? "continuing the previous segment" : "as an explicit segment");
    throw segment_error(s, i,
                        fmt::format("a {} segment {} takes {} point(s), got {}", to_string(s.kind), how,
                                    count - computed, given));
  }
  for (int j = computed; j < count; ++j) {
    sys.entries.emplace_back(sys.offset[i] + j, sys.offset[i] + j, 1.0);
    sys.rhs.row(sys.offset[i] + j) = s.points[j - computed].transpose();
  }
  if (computed > 0) add_join_rows(spec, i, computed, sys);
}

JoinSystem join_system(const CurveSpec& spec) {
  const std::size_t n = spec.segments.size();
  JoinSystem sys;
  sys.offset.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    sys.bases.push_back(basis_segment(spec.segments[i]));
    sys.offset[i + 1] = sys.offset[i] + control_count(spec.segments[i].kind);
  }
  sys.rhs = Eigen::MatrixX2d::Zero(sys.offset[n], 2);
  for (std::size_t i = 0; i < n; ++i) add_segment_rows(spec, i, sys);
  return sys;
}

// The control points. Unknowns are ordered by segment, and a join reads only
// its own segment's earlier points and its predecessor's: the system is lower
// triangular (forward substitution, linear time) unless the first segment of
// a closed curve joins the last, which closes a cycle that needs a full solve.
Eigen::MatrixX2d solve_join_system(const CurveSpec& spec, const JoinSystem& sys) {
  const int unknowns = sys.offset.back();
  Eigen::SparseMatrix<double> a(unknowns, unknowns);
  a.setFromTriplets(sys.entries.begin(), sys.entries.end());
  const bool cyclic = spec.closed && computed_count(spec, 0) > 0;
  Eigen::MatrixX2d x;
  if (!cyclic) {
    x = a.triangularView<Eigen::Lower>().solve(sys.rhs);
  } else {
    Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
    lu.compute(a);
    if (lu.info() != Eigen::Success) {
      throw GeometryError(spec.key,
                          "the join conditions cannot be satisfied together (the closing join is singular "
                          "for these shape parameters)");
    }
    x = lu.solve(sys.rhs);
  }
  if (!x.allFinite()) throw GeometryError(spec.key, "the join conditions have no finite solution");
  return x;
}

}  // namespace

CompositeCurve construct_curve(const CurveSpec& spec) {
  if (spec.family == CurveFamily::QuasiBSpline) return construct_quasi_bspline(spec);
  const std::size_t n = spec.segments.size();
  if (n == 0) throw GeometryError(spec.key, "a curve needs at least one segment");
  const JoinSystem sys = join_system(spec);
  const Eigen::MatrixX2d x = solve_join_system(spec, sys);
  std::vector<Segment> segments;
  segments.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (spec.segments[i].kind == SegmentKind::EllipseArc) {
      segments.push_back(sys.bases[i]);
      continue;
    }
    std::array<Vec2, 4> pts{};
    for (int j = 0; j < control_count(spec.segments[i].kind); ++j)
      pts[j] = x.row(sys.offset[i] + j).transpose();
    try {
      segments.push_back(sys.bases[i].with_points(pts));
    } catch (const GeometryError& e) {
      throw segment_error(spec.segments[i], i, e.what());
    }
  }
  return CompositeCurve(std::move(segments), spec.closed);
}

std::vector<Continuity> declared_continuity(const CurveSpec& spec) {
  std::vector<Continuity> out;
  if (spec.family == CurveFamily::QuasiBSpline) {
    // C2 by construction at every interior joint.
    if (spec.bspline_points.size() >= 3) out.assign(spec.bspline_points.size() - 2, Continuity::G2);
    return out;
  }
  auto of = [](const SegmentSpec& s) { return s.join ? s.join->continuity : s.declared; };
  for (std::size_t i = 1; i < spec.segments.size(); ++i) out.push_back(of(spec.segments[i]));
  if (spec.closed && !spec.segments.empty()) {
    out.push_back(spec.segments.front().join ? spec.segments.front().join->continuity
                                             : spec.closing_declared);
  }
  return out;
}

void verify_declared_continuity(const CurveSpec& spec, const CompositeCurve& curve,
                                const JointTolerances& tol) {
  const auto declared = declared_continuity(spec);
  const auto joints = curve.joints(tol);
  for (std::size_t i = 0; i < joints.size() && i < declared.size(); ++i) {
    const JointReport& j = joints[i];
    if (static_cast<int>(j.achieved) >= static_cast<int>(declared[i])) continue;
    const std::string where =
        j.closing ? std::string("closing joint")
                  : fmt::format("joint {} (segments {} -> {})", i + 1, j.before + 1, j.after + 1);
    if (!std::isfinite(j.gap) || !std::isfinite(j.tangent_angle) || !std::isfinite(j.curvature_jump)) {
      // 0/0 from a zero tangent (coincident control points): say so, never "nan".
      throw GeometryError(spec.key, fmt::format("{}: declared {} but a segment has no tangent direction at "
                                                "the joint (coincident control points?), so it cannot be "
                                                "measured",
                                                where, to_string(declared[i])));
    }
    throw GeometryError(
        spec.key, fmt::format("{}: declared {} but measured gap {:.3g}, tangent angle {:.3g} rad, "
                              "relative curvature jump {:.3g} ({})",
                              where, to_string(declared[i]), j.gap, j.tangent_angle, j.curvature_jump,
                              j.closing && j.gap > 0 ? "the curve does not close" : to_string(j.achieved)));
  }
}

}  // namespace fabmesh
